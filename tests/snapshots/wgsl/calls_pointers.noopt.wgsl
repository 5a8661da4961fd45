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

fn scale(c: ptr<function, vec3<f32>>, k: ptr<function, f32>) {
  let _19 = (*k);
  let _20 = (*c);
  (*c) = _20 * _19;
  return;
}

fn twice(x: ptr<function, f32>) -> f32 {
  let _22 = (*x);
  return _22 * 2.0;
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
  var c: vec3<f32>;
  var param: f32;
  var param_1: vec3<f32>;
  var param_2: f32;
  var k: i32;
  let _38 = textureSample(source, source_sampler, vTexCoord);
  c = _38.xyz;
  param = p.a.x;
  let _52 = twice(&param);
  let _56 = c;
  param_1 = _56;
  param_2 = _52 / 6.0;
  scale(&param_1, &param_2);
  let _59 = param_1;
  c = _59;
  k = 0i;
  loop {
    let _67 = k;
    if (!(_67 < 3i)) {
      break;
    }
    let _71 = k;
    let _72 = k;
    let _74 = c[_72];
    c[_71] = _74 + 0.125;
    continuing {
      let _78 = k;
      k = _78 + 1i;
    }
  }
  let _83 = c;
  fragColor = vec4<f32>(_83.x, _83.y, _83.z, 1.0);
  return fragColor;
}
