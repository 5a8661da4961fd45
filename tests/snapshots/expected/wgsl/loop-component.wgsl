// crtforge preset 'loop-component': WGSL for WebGPU, generated from SPIR-V by crtforge's WGSL emitter.
// loops (component) alone
// Draw 3 vertices with no vertex buffers: vs_main makes a full-screen triangle, fs_main shades it.
// Bindings (group 0) and the uniform buffer's byte layout are in manifest.json under targets.wgsl.

struct VertexOutput {
  @location(0) vTexCoord: vec2<f32>,
  @builtin(position) gl_Position: vec4<f32>,
}

struct CrtParams {
  outputSize: vec2<f32>,  // offset 0
  loopCount: i32,  // offset 8
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
  var _164: vec4<f32>;
  var _163: i32;
  var _161: vec4<f32>;
  var _141: i32;
  let _105 = textureSample(source, source_sampler, vTexCoord);
  let _128 = vec4<f32>(_105.x, _105.y, _105.z, 1.0);
  _164 = _128;
  _163 = 0i;
  loop {
    _161 = _164;
    _161.y = fma(_105.y, 0.9, 0.01 * f32(_163));
    _141 = _163 + 1i;
    if (_141 >= crt.loopCount) {
      break;
    }
    continuing {
      _164 = _161;
      _163 = _141;
    }
  }
  let _154 = _161.xyz * _164.w;
  fragColor = vec4<f32>(_154.x, _154.y, _154.z, 1.0);
  return fragColor;
}
