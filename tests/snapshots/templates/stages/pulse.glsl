// Covers: the time builtin multiplied by an angular_speed uniform inside sin().
vec3 pulse_wave(vec3 color, CrtFrag frag) {
    return color * (1.0 + pulseDepth * sin(frag.pixel.y / pulseLength + time * pulseRate));
}
