// Covers: several texture taps (cross) and derivatives dFdx, dFdy and fwidth (footprint).

#ifdef CRT_FORM_taps_cross
vec3 taps_cross(vec3 color, vec2 uv) {
    vec3 sum = texture(source, uv + vec2(tapOffset, 0.0)).rgb;
    sum += texture(source, uv - vec2(tapOffset, 0.0)).rgb;
    sum += texture(source, uv + vec2(0.0, tapOffset)).rgb;
    sum += texture(source, uv - vec2(0.0, tapOffset)).rgb;
    return mix(color, sum * 0.25, tapMix);
}
#endif

#ifdef CRT_FORM_taps_footprint
vec3 taps_footprint(vec3 color, vec2 uv) {
    vec2 stride = vec2(dFdx(uv.x), dFdy(uv.y)) * 4.0;
    float weight = clamp(length(fwidth(uv)) * 100.0, 0.0, 1.0);
    return mix(color, texture(source, uv + stride).rgb, tapMix * weight);
}
#endif
