// Super Win the Game's colour grade through a 32^3 lookup table stored as 1024 x 32: slice b (blue)
// occupies x = 32 b .. 32 b + 31, red runs along x within the slice, green along y. Bilinear
// within the two blue slices around the colour (the LUT is sampled with a linear filter), then
// mixed between them: a trilinear lookup.
vec3 color_grade_lut32(vec3 color, CrtFrag frag) {
    vec3 c = clamp(color, 0.0, 1.0) * 31.0;
    float slice = floor(c.b);
    float next = min(slice + 1.0, 31.0);
    float y = (c.g + 0.5) / 32.0;
    vec3 low = textureLod(grade, vec2((slice * 32.0 + c.r + 0.5) / 1024.0, y), 0.0).rgb;
    vec3 high = textureLod(grade, vec2((next * 32.0 + c.r + 0.5) / 1024.0, y), 0.0).rgb;
    return mix(color, mix(low, high, c.b - slice), gradeStrength);
}
