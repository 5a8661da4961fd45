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
  var n: f32;
  var bits: u32;
  var shifted: i32;
  var _51: f32;
  var _68: f32;
  n = p.a.x;
  bits = bitcast<u32>(bitcast<u32>(vTexCoord.x)) >> 16u;
  shifted = bitcast<i32>(p.i.y) >> 2u;
  let _42 = n;
  let _47 = select(0.0, 1.0, (bitcast<u32>(_42) & 0x7fffffffu) > 0x7f800000u);
  let _48 = n;
  let _49 = n;
  if (_48 != _49) {
    let _54 = shifted;
    _51 = f32(_54);
  } else {
    _51 = 0.0;
  }
  let _57 = _51;
  let _58 = bits;
  let _63 = f32(_58 & 255u) / 255.0;
  if ((bitcast<u32>(p.a.z) & 0x7fffffffu) == 0x7f800000u) {
    _68 = f32(bitcast<u32>(bitcast<u32>(p.i.y)) >> 28u);
  } else {
    _68 = 0.0;
  }
  let _78 = _68;
  fragColor = vec4<f32>(_47, _57, _63, _78);
  return fragColor;
}
