// GLSL samples with implicit derivatives inside non-uniform control flow (after the bezel's early
// exit); WGSL would reject that, so the check is off, as GLSL never had it.
diagnostic(off, derivative_uniformity);

struct VertexOutput {
  @location(0) vTexCoord: vec2<f32>,
  @builtin(position) gl_Position: vec4<f32>,
}

struct Params {
  a: vec4<f32>,  // offset 0
  b: vec4<f32>,  // offset 16
  i: vec4<i32>,  // offset 32
}

@group(0) @binding(0) var<uniform> p: Params;
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
  var c: vec3<f32>;
  var g: f32;
  let right = vTexCoord.x > p.a.x;
  let f = select(0.0, 1.0, right);
  if (right) {
    c = vec3<f32>(0.25);
  } else {
    let texel = textureSample(source, source_sampler, vTexCoord);
    c = texel.xyz;
  }
  if (vTexCoord.y > 0.5) {
    g = sin(vTexCoord.x) * 0.5;
  } else {
    g = 0.0;
  }
  fragColor = vec4<f32>(f, c.y, g, select(0.5, 1.0, right));
  return fragColor;
}
