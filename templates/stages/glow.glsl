// CRT effect pulsing glow. `time` is seconds from the host; hosts whose clock wraps must keep
// time * pulseSpeed continuous (a jump shows as the wave skipping).
vec3 glow_pulse(vec3 color, CrtFrag frag) {
    return color * (1.0 + pulseIntensity * cos(frag.pixel.x / pulseWidth + time * pulseSpeed));
}
