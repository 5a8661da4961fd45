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
  var _306: bool;
  var _320: bool;
  var _353: vec3<f32>;
  let _232 = vec4<f32>(vTexCoord.x, vTexCoord.y, vTexCoord.y, vTexCoord.x) * 2.0;
  let _234 = _232 - vec4<f32>(1.0);
  let _238 = _234.xy;
  let _246 = _234.zw * fma(crt.bendAmount, dot(_238, _238), 1.0);
  var _346 = vec4<f32>();
  _346.z = _246.x;
  var _348 = _346;
  _348.w = _246.y;
  let _253 = _348.wz * 0.5;
  let _255 = _253 + vec2<f32>(0.5);
  let _193 = textureSample(source, source_sampler, _255);
  let _262 = textureSample(source, source_sampler, _253 + vec2<f32>(0.5025, 0.5));
  let _267 = textureSample(source, source_sampler, _253 + vec2<f32>(0.4975, 0.5));
  let _274 = textureSample(source, source_sampler, _253 + vec2<f32>(0.5, 0.5025));
  let _281 = textureSample(source, source_sampler, _253 + vec2<f32>(0.5, 0.4975));
  let _291 = mix(_193.xyz, (((_262.xyz + _267.xyz) + _274.xyz) + _281.xyz) * 0.25, vec3<f32>(crt.tapMix, crt.tapMix, crt.tapMix));
  switch (0u) {
    default: {
      let _299 = _255.x < 0.0;
      if (!_299) {
        _306 = _255.x > 1.0;
      } else {
        _306 = _299;
      }
      if (_306) {
        _353 = crt.edgeColor;
        fragColor = vec4<f32>(_353.x, _353.y, _353.z, 1.0);
        return fragColor;
      }
      let _313 = _255.y < 0.0;
      if (!_313) {
        _320 = _255.y > 1.0;
      } else {
        _320 = _313;
      }
      if (_320) {
        _353 = crt.edgeColor.zyx;
        fragColor = vec4<f32>(_353.x, _353.y, _353.z, 1.0);
        return fragColor;
      }
      _353 = _291;
    }
  }
  fragColor = vec4<f32>(_353.x, _353.y, _353.z, 1.0);
  return fragColor;
}
