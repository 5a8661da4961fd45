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
@group(0) @binding(1) var source: texture_2d<f32>;
@group(0) @binding(2) var source_sampler: sampler;

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
  var q: vec4<i32>;
  var m: vec4<f32>;
  let _36_rem = p.i.x % p.i.y;
  let _36_1 = select(_36_rem, _36_rem + p.i.y, (_36_rem != i32()) & ((_36_rem < i32()) != (p.i.y < i32())));
  let _40_rem = p.i.z % (-3i);
  let _40_1 = select(_40_rem, _40_rem + (-3i), (_40_rem != i32()) & ((_40_rem < i32()) != ((-3i) < i32())));
  q = vec4<i32>(p.i.x / p.i.y, p.i.z / p.i.w, _36_1, _40_1);
  let _62 = -vTexCoord.x;
  let _69 = vec4<f32>(p.a.x - p.a.y * floor(p.a.x / p.a.y), p.a.z - p.a.w * floor(p.a.z / p.a.w), _62 - 0.25 * floor(_62 / 0.25), p.a.x - (-2.0) * floor(p.a.x / (-2.0)));
  m = _69;
  let _72 = q;
  let _74 = m;
  fragColor = vec4<f32>(_72) + _74;
  return fragColor;
}
