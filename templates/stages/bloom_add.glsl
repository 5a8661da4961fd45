// Super Win the Game adds the square of the blurred image, so only bright areas glow noticeably.
vec3 bloom_add_squared(vec3 color, CrtFrag frag) {
    vec3 glow = textureLod(bloom, frag.uv, 0.0).rgb;
    return color + glow * glow * bloomGain;
}
