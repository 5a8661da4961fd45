#version 450

layout(binding = 1) uniform sampler2D source;

layout(location = 0) out vec4 fragColor;
layout(location = 0) in vec2 vTexCoord;

void main()
{
    vec4 c = texture(source, vTexCoord);
    fragColor = mix(clamp(c, vec4(-65504.0), vec4(65504.0)), vec4(0.0), isnan(c));
}

