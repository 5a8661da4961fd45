#version 300 es
precision highp float;
precision highp int;

uniform highp sampler2D source;

layout(location = 0) out vec4 fragColor;
in vec2 vTexCoord;

void main()
{
    fragColor = texture(source, vTexCoord);
}

