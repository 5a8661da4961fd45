// crtforge 0.1.0: preset edges-radial. shape (radial, not inverted) and the scrolling pulse
// Godot 3 canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.
// Screen mode: put it on a ColorRect covering the screen; it post-processes what is drawn below.
// Time: crtforge_pipeline.gd (the exported scene) sets hostTime every frame to the exact phase time,
// seconds reduced modulo 2*pi/pulseRate in double precision. Without it (hostTime < 0) the shader
// uses TIME, which wraps at rendering/limits/time/time_rollover_secs (3600 s by default): then pulseRate is
// rounded to a multiple of 2*pi/3600 rad/s so the motion stays continuous across the wrap, and the
// phase drifts from the exact one by up to t * pi/3600 rad at t seconds.
shader_type canvas_item;

// Godot 3's SCREEN_UV and SCREEN_TEXTURE count rows from the bottom of the screen.
vec2 crt_flip_y(vec2 p) { return vec2(p.x, 1.0 - p.y); }

// shape: Multiplier on the distance from the centre
uniform float shapeScale : hint_range(0.0, 2.0, 0.01) = 1.1;
// pulse: Amplitude of the wave
uniform float pulseDepth : hint_range(0.0, 0.2, 0.005) = 0.04;
// pulse: Phase speed of the wave (rad/s)
uniform float pulseRate : hint_range(0.5, 20.0, 0.5) = 5.0;
// Seconds reduced exactly by the host (crtforge_pipeline.gd); negative: use TIME.
uniform float hostTime = -1.0;

void fragment()
{
    vec4 c = vec4((textureLod(SCREEN_TEXTURE, crt_flip_y(crt_flip_y(SCREEN_UV)), 0.0).xyz * (1.0 - smoothstep(0.3, 0.9, length((crt_flip_y(SCREEN_UV) * 2.0) - vec2(1.0)) * shapeScale))) * (pulseDepth * sin((crt_flip_y(SCREEN_UV) * round(1.0 / SCREEN_PIXEL_SIZE)).y * 0.025 + ((max(hostTime, 0.0) + (1.0 - step(0.0, hostTime)) * (TIME * (round(pulseRate * 3600.0 / uintBitsToFloat(uint(1086918619))) * uintBitsToFloat(uint(1086918619)) / 3600.0) / pulseRate)) * pulseRate)) + 1.0), 1.0);
    vec4 clamped = clamp(c, vec4(-65504.0), vec4(65504.0));
    bvec4 cond = isnan(c);
    COLOR = vec4(cond.x ? 0.0 : clamped.x, cond.y ? 0.0 : clamped.y, cond.z ? 0.0 : clamped.z, cond.w ? 0.0 : clamped.w);
}

