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
// The palette is row 0 of its texture (e.g. the Atari NTSC palette LUT, 128 colours), read exactly.
// The first entry at the smallest squared RGB distance wins, as a search of every entry finds it.
void palette_consider(int index, vec3 color, inout int best, inout float bestDistance) {
    vec3 d = texelFetch(palette, ivec2(index, 0), 0).rgb - color;
    float distance = dot(d, d);
    if (distance < bestDistance) {
        bestDistance = distance;
        best = index;
    }
}

// A palette with rows below it lists, per cell of a 16^3 grid over RGB [-1/16, 17/16], the few
// entries that can be nearest in that cell (generator/palette_cells.hpp: the same three numbers):
// a header texel per cell (first list texel in R and G, bytes; list texels in B), then four
// ascending indices per list texel. A colour off the grid (or not a number) searches them all.
int palette_byte(float v) {
    return int(v * 255.0 + 0.5);
}

vec3 palette_nearest(vec3 color, CrtFrag frag) {
    color = palette_dither(color, frag, float(paletteSize) / 4.0);
    ivec2 size = textureSize(palette, 0);
    int best = 0;
    float bestDistance = 16.0;  // a colour on the grid is within 3.4 (squared) of every entry: the first listed wins
    vec3 cell = floor((color + 0.0625) * (16.0 / 1.125));
    if (size.y > 1 && all(greaterThanEqual(cell, vec3(0.0))) && all(lessThan(cell, vec3(16.0)))) {
        int c = int(cell.x) + 16 * int(cell.y) + 256 * int(cell.z);
        vec4 head = texelFetch(palette, ivec2(c - size.x * (c / size.x), 1 + c / size.x), 0);
        int first = palette_byte(head.r) + 256 * palette_byte(head.g);
        int texels = palette_byte(head.b);
        int listRow = 1 + (4096 + size.x - 1) / size.x;
        for (int t = first; t < first + texels; ++t) {
            vec4 four = texelFetch(palette, ivec2(t - size.x * (t / size.x), listRow + t / size.x), 0);
            palette_consider(palette_byte(four.r), color, best, bestDistance);
            palette_consider(palette_byte(four.g), color, best, bestDistance);
            palette_consider(palette_byte(four.b), color, best, bestDistance);
            palette_consider(palette_byte(four.a), color, best, bestDistance);
        }
    } else {
        // Entry 0 first, whatever its distance (a colour that is not a number keeps it).
        vec3 d = texelFetch(palette, ivec2(0, 0), 0).rgb - color;
        bestDistance = dot(d, d);
        for (int i = 1; i < size.x; ++i) palette_consider(i, color, best, bestDistance);
    }
    return texelFetch(palette, ivec2(best, 0), 0).rgb;
}
#endif
