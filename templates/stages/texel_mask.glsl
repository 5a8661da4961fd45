// Super Win the Game's scanline mask over the source texels. The mask's coordinate is pushed out
// toward the corners (pincushion) so the lines do not sit exactly on the texels: the document
// staggers them on purpose and counters part of the camera's barrel with it.
#ifdef CRT_FORM_texel_mask_pincushion
vec3 texel_mask_pincushion(vec3 color, CrtFrag frag) {
    vec2 c = frag.uv * 2.0 - 1.0;
    c *= 1.0 + maskPincushion * dot(c, c);
    vec2 f = fract(crt_source_uv(c * 0.5 + 0.5) * sourceSize);
    vec2 s = sin(f * PI);
    float rows = 1.0 - maskScanline * (1.0 - s.y * s.y);
    float columns = 1.0 - maskColumn * (1.0 - s.x * s.x);
    return color * (maskGain * rows * columns);
}
#endif

#ifdef CRT_FORM_texel_mask_pincushion_filtered
// The mask's coordinate in source texels at a (warped) screen coordinate, as the point form has it.
vec2 texel_mask_coord(vec2 uv) {
    vec2 c = uv * 2.0 - 1.0;
    c *= 1.0 + maskPincushion * dot(c, c);
    return crt_source_uv(c * 0.5 + 0.5) * sourceSize;
}

// sin(pi x) / (pi x) per component: even, 1 at 0 (the floor keeps 0 / 0 away).
vec4 texel_mask_sinc(vec4 x) {
    vec4 a = max(abs(x) * PI, vec4(1e-4));
    return sin(a) / a;
}

// The filtered tier: the mask averaged over the output pixel's square. Across the pixel the mask's
// coordinate is t + dx u + dy v (u, v in [-1/2, 1/2]; dx, dy its change over one pixel across and
// down, central differences through the warp). The mask is (1 - S/2 - S/2 cos 2 pi t.y) (1 - C/2 -
// C/2 cos 2 pi t.x), and the mean of cos(2 pi (p + a u + b v)) over the square is exactly
// cos(2 pi p) sinc(a) sinc(b); the cross term splits into cos(t.x + t.y) and cos(t.x - t.y).
vec3 texel_mask_pincushion_filtered(vec3 color, CrtFrag frag) {
    vec2 across = vec2(0.5 / outputSize.x, 0.0), down = vec2(0.0, 0.5 / outputSize.y);
    vec2 dx = texel_mask_coord(crt_warp(frag.screenUv + across)) - texel_mask_coord(crt_warp(frag.screenUv - across));
    vec2 dy = texel_mask_coord(crt_warp(frag.screenUv + down)) - texel_mask_coord(crt_warp(frag.screenUv - down));
    vec2 f = fract(texel_mask_coord(frag.uv));
    vec4 phase = cos(2.0 * PI * vec4(f.x, f.y, f.x + f.y, f.x - f.y));
    vec4 alone = texel_mask_sinc(vec4(dx.x, dy.x, dx.y, dy.y));
    vec4 cross = texel_mask_sinc(vec4(dx.x + dx.y, dy.x + dy.y, dx.x - dx.y, dy.x - dy.y));
    float columns = phase.x * alone.x * alone.y;  // the mean of cos 2 pi t.x
    float rows = phase.y * alone.z * alone.w;     // of cos 2 pi t.y
    float both = 0.5 * (phase.z * cross.x * cross.y + phase.w * cross.z * cross.w);
    float s = 0.5 * maskScanline, c = 0.5 * maskColumn;
    float mean = (1.0 - s) * (1.0 - c) - s * (1.0 - c) * rows - c * (1.0 - s) * columns + s * c * both;
    return color * (maskGain * mean);
}
#endif
