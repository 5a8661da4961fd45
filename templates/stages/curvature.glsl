// Barrel distortion (screen curvature) and the bezel clamp.

#ifdef CRT_FORM_curvature_atari
// Retro CRT Effects, crt.frag distort(): scale the -1..1 coordinate by 1 + curvature * r^2.
vec2 curvature_atari(vec2 uv) {
    uv = uv * 2.0 - 1.0;
    float r2 = dot(uv, uv);
    uv *= 1.0 + curvature * r2;
    return uv * 0.5 + 0.5;
}
#endif

#ifdef CRT_FORM_curvature_crt_effect
// CRT effect (XorDev): the factor is 1 on the unit circle (r^2 = 1), so edge midpoints stay put,
// the centre is magnified and the corners fall outside the screen.
vec2 curvature_crt_effect(vec2 uv) {
    vec2 centered = uv * 2.0 - 1.0;
    centered *= 1.0 + (dot(centered, centered) - 1.0) * curvature;
    return centered * 0.5 + 0.5;
}
#endif

#ifdef CRT_FORM_curvature_quiet_frame
// Quiet Frame barrel(): r is measured in 0..0.5 units, so the same amount bends less than atari.
vec2 curvature_quiet_frame(vec2 uv) {
    vec2 c = uv - 0.5;
    float r2 = dot(c, c);
    c *= 1.0 + r2 * curvature;
    return c + 0.5;
}
#endif

// Last in the pass order: everything the warp pushed off the screen shows the bezel. The documents
// test strictly (uv < 0 || uv > 1), so the exact edge still shows the image. Written with any()
// rather than || so no target gets a chain of short-circuit branches.
bool curvature_outside(CrtFrag frag) {
    return any(bvec4(lessThan(frag.uv, vec2(0.0)), greaterThan(frag.uv, vec2(1.0))));
}

vec3 curvature_bezel(vec3 color, CrtFrag frag) {
    return curvature_outside(frag) ? bezelColor : color;
}

// The bezel's alpha: Retro CRT Effects' crt.frag writes vec4(0.0) outside (bezelAlpha = 0).
float curvature_bezel_alpha(float alpha, CrtFrag frag) {
    return curvature_outside(frag) ? bezelAlpha : alpha;
}
