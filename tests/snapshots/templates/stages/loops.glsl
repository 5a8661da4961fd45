// Covers: a loop with break and continue and a loop-carried value; a vector modified by component in a loop left by a break, read after it.

#ifdef CRT_FORM_loops_carried
vec3 loops_carried(vec3 color, CrtFrag frag) {
    float sum = 0.0;
    for (int k = 0; k < loopCount; ++k) {
        if (k == 1) continue;
        sum += color.r * float(k) * loopGain;
        if (sum > 2.0) break;
    }
    return color * (1.0 + 0.1 * sum);
}
#endif

#ifdef CRT_FORM_loops_component
// The shape that once left the inserted value scoped inside the WGSL loop: written in the body,
// the loop left by a break, the vector read after it.
vec3 loops_component(vec3 color, CrtFrag frag) {
    vec4 s = vec4(color, 1.0);
    int k = 0;
    while (true) {
        s.y = color.g * loopGain + 0.01 * float(k);
        k++;
        if (k >= loopCount) break;
    }
    return s.xyz * s.w;
}
#endif
