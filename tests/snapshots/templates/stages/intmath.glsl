// Covers: int / and % with negative operands (a negative constant divisor too) and GLSL mod() of floats with a negative divisor.
vec3 intmath_bands(vec3 color, CrtFrag frag) {
    int x = int(frag.pixel.x) - bandShift;
    int q = x / bandWidth;
    int r = x % bandWidth;
    int n = x / -3;
    float m = mod(frag.pixel.y - 4.0, -bandPeriod);
    return color * (1.0 + 0.02 * float(q) + 0.01 * float(r) - 0.001 * float(n) + 0.03 * m);
}
