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

fn expensive(x: ptr<function, f32>) -> f32 {
  let _12 = (*x);
  return sin(_12) * 0.5;
}

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
  var right: bool;
  var f: f32;
  var c: vec3<f32>;
  var _49: vec3<f32>;
  var g: f32;
  var _69: f32;
  var param: f32;
  right = vTexCoord.x > p.a.x;
  let _41 = right;
  f = select(0.0, 1.0, _41);
  let _48 = right;
  if (_48) {
    _49 = vec3<f32>(0.25);
  } else {
    let _61 = textureSample(source, source_sampler, vTexCoord);
    _49 = _61.xyz;
  }
  let _63 = _49;
  c = _63;
  if (vTexCoord.y > 0.5) {
    param = vTexCoord.x;
    let _75 = expensive(&param);
    _69 = _75;
  } else {
    _69 = 0.0;
  }
  let _77 = _69;
  g = _77;
  let _80 = f;
  let _82 = c.y;
  let _83 = g;
  let _84 = right;
  fragColor = vec4<f32>(_80, _82, _83, select(0.5, 1.0, _84));
  return fragColor;
}
