// crtforge preset 'loop-carried': WGSL for WebGPU, generated from SPIR-V by crtforge's WGSL emitter.
// loops (carried) after the derivative footprint tap
// Draw 3 vertices with no vertex buffers: vs_main makes a full-screen triangle, fs_main shades it.
// Bindings (group 0) and the uniform buffer's byte layout are in manifest.json under targets.wgsl.

struct VertexOutput {
  @location(0) vTexCoord: vec2<f32>,
  @builtin(position) gl_Position: vec4<f32>,
}

struct CrtParams {
  outputSize: vec2<f32>,  // offset 0
  tapMix: f32,  // offset 8
  loopCount: i32,  // offset 12
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
  var _238: f32;
  var _237: i32;
  var _241: f32;
  var _239: f32;
  let _144 = textureSample(source, source_sampler, vTexCoord);
  let _179 = length(fwidth(vTexCoord)) * 100.0;
  let _185 = vTexCoord + (vec2<f32>(dpdx(vTexCoord.x), dpdy(vTexCoord.y)) * 4.0);
  let _186 = textureSample(source, source_sampler, _185);
  let _191 = crt.tapMix * clamp(_179, 0.0, 1.0);
  let _193 = mix(_144.xyz, _186.xyz, vec3<f32>(_191, _191, _191));
  _238 = 0.0;
  _237 = 0i;
  loop {
    if (!(_237 < crt.loopCount)) {
      _239 = _238;
      break;
    }
    if (_237 == 1i) {
      _241 = _238;
      continue;
    }
    let _216 = fma(_193.x * f32(_237), 0.25, _238);
    if (_216 > 2.0) {
      _239 = _216;
      break;
    }
    _241 = _216;
    continuing {
      let _223 = _237 + 1i;
      _238 = _241;
      _237 = _223;
    }
  }
  let _229 = _193 * fma(0.1, _239, 1.0);
  fragColor = vec4<f32>(_229.x, _229.y, _229.z, 1.0);
  return fragColor;
}
