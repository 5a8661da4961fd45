#version 330
#ifdef GL_ARB_shading_language_420pack
#extension GL_ARB_shading_language_420pack : require
#endif

layout(binding = 1) uniform sampler2D source;

layout(location = 0) out vec4 fragColor;
in vec2 vTexCoord;

void main()
{
    vec4 _39 = texture(source, vTexCoord);
    vec4 _47 = clamp(_39, vec4(-65504.0), vec4(65504.0));
    bvec4 _49 = isnan(_39);
    fragColor = vec4(_49.x ? vec4(0.0).x : _47.x, _49.y ? vec4(0.0).y : _47.y, _49.z ? vec4(0.0).z : _47.z, _49.w ? vec4(0.0).w : _47.w);
}

