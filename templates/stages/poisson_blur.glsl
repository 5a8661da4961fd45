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
