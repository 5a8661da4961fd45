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
  var merged: f32;
  var merged_1: f32;
  let bits = bitcast<u32>(bitcast<u32>(vTexCoord.x)) >> 16u;
  let shifted = bitcast<i32>(p.i.y) >> 2u;
  let chosen = select(0.0, 1.0, (bitcast<u32>(p.a.x) & 0x7fffffffu) > 0x7f800000u);
  if (p.a.x != p.a.x) {
    merged = f32(shifted);
  } else {
    merged = 0.0;
  }
  let product = f32(bits & 255u) * 0.003921569;
  if ((bitcast<u32>(p.a.z) & 0x7fffffffu) == 0x7f800000u) {
    merged_1 = f32(bitcast<u32>(bitcast<u32>(p.i.y)) >> 28u);
  } else {
    merged_1 = 0.0;
  }
  fragColor = vec4<f32>(chosen, merged, product, merged_1);
  return fragColor;
}
