// Covers: smoothstep as the generator accepts it (reversed constant edges are refused: template_lint),
// clamp with reversed constant edges, and a baked bool branch folded by the optimiser.

#ifdef CRT_FORM_shape_radial
vec3 shape_radial(vec3 color, CrtFrag frag) {
    float v = 1.0 - smoothstep(0.3, 0.9, length(frag.centered) * shapeScale);
    if (shapeInvert) v = 1.0 - v;
    return color * v;
}
#endif

#ifdef CRT_FORM_shape_box
vec3 shape_box(vec3 color, CrtFrag frag) {
    vec2 d = abs(frag.centered) * shapeScale;
    float v = clamp(1.5 - max(d.x, d.y), 0.8, 0.2);
    if (shapeInvert) v = 1.0 - v;
    return color * v;
}
#endif
