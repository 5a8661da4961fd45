// Chromatic aberration. `color` is the centred sample, so green needs no extra texture read.

#ifdef CRT_FORM_aberration_pixels
vec3 aberration_pixels(vec3 color, vec2 uv) {
    vec2 offset = vec2(aberration / outputSize.x, 0.0);
    return vec3(texture(source, uv + offset).r, color.g, texture(source, uv - offset).b);
}
#endif

#ifdef CRT_FORM_aberration_uv
vec3 aberration_uv(vec3 color, vec2 uv) {
    vec2 offset = vec2(rgbOffset, 0.0);
    return vec3(texture(source, uv + offset).r, color.g, texture(source, uv - offset).b);
}
#endif
