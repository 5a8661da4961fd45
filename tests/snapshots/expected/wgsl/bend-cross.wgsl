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
  let uv = vec2<f32>(f32((i32(vertex_index) << 1u) & 2i), f32(i32(vertex_index) & 2i));
  vTexCoord = uv;
  let difference = (uv * 2.0) - vec2<f32>(1.0);
  gl_Position = vec4<f32>(difference.x, difference.y, 0.0, 1.0);
  return VertexOutput(vTexCoord, gl_Position * vec4<f32>(1.0, -1.0, 1.0, 1.0));
}

@fragment
fn fs_main(@location(0) vTexCoord: vec2<f32>) -> @location(0) vec4<f32> {
  var fragColor: vec4<f32>;
  var cond: bool;
  var cond_1: bool;
  var color: vec3<f32>;
  let product = vec4<f32>(vTexCoord.x, vTexCoord.y, vTexCoord.y, vTexCoord.x) * 2.0;
  let q = product - vec4<f32>(1.0);
  let q_xy = q.xy;
  let product_1 = q.zw * fma(crt.bendAmount, dot(q_xy, q_xy), 1.0);
  var q_1 = vec4<f32>();
  q_1.z = product_1.x;
  var q_2 = q_1;
  q_2.w = product_1.y;
  let product_2 = q_2.wz * 0.5;
  let sampleUv = product_2 + vec2<f32>(0.5);
  let texel = textureSample(source, source_sampler, sampleUv);
  let texel_1 = textureSample(source, source_sampler, product_2 + vec2<f32>(0.5025, 0.5));
  let texel_2 = textureSample(source, source_sampler, product_2 + vec2<f32>(0.4975, 0.5));
  let texel_3 = textureSample(source, source_sampler, product_2 + vec2<f32>(0.5, 0.5025));
  let texel_4 = textureSample(source, source_sampler, product_2 + vec2<f32>(0.5, 0.4975));
  let product_3 = (((texel_1.xyz + texel_2.xyz) + texel_3.xyz) + texel_4.xyz) * 0.25;
  let color_1 = mix(texel.xyz, product_3, vec3<f32>(crt.tapMix, crt.tapMix, crt.tapMix));
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
      color = color_1;
    }
  }
  let c = vec4<f32>(color.x, color.y, color.z, 1.0);
  let cond_4 = (bitcast<vec4<u32>>(c) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
  let chosen = select(clamp(c, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), cond_4);
  fragColor = chosen;
  return fragColor;
}
