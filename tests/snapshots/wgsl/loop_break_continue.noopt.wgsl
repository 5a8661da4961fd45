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
  var sum: f32;
  var last: i32;
  var k: i32;
  var w: i32;
  sum = 0.0;
  last = (-1i);
  k = 0i;
  loop {
    let _21 = k;
    if (!(_21 < p.i.x)) {
      break;
    }
    let _35 = k;
    if (_35 == p.i.y) {
      continue;
    }
    let _43 = sum;
    if (_43 > p.a.x) {
      break;
    }
    let _51 = k;
    let _62 = sum;
    sum = _62 + ((f32(_51) * vTexCoord.x) * 2.0);
    let _64 = k;
    last = _64;
    continuing {
      let _65 = k;
      k = _65 + 1i;
    }
  }
  w = 0i;
  loop {
    let _73 = w;
    w = _73 + 2i;
    continuing {
      let _75 = w;
      break if !(_75 < p.i.y);
    }
  }
  let _81 = sum;
  let _82 = last;
  let _84 = w;
  fragColor = vec4<f32>(_81, f32(_82), f32(_84), 1.0);
  return fragColor;
}
