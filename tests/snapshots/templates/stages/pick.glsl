// Covers: a switch on an int (fall-through case labels, default) and ternaries (one a plain select, one around a call).
vec3 pick_rows(vec3 color, CrtFrag frag) {
    vec3 tint;
    switch (int(frag.pixel.y) & 3) {
        case 0: tint = vec3(1.0, pickDim, pickDim); break;
        case 1:
        case 2: tint = vec3(pickDim, 1.0, pickDim); break;
        default: tint = vec3(pickDim, pickDim, 1.0); break;
    }
    float lift = frag.uv.x > 0.5 ? sqrt(max(color.g, 0.0)) : color.g * color.g;
    return color * tint + (frag.screenUv.y < 0.5 ? 0.01 : -0.01) * lift;
}
