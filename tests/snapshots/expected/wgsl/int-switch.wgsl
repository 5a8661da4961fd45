// crtforge preset 'int-switch': WGSL for WebGPU, generated from SPIR-V by crtforge's WGSL emitter.
// intmath bands and pick rows
// Draw 3 vertices with no vertex buffers: vs_main makes a full-screen triangle, fs_main shades it.
// Bindings (group 0) and the uniform buffer's byte layout are in manifest.json under targets.wgsl.

struct VertexOutput {
  @location(0) vTexCoord: vec2<f32>,
  @builtin(position) gl_Position: vec4<f32>,
}

struct CrtParams {
  outputSize: vec2<f32>,  // offset 0
  bandWidth: i32,  // offset 8
  pickDim: f32,  // offset 12
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
  var _362: vec3<f32>;
  var _360: f32;
  let _179 = vTexCoord * crt.outputSize;
  let _200 = textureSample(source, source_sampler, vTexCoord);
  let _233 = i32(_179.x) - 12i;
  let _241_rem = _233 % crt.bandWidth;
  let _241_1 = select(_241_rem, _241_rem + crt.bandWidth, (_241_rem != i32()) & ((_241_rem < i32()) != (crt.bandWidth < i32())));
  let _246 = _179.y - 4.0;
  let _256 = fma(0.01, f32(_241_1), fma(0.02, f32(_233 / crt.bandWidth), 1.0));
  let _263 = fma(0.03, _246 - (-6.0) * floor(_246 / (-6.0)), fma((-0.001), f32(_233 / (-3i)), _256));
  let _264 = _200.xyz * _263;
  switch (i32(_179.y) & 3i) {
    case 0i: {
      _362 = vec3<f32>(1.0, crt.pickDim, crt.pickDim);
    }
    case 1i, 2i: {
      _362 = vec3<f32>(crt.pickDim, 1.0, crt.pickDim);
    }
    default: {
      _362 = vec3<f32>(crt.pickDim, crt.pickDim, 1.0);
    }
  }
  if (vTexCoord.x > 0.5) {
    _360 = sqrt(max(_264.y, 0.0));
  } else {
    _360 = _264.y * _264.y;
  }
  let _317 = select((-0.01), 0.01, vTexCoord.y < 0.5) * _360;
  let _319 = fma(_264, _362, vec3<f32>(_317, _317, _317));
  let _218 = vec4<f32>(_319.x, _319.y, _319.z, 1.0);
  let _327 = (bitcast<vec4<u32>>(_218) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
  let _328 = select(clamp(_218, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), _327);
  fragColor = _328;
  return fragColor;
}
