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
fn fs_main() -> @location(0) vec4<f32> {
  var fragColor: vec4<f32>;
  var s: vec4<f32>;
  var k: i32;
  var s_1: vec4<f32>;
  var k_1: i32;
  s = vec4<f32>(0.0);
  k = 0i;
  loop {
    s_1 = s;
    s_1.y = f32(k) * p.a.x;
    k_1 = k + 1i;
    if (k_1 > p.i.x) {
      break;
    }
    continuing {
      s = s_1;
      k = k_1;
    }
  }
  fragColor = s_1;
  return fragColor;
}
