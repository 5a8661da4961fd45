// crtforge preset 'everything': WGSL for WebGPU, generated from SPIR-V by crtforge's WGSL emitter.
// Every snapshot stage enabled, with spec defaults except where noted
// Draw 3 vertices with no vertex buffers: vs_main makes a full-screen triangle, fs_main shades it.
// Bindings (group 0) and the uniform buffer's byte layout are in manifest.json under targets.wgsl.

struct VertexOutput {
  @location(0) vTexCoord: vec2<f32>,
  @builtin(position) gl_Position: vec4<f32>,
}

struct CrtParams {
  outputSize: vec2<f32>,  // offset 0
  time: f32,  // offset 8
  bendAmount: f32,  // offset 12
  edgeColor: vec3<f32>,  // offset 16
  tapMix: f32,  // offset 28
  loopCount: i32,  // offset 32
  bandWidth: i32,  // offset 36
  pickDim: f32,  // offset 40
  shapeScale: f32,  // offset 44
  pulseDepth: f32,  // offset 48
  pulseRate: f32,  // offset 52
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
  var _829: vec4<f32>;
  var _828: i32;
  var _832: vec3<f32>;
  var _830: f32;
  var _727: bool;
  var _741: bool;
  var _833: vec3<f32>;
  var _811: vec4<f32>;
  var _563: i32;
  let _402 = vTexCoord * crt.outputSize;
  let _488 = vec4<f32>(vTexCoord.x, vTexCoord.y, vTexCoord.y, vTexCoord.x) * 2.0;
  let _490 = _488 - vec4<f32>(1.0);
  let _494 = _490.xy;
  let _502 = _490.zw * fma(crt.bendAmount, dot(_494, _494), 1.0);
  var _804 = vec4<f32>();
  _804.z = _502.x;
  var _806 = _804;
  _806.w = _502.y;
  let _511 = (_806.wz * 0.5) + vec2<f32>(0.5);
  let _415 = (_511 * 2.0) - vec2<f32>(1.0);
  let _423 = textureSample(source, source_sampler, _511);
  let _527 = length(fwidth(_511)) * 100.0;
  let _534 = textureSample(source, source_sampler, _511 + (vec2<f32>(dpdx(_511.x), dpdy(_511.y)) * 4.0));
  let _539 = crt.tapMix * clamp(_527, 0.0, 1.0);
  let _541 = mix(_423.xyz, _534.xyz, vec3<f32>(_539, _539, _539));
  let _550 = vec4<f32>(_541.x, _541.y, _541.z, 1.0);
  _829 = _550;
  _828 = 0i;
  loop {
    _811 = _829;
    _811.y = fma(_541.y, 0.5, 0.01 * f32(_828));
    _563 = _828 + 1i;
    if (_563 >= crt.loopCount) {
      break;
    }
    continuing {
      _829 = _811;
      _828 = _563;
    }
  }
  let _587 = i32(_402.x) - 10i;
  let _595_rem = _587 % crt.bandWidth;
  let _595_1 = select(_595_rem, _595_rem + crt.bandWidth, (_595_rem != i32()) & ((_595_rem < i32()) != (crt.bandWidth < i32())));
  let _600 = _402.y - 4.0;
  let _610 = fma(0.01, f32(_595_1), fma(0.02, f32(_587 / crt.bandWidth), 1.0));
  let _617 = fma(0.03, _600 - (-5.0) * floor(_600 / (-5.0)), fma((-0.001), f32(_587 / (-3i)), _610));
  let _618 = (_811.xyz * _829.w) * _617;
  switch (i32(_402.y) & 3i) {
    case 0i: {
      _832 = vec3<f32>(1.0, crt.pickDim, crt.pickDim);
    }
    case 1i, 2i: {
      _832 = vec3<f32>(crt.pickDim, 1.0, crt.pickDim);
    }
    default: {
      _832 = vec3<f32>(crt.pickDim, crt.pickDim, 1.0);
    }
  }
  if (_511.x > 0.5) {
    _830 = sqrt(max(_618.y, 0.0));
  } else {
    _830 = _618.y * _618.y;
  }
  let _671 = select((-0.01), 0.01, vTexCoord.y < 0.5) * _830;
  let _683 = abs(_415) * crt.shapeScale;
  let _689 = 1.5 - max(_683.x, _683.y);
  let _694 = fma(_618, _832, vec3<f32>(_671, _671, _671)) * min(max(_689, 0.8), 0.2);
  let _711 = fma(crt.pulseDepth, sin(fma(_402.y, 0.025, crt.time * crt.pulseRate)), 1.0);
  let _712 = _694 * _711;
  switch (0u) {
    default: {
      let _720 = _511.x < 0.0;
      if (!_720) {
        _727 = _511.x > 1.0;
      } else {
        _727 = _720;
      }
      if (_727) {
        _833 = crt.edgeColor;
        let _466 = vec4<f32>(_833.x, _833.y, _833.z, 1.0);
        let _757 = (bitcast<vec4<u32>>(_466) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
        let _758 = select(clamp(_466, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), _757);
        fragColor = _758;
        return fragColor;
      }
      let _734 = _511.y < 0.0;
      if (!_734) {
        _741 = _511.y > 1.0;
      } else {
        _741 = _734;
      }
      if (_741) {
        _833 = crt.edgeColor.zyx;
        let _466_1 = vec4<f32>(_833.x, _833.y, _833.z, 1.0);
        let _757_1 = (bitcast<vec4<u32>>(_466_1) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
        let _758_1 = select(clamp(_466_1, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), _757_1);
        fragColor = _758_1;
        return fragColor;
      }
      _833 = _712;
    }
  }
  let _466_2 = vec4<f32>(_833.x, _833.y, _833.z, 1.0);
  let _757_2 = (bitcast<vec4<u32>>(_466_2) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
  let _758_2 = select(clamp(_466_2, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), _757_2);
  fragColor = _758_2;
  return fragColor;
}
