// The blur of Super Win the Game's bloom: a 12-point Poisson disk (dart throwing with minimum
// distance 0.45 and a fixed seed, centred on its mean) plus the centre, equally weighted.
vec3 poisson_blur_tap(vec2 uv, vec2 offset, vec2 radius) { return textureLod(source, uv + offset * radius, 0.0).rgb; }

vec3 poisson_blur_disk(vec3 color, vec2 uv) {
    vec2 r = vec2(blurRadius) / outputSize;
    vec3 sum = color;
    sum += poisson_blur_tap(uv, vec2(0.3137, -0.3266), r);
    sum += poisson_blur_tap(uv, vec2(-0.8880, 0.3373), r);
    sum += poisson_blur_tap(uv, vec2(0.6626, 0.3968), r);
    sum += poisson_blur_tap(uv, vec2(-0.2229, -0.2067), r);
    sum += poisson_blur_tap(uv, vec2(0.4765, -0.8205), r);
    sum += poisson_blur_tap(uv, vec2(-0.2606, 0.7713), r);
    sum += poisson_blur_tap(uv, vec2(-0.2568, -0.7517), r);
    sum += poisson_blur_tap(uv, vec2(0.2967, 0.1267), r);
    sum += poisson_blur_tap(uv, vec2(-0.9739, -0.4774), r);
    sum += poisson_blur_tap(uv, vec2(-0.2619, 0.2653), r);
    sum += poisson_blur_tap(uv, vec2(0.8322, -0.0817), r);
    sum += poisson_blur_tap(uv, vec2(0.2822, 0.7673), r);
    return sum / 13.0;
}

#ifdef CRT_FORM_poisson_blur_poisson_filtered
// The filtered blur of a pass that shrinks its source: the blur averaged over the output pixel's
// square at 4 x 4 points (a 1/16 downsample read at 13 points aliases the texel pattern it shrinks
// into moire blotches of bloom). A pass that does not shrink reads as the point form. Written out,
// not looped: Godot 3's shading language has no comma operator for the update a loop-carried sum
// compiles to.
vec3 poisson_blur_quad_row(vec2 at, float spacing) {
    return poisson_blur_disk(textureLod(source, at + vec2(-1.5 * spacing, 0.0), 0.0).rgb, at + vec2(-1.5 * spacing, 0.0)) +
           poisson_blur_disk(textureLod(source, at + vec2(-0.5 * spacing, 0.0), 0.0).rgb, at + vec2(-0.5 * spacing, 0.0)) +
           poisson_blur_disk(textureLod(source, at + vec2(0.5 * spacing, 0.0), 0.0).rgb, at + vec2(0.5 * spacing, 0.0)) +
           poisson_blur_disk(textureLod(source, at + vec2(1.5 * spacing, 0.0), 0.0).rgb, at + vec2(1.5 * spacing, 0.0));
}

vec3 poisson_blur_filtered(vec3 color, vec2 uv) {
    if (sourceSize.x <= outputSize.x && sourceSize.y <= outputSize.y) return poisson_blur_disk(color, uv);
    vec2 spacing = 0.25 / outputSize;
    vec3 sum = poisson_blur_quad_row(uv + vec2(0.0, -1.5 * spacing.y), spacing.x) + poisson_blur_quad_row(uv + vec2(0.0, -0.5 * spacing.y), spacing.x) +
               poisson_blur_quad_row(uv + vec2(0.0, 0.5 * spacing.y), spacing.x) + poisson_blur_quad_row(uv + vec2(0.0, 1.5 * spacing.y), spacing.x);
    return sum / 16.0;
}
#endif
