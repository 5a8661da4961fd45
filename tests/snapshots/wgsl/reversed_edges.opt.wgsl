struct VertexOutput {
  @location(0) vTexCoord: vec2<f32>,
  @builtin(position) gl_Position: vec4<f32>,
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
  let smoothed_t = clamp((vTexCoord.x - 0.85) / (0.4 - 0.85), f32(0.0), f32(1.0));
  let composite = vec4<f32>(smoothed_t * smoothed_t * (3.0 - 2.0 * smoothed_t), smoothstep(0.4, 0.85, vTexCoord.x), min(max(vTexCoord.x, 0.75), 0.25), clamp(vTexCoord.x, 0.25, 0.75));
  fragColor = composite;
  return fragColor;
}
