// Covers: vector shuffles, composite construct/extract/insert (warp) and early returns, a bezel-style branch (finish).
vec2 bend_swizzle(vec2 uv) {
    vec4 q = vec4(uv, uv.yx) * 2.0 - 1.0;
    q.zw *= 1.0 + bendAmount * dot(q.xy, q.xy);
    return q.wz * 0.5 + 0.5;
}

vec3 bend_edge(vec3 color, CrtFrag frag) {
    if (frag.uv.x < 0.0 || frag.uv.x > 1.0) return edgeColor;
    if (frag.uv.y < 0.0 || frag.uv.y > 1.0) return edgeColor.bgr;
    return color;
}
