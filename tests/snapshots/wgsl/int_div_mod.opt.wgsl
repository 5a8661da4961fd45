struct VertexOutput {
  @location(0) vTexCoord: vec2<f32>,
  @builtin(position) gl_Position: vec4<f32>,
}

struct Params {
  a: vec4<f32>,  // offset 0
  b: vec4<f32>,  // offset 16
  i: vec4<i32>,  // offset 32
}

@group(0) @binding(0) var<uniform> p: Params;

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> VertexOutput {
  var vTexCoord: vec2<f32>;
  var gl_Position: vec4<f32>;
  let uv = vec2<f32>(f32((i32(vertex_index) << 1u) & 2i), f32(i32(vertex_index) & 2i));
  vTexCoord = uv;
  let difference = (uv * 2.0) - vec2<f32>(1.0);
  gl_Position = vec4<f32>(difference.x, difference.y, 0.0, 1.0);
  return VertexOutput(vTexCoord, gl_Position * vec4<f32>(1.0, -1.0, 1.0, 1.0));
}

@fragment
fn fs_main(@location(0) vTexCoord: vec2<f32>) -> @location(0) vec4<f32> {
  var fragColor: vec4<f32>;
  let remainder_rem = p.i.x % p.i.y;
  let remainder_1 = select(remainder_rem, remainder_rem + p.i.y, (remainder_rem != i32()) & ((remainder_rem < i32()) != (p.i.y < i32())));
  let remainder_2_rem = p.i.z % (-3i);
  let remainder_3 = select(remainder_2_rem, remainder_2_rem + (-3i), (remainder_2_rem != i32()) & ((remainder_2_rem < i32()) != ((-3i) < i32())));
  let q = vec4<i32>(p.i.x / p.i.y, p.i.z / p.i.w, remainder_1, remainder_3);
  let negated = -vTexCoord.x;
  let m = vec4<f32>(p.a.x - p.a.y * floor(p.a.x / p.a.y), p.a.z - p.a.w * floor(p.a.z / p.a.w), negated - 0.25 * floor(negated / 0.25), p.a.x - (-2.0) * floor(p.a.x / (-2.0)));
  fragColor = vec4<f32>(q) + m;
  return fragColor;
}
