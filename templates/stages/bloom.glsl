// Quiet Frame cheap_bloom(): pixel art has hard edges, so two taps next to the centre are enough
// to make bright pixels bleed into dark neighbours. The result may exceed 1.0 (HDR).
vec3 bloom_two_tap(vec3 color, vec2 uv) {
    vec3 cx = texture(source, uv + vec2(bloomOffset, 0.0)).rgb;
    vec3 cy = texture(source, uv + vec2(0.0, bloomOffset)).rgb;
    vec3 surrounding = (cx + cy) * 0.5;
    return color + max(surrounding - bloomThreshold, 0.0) * bloomStrength;
}
