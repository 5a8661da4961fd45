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
  let _22 = vec2<f32>(f32((i32(vertex_index) << 1u) & 2i), f32(i32(vertex_index) & 2i));
  vTexCoord = _22;
  let _39 = (_22 * 2.0) - vec2<f32>(1.0);
  gl_Position = vec4<f32>(_39.x, _39.y, 0.0, 1.0);
  return VertexOutput(vTexCoord, gl_Position * vec4<f32>(1.0, -1.0, 1.0, 1.0));
}

@fragment
fn fs_main(@location(0) vTexCoord: vec2<f32>) -> @location(0) vec4<f32> {
  var fragColor: vec4<f32>;
  var _73: vec4<f32>;
  var _72: i32;
  let _19 = textureSample(source, source_sampler, vTexCoord);
  _73 = _19;
  _72 = 0i;
  loop {
    if (!(_72 < p.i.x)) {
      break;
    }
    continuing {
      var _68 = _73;
      _68.y = fma(_73.y, p.a.x, f32(_72));
      var _71 = _68;
      _71.w = _73.w + 0.5;
      let _62 = _72 + 1i;
      _73 = _71;
      _72 = _62;
    }
  }
  fragColor = _73;
  return fragColor;
}
