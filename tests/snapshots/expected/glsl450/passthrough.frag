#version 450

layout(binding = 1) uniform sampler2D source;

layout(location = 0) out vec4 fragColor;
layout(location = 0) in vec2 vTexCoord;

void main()
{
    fragColor = texture(source, vTexCoord);
}

