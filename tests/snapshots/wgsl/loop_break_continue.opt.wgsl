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
  var last: i32;
  var sum: f32;
  var k: i32;
  var last_1: i32;
  var sum_1: f32;
  var w: i32;
  var w_1: i32;
  last = (-1i);
  sum = 0.0;
  k = 0i;
  loop {
    if (!(k < p.i.x)) {
      break;
    }
    if (k == p.i.y) {
      last_1 = last;
      sum_1 = sum;
      continue;
    }
    if (sum > p.a.x) {
      break;
    }
    let sum_2 = fma(f32(k) * vTexCoord.x, 2.0, sum);
    last_1 = k;
    sum_1 = sum_2;
    continuing {
      let k_1 = k + 1i;
      last = last_1;
      sum = sum_1;
      k = k_1;
    }
  }
  w = 0i;
  loop {
    w_1 = w + 2i;
    if (!(w_1 < p.i.y)) {
      break;
    }
    w = w_1;
  }
  fragColor = vec4<f32>(sum, f32(last), f32(w_1), 1.0);
  return fragColor;
}
