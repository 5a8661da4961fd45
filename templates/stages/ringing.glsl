// Super Win the Game's edge ringing: alternating bright and dark bands beside high-contrast edges.
// The weights 1, -1/2, 1/3, ... fall with distance and alternate in sign. Rec. 601 luma, as NTSC.
float ringing_luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }

vec3 ringing_bands(vec3 color, vec2 uv) {
    float center = ringing_luma(color);
    float ring = 0.0;
    for (int k = 1; k <= ringTaps; ++k) {
        vec2 offset = vec2(float(k) / sourceSize.x, 0.0);
        float side = 0.5 * (ringing_luma(textureLod(source, uv - offset, 0.0).rgb) +
                            ringing_luma(textureLod(source, uv + offset, 0.0).rgb));
        float sign = (k % 2 == 1) ? 1.0 : -1.0;
        ring += sign / float(k) * (side - center);
    }
    return color * max(1.0 + ringStrength * ring, 0.0);
}
