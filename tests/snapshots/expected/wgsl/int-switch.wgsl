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
  var _333: vec3<f32>;
  var _331: f32;
  let _160 = vTexCoord * crt.outputSize;
  let _182 = textureSample(source, source_sampler, vTexCoord);
  let _213 = i32(_160.x) - 12i;
  let _221_rem = _213 % crt.bandWidth;
  let _221_1 = select(_221_rem, _221_rem + crt.bandWidth, (_221_rem != i32()) & ((_221_rem < i32()) != (crt.bandWidth < i32())));
  let _226 = _160.y - 4.0;
  let _236 = fma(0.01, f32(_221_1), fma(0.02, f32(_213 / crt.bandWidth), 1.0));
  let _243 = fma(0.03, _226 - (-6.0) * floor(_226 / (-6.0)), fma((-0.001), f32(_213 / (-3i)), _236));
  let _244 = _182.xyz * _243;
  switch (i32(_160.y) & 3i) {
    case 0i: {
      _333 = vec3<f32>(1.0, crt.pickDim, crt.pickDim);
    }
    case 1i, 2i: {
      _333 = vec3<f32>(crt.pickDim, 1.0, crt.pickDim);
    }
    default: {
      _333 = vec3<f32>(crt.pickDim, crt.pickDim, 1.0);
    }
  }
  if (vTexCoord.x > 0.5) {
    _331 = sqrt(max(_244.y, 0.0));
  } else {
    _331 = _244.y * _244.y;
  }
  let _297 = select((-0.01), 0.01, vTexCoord.y < 0.5) * _331;
  let _299 = fma(_244, _333, vec3<f32>(_297, _297, _297));
  fragColor = vec4<f32>(_299.x, _299.y, _299.z, 1.0);
  return fragColor;
}
