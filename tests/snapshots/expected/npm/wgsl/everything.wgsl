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
  let uv = vec2<f32>(f32((i32(vertex_index) << 1u) & 2i), f32(i32(vertex_index) & 2i));
  vTexCoord = uv;
  let difference = (uv * 2.0) - vec2<f32>(1.0);
  gl_Position = vec4<f32>(difference.x, difference.y, 0.0, 1.0);
  return VertexOutput(vTexCoord, gl_Position * vec4<f32>(1.0, -1.0, 1.0, 1.0));
}

@fragment
fn fs_main(@location(0) vTexCoord: vec2<f32>) -> @location(0) vec4<f32> {
  var fragColor: vec4<f32>;
  var s: vec4<f32>;
  var k: i32;
  var tint: vec3<f32>;
  var lift: f32;
  var cond: bool;
  var cond_1: bool;
  var color: vec3<f32>;
  var s_1: vec4<f32>;
  var k_1: i32;
  let product = vTexCoord * crt.outputSize;
  let product_1 = vec4<f32>(vTexCoord.x, vTexCoord.y, vTexCoord.y, vTexCoord.x) * 2.0;
  let q = product_1 - vec4<f32>(1.0);
  let q_xy = q.xy;
  let product_2 = q.zw * fma(crt.bendAmount, dot(q_xy, q_xy), 1.0);
  var q_1 = vec4<f32>();
  q_1.z = product_2.x;
  var q_2 = q_1;
  q_2.w = product_2.y;
  let sampleUv = (q_2.wz * 0.5) + vec2<f32>(0.5);
  let difference = (sampleUv * 2.0) - vec2<f32>(1.0);
  let texel = textureSample(source, source_sampler, sampleUv);
  let product_3 = length(fwidth(sampleUv)) * 100.0;
  let texel_1 = textureSample(source, source_sampler, sampleUv + (vec2<f32>(dpdx(sampleUv.x), dpdy(sampleUv.y)) * 4.0));
  let product_4 = crt.tapMix * clamp(product_3, 0.0, 1.0);
  let color_1 = mix(texel.xyz, texel_1.xyz, vec3<f32>(product_4, product_4, product_4));
  let s_2 = vec4<f32>(color_1.x, color_1.y, color_1.z, 1.0);
  s = s_2;
  k = 0i;
  loop {
    s_1 = s;
    s_1.y = fma(color_1.y, 0.5, 0.01 * f32(k));
    k_1 = k + 1i;
    if (k_1 >= crt.loopCount) {
      break;
    }
    continuing {
      s = s_1;
      k = k_1;
    }
  }
  let x = i32(product.x) - 10i;
  let r_rem = x % crt.bandWidth;
  let r_1 = select(r_rem, r_rem + crt.bandWidth, (r_rem != i32()) & ((r_rem < i32()) != (crt.bandWidth < i32())));
  let difference_1 = product.y - 4.0;
  let value = fma((-0.001), f32(x / (-3i)), fma(0.01, f32(r_1), fma(0.02, f32(x / crt.bandWidth), 1.0)));
  let value_1 = fma(0.03, difference_1 - (-5.0) * floor(difference_1 / (-5.0)), value);
  let color_2 = (s_1.xyz * s.w) * value_1;
  switch (i32(product.y) & 3i) {
    case 0i: {
      tint = vec3<f32>(1.0, crt.pickDim, crt.pickDim);
    }
    case 1i, 2i: {
      tint = vec3<f32>(crt.pickDim, 1.0, crt.pickDim);
    }
    default: {
      tint = vec3<f32>(crt.pickDim, crt.pickDim, 1.0);
    }
  }
  if (sampleUv.x > 0.5) {
    lift = sqrt(max(color_2.y, 0.0));
  } else {
    lift = color_2.y * color_2.y;
  }
  let product_5 = select((-0.01), 0.01, vTexCoord.y < 0.5) * lift;
  let d = abs(difference) * crt.shapeScale;
  let color_3 = fma(color_2, tint, vec3<f32>(product_5, product_5, product_5)) * min(max(1.5 - max(d.x, d.y), 0.8), 0.2);
  let value_2 = fma(crt.pulseDepth, sin(fma(product.y, 0.025, crt.time * crt.pulseRate)), 1.0);
  let color_4 = color_3 * value_2;
  switch (0u) {
    default: {
      let cond_2 = sampleUv.x < 0.0;
      if (!cond_2) {
        cond = sampleUv.x > 1.0;
      } else {
        cond = cond_2;
      }
      if (cond) {
        color = crt.edgeColor;
        break;
      }
      let cond_3 = sampleUv.y < 0.0;
      if (!cond_3) {
        cond_1 = sampleUv.y > 1.0;
      } else {
        cond_1 = cond_3;
      }
      if (cond_1) {
        color = crt.edgeColor.zyx;
        break;
      }
      color = color_4;
    }
  }
  let c = vec4<f32>(color.x, color.y, color.z, 1.0);
  let cond_4 = (bitcast<vec4<u32>>(c) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
  let chosen = select(clamp(c, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), cond_4);
  fragColor = chosen;
  return fragColor;
}
