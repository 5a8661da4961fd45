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
  var _193: vec4<f32>;
  var _192: i32;
  var _190: vec4<f32>;
  var _161: i32;
  let _123 = textureSample(source, source_sampler, vTexCoord);
  let _148 = vec4<f32>(_123.x, _123.y, _123.z, 1.0);
  _193 = _148;
  _192 = 0i;
  loop {
    _190 = _193;
    _190.y = fma(_123.y, 0.9, 0.01 * f32(_192));
    _161 = _192 + 1i;
    if (_161 >= crt.loopCount) {
      break;
    }
    continuing {
      _193 = _190;
      _192 = _161;
    }
  }
  let _174 = _190.xyz * _193.w;
  let _136 = vec4<f32>(_174.x, _174.y, _174.z, 1.0);
  let _182 = (bitcast<vec4<u32>>(_136) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
  let _183 = select(clamp(_136, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), _182);
  fragColor = _183;
  return fragColor;
}
