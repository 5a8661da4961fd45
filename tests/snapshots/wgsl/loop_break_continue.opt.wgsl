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
fn fs_main(@location(0) vTexCoord: vec2<f32>) -> @location(0) vec4<f32> {
  var fragColor: vec4<f32>;
  var _99: i32;
  var _93: f32;
  var _92: i32;
  var _102: i32;
  var _101: f32;
  var _94: i32;
  var _74: i32;
  _99 = (-1i);
  _93 = 0.0;
  _92 = 0i;
  loop {
    if (!(_92 < p.i.x)) {
      break;
    }
    if (_92 == p.i.y) {
      _102 = _99;
      _101 = _93;
      continue;
    }
    if (_93 > p.a.x) {
      break;
    }
    let _63 = fma(f32(_92) * vTexCoord.x, 2.0, _93);
    _102 = _92;
    _101 = _63;
    continuing {
      let _67 = _92 + 1i;
      _99 = _102;
      _93 = _101;
      _92 = _67;
    }
  }
  _94 = 0i;
  loop {
    _74 = _94 + 2i;
    if (!(_74 < p.i.y)) {
      break;
    }
    _94 = _74;
  }
  fragColor = vec4<f32>(_93, f32(_99), f32(_74), 1.0);
  return fragColor;
}
