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
#endif

#if defined(CRT_FORM_mask_shadow) || defined(CRT_FORM_mask_shadow_filtered)

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

// The filtered tiers: each mask's multiplier averaged over the output pixel's square [x-0.5, x+0.5]
// x [y-0.5, y+0.5], computed exactly. Both profiles are the quadratic 1 - border*(2t-1)^2 over a
// stripe or cell (t in 0..1), whose integral from 0 to t is H(t) below; the pixel is cut where it
// crosses stripe edges (sub-columns are at least 2/3 px wide, so at most three pieces).
#if defined(CRT_FORM_mask_shadow_filtered) || defined(CRT_FORM_mask_grille_filtered)
float mask_profile_integral(float t) {
    float u = 2.0 * t - 1.0;
    return t - maskBorder * (u * u * u + 1.0) / 6.0;
}

// The integral of the periodic profile (period 1) from a to b (0 <= b - a <= 1), in periods.
float mask_profile_span(float a, float b) {
    float whole = floor(a);
    a -= whole;
    b -= whole;
    float full = mask_profile_integral(1.0);
    float upper = b >= 1.0 ? full + mask_profile_integral(b - 1.0) : mask_profile_integral(b);
    return upper - mask_profile_integral(a);
}

// Per channel, the integral over [x0, x1] (the pixel's width) of (lit stripe) x (stripe profile) x
// rows, on stripe number `stripe` of `width` px cycling R, G, B; `rows` holds the shadow mask's rows
// averaged over the pixel's height for even and odd cell columns (1, 1 for the grille). Zero where
// the stripe misses the pixel.
vec3 mask_filtered_piece(float width, vec2 rows, float stripe, float x0, float x1) {
    float lo = max(x0, stripe * width);
    float hi = min(x1, (stripe + 1.0) * width);
    if (hi <= lo) return vec3(0.0);
    float across = mask_profile_span(lo / width - stripe, hi / width - stripe) * width;
    // `stripe` is a whole number: +0.5 keeps floor() off the exact multiple of 3, where a GPU's
    // division by reciprocal lands just below it (Mesa GLES does).
    float column = floor((stripe + 0.5) / 3.0);
    float channel = stripe - 3.0 * column;
    float odd = column - 2.0 * floor((column + 0.5) / 2.0);
    return vec3(channel == 0.0, channel == 1.0, channel == 2.0) * (across * mix(rows.x, rows.y, odd));
}

// The pixel's square cut into the stripes it crosses: stripes are counted from the first, not found
// again from each piece's start (rounding can leave that on the stripe before, and can make the
// first piece empty: hence four). Written out rather than looped: Godot's shading language has no
// comma operator for the loop's update that a loop-carried sum compiles to.
vec3 mask_filtered_sum(CrtFrag frag, float width, bool cellRows) {
    vec2 rows = vec2(1.0);
    if (cellRows) {
        // The rows' profile over the pixel's height; odd cell columns are staggered by half a cell.
        float y0 = (frag.pixel.y - 0.5) / maskSize;
        rows = vec2(mask_profile_span(y0, y0 + 1.0 / maskSize), mask_profile_span(y0 + 0.5, y0 + 0.5 + 1.0 / maskSize)) * maskSize;
    }
    float x0 = frag.pixel.x - 0.5;
    float x1 = frag.pixel.x + 0.5;
    float first = floor(x0 / width);
    return mask_filtered_piece(width, rows, first, x0, x1) + mask_filtered_piece(width, rows, first + 1.0, x0, x1) +
           mask_filtered_piece(width, rows, first + 2.0, x0, x1) + mask_filtered_piece(width, rows, first + 3.0, x0, x1);
}
#endif

#ifdef CRT_FORM_mask_shadow_filtered
vec3 mask_shadow_filtered(vec3 color, CrtFrag frag) {
    vec3 maskColor = mask_filtered_sum(frag, maskSize / 3.0, true) * 3.0;
    return color * (1.0 + (maskColor - 1.0) * maskIntensity);
}
#endif

#ifdef CRT_FORM_mask_grille_filtered
vec3 mask_grille_filtered(vec3 color, CrtFrag frag) {
    vec3 maskColor = mask_filtered_sum(frag, maskSize, false) * 3.0;
    return color * (1.0 + (maskColor - 1.0) * maskIntensity);
}
#endif
