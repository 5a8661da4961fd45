// Barrel distortion (screen curvature) and the bezel clamp.

#if defined(CRT_FORM_curvature_atari) || defined(CRT_FORM_curvature_atari_filtered)
// Retro CRT Effects, crt.frag distort(): scale the -1..1 coordinate by 1 + curvature * r^2.
vec2 curvature_atari(vec2 uv) {
    uv = uv * 2.0 - 1.0;
    float r2 = dot(uv, uv);
    uv *= 1.0 + curvature * r2;
    return uv * 0.5 + 0.5;
}
#endif

#if defined(CRT_FORM_curvature_crt_effect) || defined(CRT_FORM_curvature_crt_effect_filtered)
// CRT effect (XorDev): the factor is 1 on the unit circle (r^2 = 1), so edge midpoints stay put,
// the centre is magnified and the corners fall outside the screen.
vec2 curvature_crt_effect(vec2 uv) {
    vec2 centered = uv * 2.0 - 1.0;
    centered *= 1.0 + (dot(centered, centered) - 1.0) * curvature;
    return centered * 0.5 + 0.5;
}
#endif

#if defined(CRT_FORM_curvature_quiet_frame) || defined(CRT_FORM_curvature_quiet_frame_filtered)
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

#if defined(CRT_FORM_curvature_atari_filtered) || defined(CRT_FORM_curvature_crt_effect_filtered) || defined(CRT_FORM_curvature_quiet_frame_filtered)
// The edge anti-aliased bezel: the share of the pixel's square that lands on the screen, instead of
// whether its centre does. Across one pixel the warp is close to linear; its Jacobian is
// factor * I + 2 * curvature * c c^T for each form's centred coordinate c and scale factor, so the
// screen's edge x = 0 (or 1) is a straight line at |uv.x| / |grad uv.x| pixels, and a box filter
// over the pixel covers clamp(0.5 + distance, 0, 1) of it. At a corner the two shares multiply.
float curvature_coverage(CrtFrag frag, vec2 c, float factor) {
    float bend = 2.0 * curvature * c.x * c.y;
    vec2 rowX = vec2(factor + 2.0 * curvature * c.x * c.x, bend) / outputSize;
    vec2 rowY = vec2(bend, factor + 2.0 * curvature * c.y * c.y) / outputSize;
    vec2 rate = max(vec2(length(rowX), length(rowY)), vec2(1e-8));
    vec2 share = clamp(min(frag.uv, 1.0 - frag.uv) / rate + 0.5, 0.0, 1.0);
    return share.x * share.y;
}
#endif

#ifdef CRT_FORM_curvature_atari_filtered
float curvature_atari_coverage(CrtFrag frag) {
    vec2 c = frag.screenUv * 2.0 - 1.0;
    return curvature_coverage(frag, c, 1.0 + curvature * dot(c, c));
}
vec3 curvature_atari_bezel_filtered(vec3 color, CrtFrag frag) {
    return mix(bezelColor, color, curvature_atari_coverage(frag));
}
float curvature_atari_alpha_filtered(float alpha, CrtFrag frag) {
    return mix(bezelAlpha, alpha, curvature_atari_coverage(frag));
}
#endif

#ifdef CRT_FORM_curvature_crt_effect_filtered
float curvature_crt_effect_coverage(CrtFrag frag) {
    vec2 c = frag.screenUv * 2.0 - 1.0;
    return curvature_coverage(frag, c, 1.0 + (dot(c, c) - 1.0) * curvature);
}
vec3 curvature_crt_effect_bezel_filtered(vec3 color, CrtFrag frag) {
    return mix(bezelColor, color, curvature_crt_effect_coverage(frag));
}
float curvature_crt_effect_alpha_filtered(float alpha, CrtFrag frag) {
    return mix(bezelAlpha, alpha, curvature_crt_effect_coverage(frag));
}
#endif

#ifdef CRT_FORM_curvature_quiet_frame_filtered
float curvature_quiet_frame_coverage(CrtFrag frag) {
    vec2 c = frag.screenUv - 0.5;
    return curvature_coverage(frag, c, 1.0 + dot(c, c) * curvature);
}
vec3 curvature_quiet_frame_bezel_filtered(vec3 color, CrtFrag frag) {
    return mix(bezelColor, color, curvature_quiet_frame_coverage(frag));
}
float curvature_quiet_frame_alpha_filtered(float alpha, CrtFrag frag) {
    return mix(bezelAlpha, alpha, curvature_quiet_frame_coverage(frag));
}
#endif
