// Super Win the Game's RGB mask: a cycle of pure red, green and blue along each row, one step later
// on every next row (the colour subcarrier's phase advances a third of a cycle per line). Times 3
// so a grey stays as bright on average.
vec3 ntsc_mask_cycle(float phase) {
    float i = mod(phase, 3.0);
    return vec3(i == 0.0, i == 1.0, i == 2.0) * 3.0;
}

float ntsc_mask_phase(CrtFrag frag) { return floor(frag.pixel.x) + floor(frag.pixel.y); }

#ifdef CRT_FORM_ntsc_mask_alternate
// The frame's parity in integers, exact at any frame count.
vec3 ntsc_mask_alternate(vec3 color, CrtFrag frag) {
    vec3 mask = ntsc_mask_cycle(ntsc_mask_phase(frag) + float(frameCount % 2));
    return color * mix(vec3(1.0), mask, ntscStrength);
}
#endif

#ifdef CRT_FORM_ntsc_mask_blend
vec3 ntsc_mask_blend(vec3 color, CrtFrag frag) {
    float phase = ntsc_mask_phase(frag);
    vec3 mask = 0.5 * (ntsc_mask_cycle(phase) + ntsc_mask_cycle(phase + 1.0));
    return color * mix(vec3(1.0), mask, ntscStrength);
}
#endif
