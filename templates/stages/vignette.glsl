// Vignettes.

#ifdef CRT_FORM_vignette_atari
// Uses the unwarped coordinate. For strength > 0.5 the corners go below zero, as in the article;
// the output's clamp (or the curvature bezel) hides it.
vec3 vignette_atari(vec3 color, CrtFrag frag) {
    vec2 vigUV = frag.screenUv * 2.0 - 1.0;
    float vignette = 1.0 - dot(vigUV, vigUV) * vignetteStrength;
    return color * vignette;
}
#endif

#ifdef CRT_FORM_vignette_crt_effect
// Separable x/y falloff on the warped, centred coordinate.
vec3 vignette_crt_effect(vec3 color, CrtFrag frag) {
    vec2 edge = max(1.0 - frag.centered * frag.centered, 0.0);
    float vignette = pow(edge.x * edge.y, vignetteExponent);
    return color * vignette;
}
#endif

#ifdef CRT_FORM_vignette_quiet_frame
// The article writes smoothstep(0.85, 0.4, r). GLSL (and WGSL) leave reversed edges undefined,
// so the identical 1 - smoothstep(0.4, 0.85, r) is used: s(1 - t) = 1 - s(t) for t(3 - 2t)t.
vec3 vignette_quiet_frame(vec3 color, CrtFrag frag) {
    vec2 d = frag.uv - 0.5;
    float r = length(d) * vignetteScale;
    return color * (1.0 - smoothstep(0.4, 0.85, r));
}
#endif
