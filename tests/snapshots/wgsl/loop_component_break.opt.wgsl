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
  let _22 = vec2<f32>(f32((i32(vertex_index) << 1u) & 2i), f32(i32(vertex_index) & 2i));
  vTexCoord = _22;
  let _39 = (_22 * 2.0) - vec2<f32>(1.0);
  gl_Position = vec4<f32>(_39.x, _39.y, 0.0, 1.0);
  return VertexOutput(vTexCoord, gl_Position * vec4<f32>(1.0, -1.0, 1.0, 1.0));
}

@fragment
fn fs_main() -> @location(0) vec4<f32> {
  var fragColor: vec4<f32>;
  var _63: vec4<f32>;
  var _62: i32;
  var _61: vec4<f32>;
  var _40: i32;
  _63 = vec4<f32>(0.0);
  _62 = 0i;
  loop {
    _61 = _63;
    _61.y = f32(_62) * p.a.x;
    _40 = _62 + 1i;
    if (_40 > p.i.x) {
      break;
    }
    continuing {
      _63 = _61;
      _62 = _40;
    }
  }
  fragColor = _61;
  return fragColor;
}
