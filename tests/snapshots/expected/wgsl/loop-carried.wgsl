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
  var _267: f32;
  var _266: i32;
  var _270: f32;
  var _268: f32;
  let _162 = textureSample(source, source_sampler, vTexCoord);
  let _199 = length(fwidth(vTexCoord)) * 100.0;
  let _205 = vTexCoord + (vec2<f32>(dpdx(vTexCoord.x), dpdy(vTexCoord.y)) * 4.0);
  let _206 = textureSample(source, source_sampler, _205);
  let _211 = crt.tapMix * clamp(_199, 0.0, 1.0);
  let _213 = mix(_162.xyz, _206.xyz, vec3<f32>(_211, _211, _211));
  _267 = 0.0;
  _266 = 0i;
  loop {
    if (!(_266 < crt.loopCount)) {
      _268 = _267;
      break;
    }
    if (_266 == 1i) {
      _270 = _267;
      continue;
    }
    let _236 = fma(_213.x * f32(_266), 0.25, _267);
    if (_236 > 2.0) {
      _268 = _236;
      break;
    }
    _270 = _236;
    continuing {
      let _243 = _266 + 1i;
      _267 = _270;
      _266 = _243;
    }
  }
  let _249 = _213 * fma(0.1, _268, 1.0);
  let _180 = vec4<f32>(_249.x, _249.y, _249.z, 1.0);
  let _257 = (bitcast<vec4<u32>>(_180) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
  let _258 = select(clamp(_180, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), _257);
  fragColor = _258;
  return fragColor;
}
