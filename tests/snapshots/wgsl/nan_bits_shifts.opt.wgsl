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
  var _219: f32;
  var _220: f32;
  let bits = bitcast<u32>(bitcast<u32>(vTexCoord.x)) >> 16u;
  let shifted = bitcast<i32>(p.i.y) >> 2u;
  let _113 = select(0.0, 1.0, (bitcast<u32>(p.a.x) & 0x7fffffffu) > 0x7f800000u);
  if (p.a.x != p.a.x) {
    _219 = f32(shifted);
  } else {
    _219 = 0.0;
  }
  let _134 = f32(bits & 255u) * 0.003921569;
  if ((bitcast<u32>(p.a.z) & 0x7fffffffu) == 0x7f800000u) {
    _220 = f32(bitcast<u32>(bitcast<u32>(p.i.y)) >> 28u);
  } else {
    _220 = 0.0;
  }
  fragColor = vec4<f32>(_113, _219, _134, _220);
  return fragColor;
}
