#version 300 es

out vec2 vTexCoord;

void main()
{
    vec2 uv = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    vTexCoord = uv;
    gl_Position = vec4((uv * 2.0) - vec2(1.0), 0.0, 1.0);
    gl_Position.y = -gl_Position.y;
}

