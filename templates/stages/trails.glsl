// Super Win the Game's trails. `feedback` is the previous frame's final NES-space image, the size
// of this pass's output, so one of its texels is one output pixel. On a black background a moving
// sprite leaves a trail that decays by trailBlend * trailTint per frame (the horizontal blur
// leaves a uniform row as it is); a still picture stays as it is except for a little fuzz at edges.
vec3 trails_persistence(vec3 color, CrtFrag frag) {
    vec2 texel = vec2(1.0 / outputSize.x, 0.0);
    vec3 previous = (textureLod(feedback, frag.uv - texel, 0.0).rgb + textureLod(feedback, frag.uv, 0.0).rgb +
                     textureLod(feedback, frag.uv + texel, 0.0).rgb) / 3.0;
    previous *= trailTint;
    return mix(color, max(color, previous), trailBlend);
}
