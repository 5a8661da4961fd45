// Double-precision vector helpers and GLSL-equivalent scalar functions for the reference renderer.
#pragma once

#include <algorithm>
#include <cmath>

namespace crtforge::reference {

struct Vec2 {
    double x = 0, y = 0;
};
struct Vec3 {
    double r = 0, g = 0, b = 0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline Vec3 operator*(Vec3 a, double s) { return {a.r * s, a.g * s, a.b * s}; }
inline Vec3 operator*(Vec3 a, Vec3 b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }

// GLSL's fract and floor-based mod (not C's fmod, which truncates).
inline double fract(double x) { return x - std::floor(x); }
inline double glsl_mod(double x, double y) { return x - y * std::floor(x / y); }
inline double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}
inline double mix(double a, double b, double t) { return a + (b - a) * t; }

}  // namespace crtforge::reference
