// crtforge preset 'bend-cross': WGSL for WebGPU, generated from SPIR-V by crtforge's WGSL emitter.
// bend (swizzle warp, edge colour) with the four-tap cross
// Draw 3 vertices with no vertex buffers: vs_main makes a full-screen triangle, fs_main shades it.
// Bindings (group 0) and the uniform buffer's byte layout are in manifest.json under targets.wgsl.

struct VertexOutput {
  @location(0) vTexCoord: vec2<f32>,
  @builtin(position) gl_Position: vec4<f32>,
}

struct CrtParams {
  outputSize: vec2<f32>,  // offset 0
  bendAmount: f32,  // offset 8
  edgeColor: vec3<f32>,  // offset 16
  tapMix: f32,  // offset 28
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
  var _325: bool;
  var _339: bool;
  var _381: vec3<f32>;
  let _251 = vec4<f32>(vTexCoord.x, vTexCoord.y, vTexCoord.y, vTexCoord.x) * 2.0;
  let _253 = _251 - vec4<f32>(1.0);
  let _257 = _253.xy;
  let _265 = _253.zw * fma(crt.bendAmount, dot(_257, _257), 1.0);
  var _374 = vec4<f32>();
  _374.z = _265.x;
  var _376 = _374;
  _376.w = _265.y;
  let _272 = _376.wz * 0.5;
  let _274 = _272 + vec2<f32>(0.5);
  let _210 = textureSample(source, source_sampler, _274);
  let _281 = textureSample(source, source_sampler, _272 + vec2<f32>(0.5025, 0.5));
  let _286 = textureSample(source, source_sampler, _272 + vec2<f32>(0.4975, 0.5));
  let _293 = textureSample(source, source_sampler, _272 + vec2<f32>(0.5, 0.5025));
  let _300 = textureSample(source, source_sampler, _272 + vec2<f32>(0.5, 0.4975));
  let _310 = mix(_210.xyz, (((_281.xyz + _286.xyz) + _293.xyz) + _300.xyz) * 0.25, vec3<f32>(crt.tapMix, crt.tapMix, crt.tapMix));
  switch (0u) {
    default: {
      let _318 = _274.x < 0.0;
      if (!_318) {
        _325 = _274.x > 1.0;
      } else {
        _325 = _318;
      }
      if (_325) {
        _381 = crt.edgeColor;
        let _228 = vec4<f32>(_381.x, _381.y, _381.z, 1.0);
        let _355 = (bitcast<vec4<u32>>(_228) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
        let _356 = select(clamp(_228, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), _355);
        fragColor = _356;
        return fragColor;
      }
      let _332 = _274.y < 0.0;
      if (!_332) {
        _339 = _274.y > 1.0;
      } else {
        _339 = _332;
      }
      if (_339) {
        _381 = crt.edgeColor.zyx;
        let _228_1 = vec4<f32>(_381.x, _381.y, _381.z, 1.0);
        let _355_1 = (bitcast<vec4<u32>>(_228_1) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
        let _356_1 = select(clamp(_228_1, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), _355_1);
        fragColor = _356_1;
        return fragColor;
      }
      _381 = _310;
    }
  }
  let _228_2 = vec4<f32>(_381.x, _381.y, _381.z, 1.0);
  let _355_2 = (bitcast<vec4<u32>>(_228_2) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
  let _356_2 = select(clamp(_228_2, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), _355_2);
  fragColor = _356_2;
  return fragColor;
}
