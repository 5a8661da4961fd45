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
  var _801: vec4<f32>;
  var _800: i32;
  var _804: vec3<f32>;
  var _802: f32;
  var _708: bool;
  var _722: bool;
  var _805: vec3<f32>;
  var _783: vec4<f32>;
  var _544: i32;
  let _385 = vTexCoord * crt.outputSize;
  let _469 = vec4<f32>(vTexCoord.x, vTexCoord.y, vTexCoord.y, vTexCoord.x) * 2.0;
  let _471 = _469 - vec4<f32>(1.0);
  let _475 = _471.xy;
  let _483 = _471.zw * fma(crt.bendAmount, dot(_475, _475), 1.0);
  var _776 = vec4<f32>();
  _776.z = _483.x;
  var _778 = _776;
  _778.w = _483.y;
  let _492 = (_778.wz * 0.5) + vec2<f32>(0.5);
  let _398 = (_492 * 2.0) - vec2<f32>(1.0);
  let _406 = textureSample(source, source_sampler, _492);
  let _508 = length(fwidth(_492)) * 100.0;
  let _515 = textureSample(source, source_sampler, _492 + (vec2<f32>(dpdx(_492.x), dpdy(_492.y)) * 4.0));
  let _520 = crt.tapMix * clamp(_508, 0.0, 1.0);
  let _522 = mix(_406.xyz, _515.xyz, vec3<f32>(_520, _520, _520));
  let _531 = vec4<f32>(_522.x, _522.y, _522.z, 1.0);
  _801 = _531;
  _800 = 0i;
  loop {
    _783 = _801;
    _783.y = fma(_522.y, 0.5, 0.01 * f32(_800));
    _544 = _800 + 1i;
    if (_544 >= crt.loopCount) {
      break;
    }
    continuing {
      _801 = _783;
      _800 = _544;
    }
  }
  let _568 = i32(_385.x) - 10i;
  let _576_rem = _568 % crt.bandWidth;
  let _576_1 = select(_576_rem, _576_rem + crt.bandWidth, (_576_rem != i32()) & ((_576_rem < i32()) != (crt.bandWidth < i32())));
  let _581 = _385.y - 4.0;
  let _591 = fma(0.01, f32(_576_1), fma(0.02, f32(_568 / crt.bandWidth), 1.0));
  let _598 = fma(0.03, _581 - (-5.0) * floor(_581 / (-5.0)), fma((-0.001), f32(_568 / (-3i)), _591));
  let _599 = (_783.xyz * _801.w) * _598;
  switch (i32(_385.y) & 3i) {
    case 0i: {
      _804 = vec3<f32>(1.0, crt.pickDim, crt.pickDim);
    }
    case 1i, 2i: {
      _804 = vec3<f32>(crt.pickDim, 1.0, crt.pickDim);
    }
    default: {
      _804 = vec3<f32>(crt.pickDim, crt.pickDim, 1.0);
    }
  }
  if (_492.x > 0.5) {
    _802 = sqrt(max(_599.y, 0.0));
  } else {
    _802 = _599.y * _599.y;
  }
  let _652 = select((-0.01), 0.01, vTexCoord.y < 0.5) * _802;
  let _664 = abs(_398) * crt.shapeScale;
  let _670 = 1.5 - max(_664.x, _664.y);
  let _675 = fma(_599, _804, vec3<f32>(_652, _652, _652)) * min(max(_670, 0.8), 0.2);
  let _692 = fma(crt.pulseDepth, sin(fma(_385.y, 0.025, crt.time * crt.pulseRate)), 1.0);
  let _693 = _675 * _692;
  switch (0u) {
    default: {
      let _701 = _492.x < 0.0;
      if (!_701) {
        _708 = _492.x > 1.0;
      } else {
        _708 = _701;
      }
      if (_708) {
        _805 = crt.edgeColor;
        fragColor = vec4<f32>(_805.x, _805.y, _805.z, 1.0);
        return fragColor;
      }
      let _715 = _492.y < 0.0;
      if (!_715) {
        _722 = _492.y > 1.0;
      } else {
        _722 = _715;
      }
      if (_722) {
        _805 = crt.edgeColor.zyx;
        fragColor = vec4<f32>(_805.x, _805.y, _805.z, 1.0);
        return fragColor;
      }
      _805 = _693;
    }
  }
  fragColor = vec4<f32>(_805.x, _805.y, _805.z, 1.0);
  return fragColor;
}
