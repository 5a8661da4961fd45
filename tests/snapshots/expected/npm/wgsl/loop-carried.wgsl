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
  let uv = vec2<f32>(f32((i32(vertex_index) << 1u) & 2i), f32(i32(vertex_index) & 2i));
  vTexCoord = uv;
  let difference = (uv * 2.0) - vec2<f32>(1.0);
  gl_Position = vec4<f32>(difference.x, difference.y, 0.0, 1.0);
  return VertexOutput(vTexCoord, gl_Position * vec4<f32>(1.0, -1.0, 1.0, 1.0));
}

@fragment
fn fs_main(@location(0) vTexCoord: vec2<f32>) -> @location(0) vec4<f32> {
  var fragColor: vec4<f32>;
  var sum: f32;
  var k: i32;
  var sum_1: f32;
  var sum_2: f32;
  let texel = textureSample(source, source_sampler, vTexCoord);
  let product = length(fwidth(vTexCoord)) * 100.0;
  let sum_3 = vTexCoord + (vec2<f32>(dpdx(vTexCoord.x), dpdy(vTexCoord.y)) * 4.0);
  let texel_1 = textureSample(source, source_sampler, sum_3);
  let product_1 = crt.tapMix * clamp(product, 0.0, 1.0);
  let color = mix(texel.xyz, texel_1.xyz, vec3<f32>(product_1, product_1, product_1));
  sum = 0.0;
  k = 0i;
  loop {
    if (!(k < crt.loopCount)) {
      sum_2 = sum;
      break;
    }
    if (k == 1i) {
      sum_1 = sum;
      continue;
    }
    let sum_4 = fma(color.x * f32(k), 0.25, sum);
    if (sum_4 > 2.0) {
      sum_2 = sum_4;
      break;
    }
    sum_1 = sum_4;
    continuing {
      let k_1 = k + 1i;
      sum = sum_1;
      k = k_1;
    }
  }
  let color_1 = color * fma(0.1, sum_2, 1.0);
  let c = vec4<f32>(color_1.x, color_1.y, color_1.z, 1.0);
  let cond = (bitcast<vec4<u32>>(c) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
  let chosen = select(clamp(c, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), cond);
  fragColor = chosen;
  return fragColor;
}
