#version 330
#ifdef GL_ARB_shading_language_420pack
#extension GL_ARB_shading_language_420pack : require
#endif

layout(binding = 1) uniform sampler2D source;

layout(location = 0) out vec4 fragColor;
in vec2 vTexCoord;

void main()
{
    fragColor = texture(source, vTexCoord);
}

