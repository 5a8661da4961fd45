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
  let uv = vec2<f32>(f32((i32(vertex_index) << 1u) & 2i), f32(i32(vertex_index) & 2i));
  vTexCoord = uv;
  let difference = (uv * 2.0) - vec2<f32>(1.0);
  gl_Position = vec4<f32>(difference.x, difference.y, 0.0, 1.0);
  return VertexOutput(vTexCoord, gl_Position * vec4<f32>(1.0, -1.0, 1.0, 1.0));
}

@fragment
fn fs_main(@location(0) vTexCoord: vec2<f32>) -> @location(0) vec4<f32> {
  var fragColor: vec4<f32>;
  var tint: vec3<f32>;
  var lift: f32;
  let product = vTexCoord * crt.outputSize;
  let texel = textureSample(source, source_sampler, vTexCoord);
  let x = i32(product.x) - 12i;
  let r_rem = x % crt.bandWidth;
  let r_1 = select(r_rem, r_rem + crt.bandWidth, (r_rem != i32()) & ((r_rem < i32()) != (crt.bandWidth < i32())));
  let difference = product.y - 4.0;
  let value = fma((-0.001), f32(x / (-3i)), fma(0.01, f32(r_1), fma(0.02, f32(x / crt.bandWidth), 1.0)));
  let value_1 = fma(0.03, difference - (-6.0) * floor(difference / (-6.0)), value);
  let color = texel.xyz * value_1;
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
  if (vTexCoord.x > 0.5) {
    lift = sqrt(max(color.y, 0.0));
  } else {
    lift = color.y * color.y;
  }
  let product_1 = select((-0.01), 0.01, vTexCoord.y < 0.5) * lift;
  let color_1 = fma(color, tint, vec3<f32>(product_1, product_1, product_1));
  let c = vec4<f32>(color_1.x, color_1.y, color_1.z, 1.0);
  let cond = (bitcast<vec4<u32>>(c) & vec4<u32>(0x7fffffffu)) > vec4<u32>(0x7f800000u);
  let chosen = select(clamp(c, vec4<f32>((-65504.0)), vec4<f32>(65504.0)), vec4<f32>(0.0), cond);
  fragColor = chosen;
  return fragColor;
}
