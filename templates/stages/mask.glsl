// Phosphor masks. The mask follows output pixels (not warped ones), as the CRT-effect document
// requires: curvature runs first so the mask stays aligned to the screen.

#ifdef CRT_FORM_mask_shadow
vec3 mask_shadow(vec3 color, CrtFrag frag) {
    vec2 coord = frag.pixel / maskSize;
    vec2 subcoord = coord * vec2(3.0, 1.0);
    // Stagger every other column of cells by half a cell in y.
    vec2 cellOffset = vec2(0.0, fract(floor(coord.x) * 0.5));
    // Which channel this sub-column lights (0 = R, 1 = G, 2 = B); x3 keeps brightness.
    float ind = mod(floor(subcoord.x), 3.0);
    vec3 maskColor = vec3(ind == 0.0, ind == 1.0, ind == 2.0) * 3.0;
    // Soft borders: squared falloff from the sub-cell centre.
    vec2 cellUV = fract(subcoord + cellOffset) * 2.0 - 1.0;
    vec2 border = 1.0 - cellUV * cellUV * maskBorder;
    maskColor *= border.x * border.y;
    return color * (1.0 + (maskColor - 1.0) * maskIntensity);
}

// "Sample texture at warped UV (quantized to mask cell center for shadow mask)", "one sample per
// cell": the cell is the mask's own, in screen pixels (stagger included), and its centre is warped
// as the fragment was, so every pixel of a cell reads the same source point.
vec2 mask_shadow_cell_uv(vec2 uv, CrtFrag frag) {
    if (!maskQuantize) return uv;
    vec2 coord = frag.pixel / maskSize;
    float stagger = fract(floor(coord.x) * 0.5);
    vec2 cell = vec2(floor(coord.x) + 0.5, floor(coord.y + stagger) - stagger + 0.5);
    return crt_warp(cell * maskSize / outputSize);
}
#endif

#ifdef CRT_FORM_mask_grille
vec3 mask_grille(vec3 color, CrtFrag frag) {
    float stripe = fract(frag.pixel.x / maskSize * 0.333333);
    float ind = floor(stripe * 3.0);
    vec3 maskColor = vec3(ind == 0.0, ind == 1.0, ind == 2.0) * 3.0;
    // Vertical gap between stripes.
    float gap = 1.0 - pow(abs(fract(stripe * 3.0) * 2.0 - 1.0), 2.0) * maskBorder;
    maskColor *= gap;
    return color * (1.0 + (maskColor - 1.0) * maskIntensity);
}
#endif

#ifdef CRT_FORM_mask_atari_grille
// iResolution is the input texture size: one source column per phosphor colour.
vec3 mask_atari_grille(vec3 color, CrtFrag frag) {
    float mask = mod(floor(frag.uv.x * sourceSize.x), 3.0);
    vec3 maskColor = vec3(mask == 0.0 ? 1.0 : maskDim,
                          mask == 1.0 ? 1.0 : maskDim,
                          mask == 2.0 ? 1.0 : maskDim);
    return color * mix(vec3(1.0), maskColor, maskBlend);
}
#endif

#ifdef CRT_FORM_mask_slot
vec3 mask_slot(vec3 color, CrtFrag frag) {
    int col = int(mod(frag.pixel.x, 3.0));
    vec3 mask = vec3(1.0);
    if (col == 0) mask = vec3(1.0, maskDim, maskDim);
    if (col == 1) mask = vec3(maskDim, 1.0, maskDim);
    if (col == 2) mask = vec3(maskDim, maskDim, 1.0);
    return color * mask;
}
#endif
