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
  let _92 = (uv * 2.0) - vec2<f32>(1.0);
  gl_Position = vec4<f32>(_92.x, _92.y, 0.0, 1.0);
  return VertexOutput(vTexCoord, gl_Position * vec4<f32>(1.0, -1.0, 1.0, 1.0));
}

@fragment
fn fs_main(@location(0) vTexCoord: vec2<f32>) -> @location(0) vec4<f32> {
  var fragColor: vec4<f32>;
  let _77_rem = p.i.x % p.i.y;
  let _77_1 = select(_77_rem, _77_rem + p.i.y, (_77_rem != i32()) & ((_77_rem < i32()) != (p.i.y < i32())));
  let _81_rem = p.i.z % (-3i);
  let _81_1 = select(_81_rem, _81_rem + (-3i), (_81_rem != i32()) & ((_81_rem < i32()) != ((-3i) < i32())));
  let _111 = -vTexCoord.x;
  let m = vec4<f32>(p.a.x - p.a.y * floor(p.a.x / p.a.y), p.a.z - p.a.w * floor(p.a.z / p.a.w), _111 - 0.25 * floor(_111 / 0.25), p.a.x - (-2.0) * floor(p.a.x / (-2.0)));
  let _128 = vec4<f32>(vec4<i32>(p.i.x / p.i.y, p.i.z / p.i.w, _77_1, _81_1)) + m;
  fragColor = _128;
  return fragColor;
}
