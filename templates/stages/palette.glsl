// Colour palette reduction (Retro CRT Effects, shaders/post/palette.frag).

// The article's 4x4 Bayer threshold at the pixel, bayer[x][y] of its column-major mat4
// (0, 8, 2, 10 / 12, 4, 14, 6 / 3, 11, 1, 9 / 15, 7, 13, 5) / 16, indexed by
// ivec2(mod(gl_FragCoord.xy, 4.0)). gl_FragCoord in its OpenGL counts rows from the bottom, so the
// row here does too. Written as the recursive Bayer construction, M4(x, y) = 4 M2(x mod 2, y mod 2)
// + M2(x / 2, y / 2) with M2(a, b) = 2 |a - b| + a: the same sixteen values, with no matrix indexed
// at run time (which not every target can express).
float palette_bayer(CrtFrag frag) {
    vec2 pos = mod(floor(vec2(frag.pixel.x, outputSize.y - frag.pixel.y)), 4.0);
    vec2 low = mod(pos, 2.0);
    vec2 high = floor(pos * 0.5);
    float fine = 2.0 * abs(low.x - low.y) + low.x;
    float coarse = 2.0 * abs(high.x - high.y) + high.x;
    return (4.0 * fine + coarse) / 16.0;
}

vec3 palette_dither(vec3 color, CrtFrag frag, float levels) {
    if (!paletteDither) return color;
    return color + (palette_bayer(frag) - 0.5) / levels;
}

#ifdef CRT_FORM_palette_levels
vec3 palette_levels(vec3 color, CrtFrag frag) {
    float levels = float(paletteSize) / 4.0;  // "Rough approximation"
    color = palette_dither(color, frag, levels);
    return floor(color * levels + 0.5) / levels;
}
#endif

#ifdef CRT_FORM_palette_nearest
// The palette is a row of texels (e.g. the Atari NTSC palette LUT, 128 x 1), read exactly.
vec3 palette_nearest(vec3 color, CrtFrag frag) {
    color = palette_dither(color, frag, float(paletteSize) / 4.0);
    int count = textureSize(palette, 0).x;
    vec3 best = texelFetch(palette, ivec2(0, 0), 0).rgb;
    vec3 d = best - color;
    float bestDistance = dot(d, d);
    for (int i = 1; i < count; ++i) {
        vec3 candidate = texelFetch(palette, ivec2(i, 0), 0).rgb;
        d = candidate - color;
        float distance = dot(d, d);
        if (distance < bestDistance) {
            bestDistance = distance;
            best = candidate;
        }
    }
    return best;
}
#endif
