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
  var t: vec4<f32>;
  var d: vec2<f32>;
  var s: vec4<f32>;
  var m: mat2x2<f32>;
  t = textureSample(source, source_sampler, vTexCoord);
  d = vec2<f32>(dpdx(vTexCoord.x), dpdy(vTexCoord.y)) * 16.0;
  let _36 = t;
  s = _36.wzyx;
  let _40 = d.x;
  s.y = _40;
  s.z = fwidth(vTexCoord.y);
  let _50 = s;
  let _51 = _50.xy;
  let _52 = t;
  let _53 = _52.zw;
  m = mat2x2<f32>(vec2<f32>(_51.x, _51.y), vec2<f32>(_53.x, _53.y));
  let _65 = s;
  let _66 = _65.xy;
  let _70 = m[1i].x;
  let _72 = t.x;
  let _74 = d.y;
  fragColor = vec4<f32>(_66.x, _66.y, _70, _72 + _74);
  return fragColor;
}
