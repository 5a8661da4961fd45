// Scanlines. Each form is the formula of one source document, kept term for term.

#ifdef CRT_FORM_scanlines_period
// WebGPU post pass: the frequency is tied to the output height so the bands stay
// scanlinePeriodPx device pixels apart at any size.
vec3 scanlines_period(vec3 color, CrtFrag frag) {
    float f = outputSize.y * (2.0 * PI / scanlinePeriodPx);
    float scan = 1.0 - scanlineStrength * (0.5 + 0.5 * sin(frag.uv.y * f));
    return color * scan;
}
#endif

#ifdef CRT_FORM_scanlines_period_filtered
// The same bands averaged over the pixel's height: a pixel spans h = pi / scanlinePeriodPx of
// phase either side of its centre, and the mean of sin over it is the centre's sin * sin(h) / h.
vec3 scanlines_period_filtered(vec3 color, CrtFrag frag) {
    float h = PI / scanlinePeriodPx;
    float f = outputSize.y * 2.0 * h;
    float scan = 1.0 - scanlineStrength * (0.5 + 0.5 * (sin(h) / h) * sin(frag.uv.y * f));
    return color * scan;
}
#endif

#ifdef CRT_FORM_scanlines_atari
// Retro CRT Effects: iResolution is the input texture's size, so lines follow source rows and
// bend with the curvature (the warped uv is used).
vec3 scanlines_atari(vec3 color, CrtFrag frag) {
    float scanline = sin(frag.uv.y * sourceSize.y * 3.14159) * 0.5 + 0.5;
    scanline = pow(scanline, scanlineSharpness);
    return color * mix(1.0, scanline, scanlineIntensity);
}
#endif

#ifdef CRT_FORM_scanlines_crt_effect
// CRT effect: screen-pixel lines; bright pixels (Rec. 601 luma) resist the darkening.
vec3 scanlines_crt_effect(vec3 color, CrtFrag frag) {
    float scanline = sin(frag.pixel.y * PI / scanlineSpacing) * 0.5 + 0.5;
    scanline = pow(scanline, scanlineSharpness);
    float bright = dot(color, vec3(0.299, 0.587, 0.114));
    return color * mix(1.0 - scanlineIntensity, 1.0, scanline * mix(1.0, bright, scanlineBrightBoost));
}
#endif

#ifdef CRT_FORM_scanlines_quiet_frame
// Quiet Frame: at pixel centres sin((k + 0.5) * pi) = +-1, so rows alternate full and dimmed.
vec3 scanlines_quiet_frame(vec3 color, CrtFrag frag) {
    float s = sin(frag.pixel.y * 3.14159);
    return color * (1.0 - scanlineIntensity * 0.5 * (1.0 - s));
}
#endif

#ifdef CRT_FORM_scanlines_quiet_frame_filtered
// The same over the pixel's height: the mean of sin(c*y) over [y - 0.5, y + 0.5] is
// sin(c*y) * sin(c/2) / (c/2), and the formula is linear in it.
vec3 scanlines_quiet_frame_filtered(vec3 color, CrtFrag frag) {
    float s = sin(frag.pixel.y * 3.14159) * (sin(1.570795) / 1.570795);
    return color * (1.0 - scanlineIntensity * 0.5 * (1.0 - s));
}
#endif

#ifdef CRT_FORM_scanlines_crt_effect_filtered
// The same over the pixel's height: the mean of pow(sin(y*PI/spacing)*0.5+0.5, sharpness) over
// [y - 0.5, y + 0.5] by 4-point Gauss-Legendre (nodes +-0.5*0.33998, +-0.5*0.86114; weights
// halved to sum to 1). Written out: Godot 3's language has no comma operator for a loop.
float scanlines_crt_effect_at(float y) {
    return pow(sin(y * PI / scanlineSpacing) * 0.5 + 0.5, scanlineSharpness);
}

vec3 scanlines_crt_effect_filtered(vec3 color, CrtFrag frag) {
    float y = frag.pixel.y;
    float scanline = 0.32607257743127305 * (scanlines_crt_effect_at(y - 0.16999052179242813) + scanlines_crt_effect_at(y + 0.16999052179242813))
                   + 0.17392742256872690 * (scanlines_crt_effect_at(y - 0.43056815579702629) + scanlines_crt_effect_at(y + 0.43056815579702629));
    float bright = dot(color, vec3(0.299, 0.587, 0.114));
    return color * mix(1.0 - scanlineIntensity, 1.0, scanline * mix(1.0, bright, scanlineBrightBoost));
}
#endif
