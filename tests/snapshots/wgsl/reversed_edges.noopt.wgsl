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
  var x: f32;
  x = vTexCoord.x;
  let _22 = x;
  let _23_t = clamp((_22 - 0.85) / (0.4 - 0.85), f32(0.0), f32(1.0));
  let _24 = x;
  let _26 = x;
  let _30 = x;
  let _32 = vec4<f32>(_23_t * _23_t * (3.0 - 2.0 * _23_t), smoothstep(0.4, 0.85, _24), min(max(_26, 0.75), 0.25), clamp(_30, 0.25, 0.75));
  fragColor = _32;
  return fragColor;
}
