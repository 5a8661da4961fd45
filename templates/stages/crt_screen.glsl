// Super Win the Game's curved screen. The document draws the picture on a 3D mesh of a curved
// screen and looks at it with a perspective camera; here the mesh is the analytic surface it
// models: a cap of a sphere of radius R = 1 / screenCurvature (in half heights) touching the
// plane z = 0 at the screen's centre, its centre of curvature at (0, 0, R) behind the glass, so the
// glass bulges toward the camera at (0, 0, -cameraDistance). The viewport has the screen's aspect.

// The screen coordinate (0..1) seen at a viewport coordinate; far outside 0..1 when the ray misses.
vec2 crt_screen_perspective(vec2 uv) {
    float aspect = outputSize.x / outputSize.y;
    vec2 flat_point = (uv * 2.0 - 1.0) * vec2(aspect, 1.0) / screenZoom;
    vec2 hit = flat_point;
    if (screenCurvature > 0.0) {
        float radius = 1.0 / screenCurvature;  // guarded: screenCurvature > 0 here
        vec3 dir = vec3(flat_point, cameraDistance);       // camera -> the flat screen point
        vec3 oc = vec3(0.0, 0.0, -cameraDistance - radius);  // camera - sphere centre
        float a = dot(dir, dir);
        float b = dot(dir, oc);                             // negative: the sphere is ahead
        float c = dot(oc, oc) - radius * radius;            // = D^2 + 2 D R > 0: the camera is outside
        float disc = b * b - a * c;
        if (disc < 0.0) return vec2(-10.0);                 // the ray passes the glass by
        // The nearer root t = (-b - sqrt(disc)) / a, written c / (-b + sqrt(disc)): no cancellation.
        float t = c / (-b + sqrt(disc));
        hit = t * dir.xy;
    }
    return hit / vec2(aspect, 1.0) * 0.5 + 0.5;
}

// Off the glass: the border, with the picture mirrored across the nearest edge fading out over
// reflectionWidth and tapering toward the corners, where the mirror image folds over itself.
vec3 crt_screen_border(vec3 color, CrtFrag frag) {
    vec2 uv = frag.uv;
    vec2 over = max(-uv, uv - 1.0);  // how far outside, per axis (negative inside)
    float distance = max(over.x, over.y);
    if (distance <= 0.0) return color;
    if (reflectionStrength <= 0.0 || distance >= reflectionWidth) return borderColor;
    vec2 mirrored = mix(uv, mix(-uv, 2.0 - uv, step(0.5, uv)), vec2(greaterThan(over, vec2(0.0))));
    vec3 picture = textureLod(source, crt_source_uv(mirrored), 0.0).rgb;
    float along = over.y > over.x ? min(uv.x, 1.0 - uv.x) : min(uv.y, 1.0 - uv.y);
    float taper = smoothstep(0.0, reflectionTaper, along);
    float fade = 1.0 - distance / reflectionWidth;
    return borderColor + picture * (reflectionStrength * fade * taper);
}
