// The composite is mostly in 0..1 with a modest bloom overshoot: clamping keeps midtones and lets
// highlights blow out, exactly like the swap chain's implicit clamp.
vec3 tonemap_saturate(vec3 color, CrtFrag frag) {
    return clamp(color, 0.0, 1.0);
}
