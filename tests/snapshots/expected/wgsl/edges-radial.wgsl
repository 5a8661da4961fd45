// crtforge preset 'edges-radial': WGSL for WebGPU, generated from SPIR-V by crtforge's WGSL emitter.
// shape (radial, not inverted) and the scrolling pulse
// Draw 3 vertices with no vertex buffers: vs_main makes a full-screen triangle, fs_main shades it.
// Bindings (group 0) and the uniform buffer's byte layout are in manifest.json under targets.wgsl.

struct VertexOutput {
  @location(0) vTexCoord: vec2<f32>,
  @builtin(position) gl_Position: vec4<f32>,
}

struct CrtParams {
  outputSize: vec2<f32>,  // offset 0
  time: f32,  // offset 8
  shapeScale: f32,  // offset 12
  pulseDepth: f32,  // offset 16
  pulseRate: f32,  // offset 20
}

@group(0) @binding(0) var<uniform> crt: CrtParams;
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
  let _126 = textureSample(source, source_sampler, vTexCoord);
  let _156 = length((vTexCoord * 2.0) - vec2<f32>(1.0)) * crt.shapeScale;
  let _157_t = clamp((_156 - 0.9) / (0.3 - 0.9), f32(0.0), f32(1.0));
  let _175 = fma((vTexCoord * crt.outputSize).y, 0.025, crt.time * crt.pulseRate);
  let _179 = (_126.xyz * (_157_t * _157_t * (3.0 - 2.0 * _157_t))) * fma(crt.pulseDepth, sin(_175), 1.0);
  let _144 = vec4<f32>(_179.x, _179.y, _179.z, 1.0);
  let _187 = (bitcast<vec4<u32>>(_144) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
  let _188 = select(clamp(_144, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), _187);
  fragColor = _188;
  return fragColor;
}
