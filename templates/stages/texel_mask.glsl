// Super Win the Game's scanline mask over the source texels. The mask's coordinate is pushed out
// toward the corners (pincushion) so the lines do not sit exactly on the texels: the document
// staggers them on purpose and counters part of the camera's barrel with it.
vec3 texel_mask_pincushion(vec3 color, CrtFrag frag) {
    vec2 c = frag.uv * 2.0 - 1.0;
    c *= 1.0 + maskPincushion * dot(c, c);
    vec2 f = fract(crt_source_uv(c * 0.5 + 0.5) * sourceSize);
    vec2 s = sin(f * PI);
    float rows = 1.0 - maskScanline * (1.0 - s.y * s.y);
    float columns = 1.0 - maskColumn * (1.0 - s.x * s.x);
    return color * (maskGain * rows * columns);
}
