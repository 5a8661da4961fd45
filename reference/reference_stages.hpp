// The reference model of each stage, one function per documented formula. Each reads its params by
// the spec's names; the pipeline (reference_renderer.cpp) calls them in the documented pass order.
#pragma once

#include <map>
#include <string>

#include "crtforge/value.hpp"
#include "reference/reference_math.hpp"
#include "reference/reference_sampler.hpp"

namespace crtforge::reference {

class Params {
public:
    explicit Params(const std::map<std::string, Value>& values) : values_(values) {}
    double num(const std::string& name) const;       // float or int param
    bool flag(const std::string& name) const;
    Vec3 color(const std::string& name) const;

private:
    const std::map<std::string, Value>& values_;
};

// What every stage may read about the fragment being shaded (cf. the CRT-effect document's
// "pixel", "uv" and "centered").
struct Fragment {
    Vec2 screen_uv;   // unwarped 0..1
    Vec2 pixel;       // output pixel coordinate, centres at +0.5
    Vec2 uv;          // after curvature
    Vec2 centered;    // uv * 2 - 1
    Vec2 output_size, source_size;
    double time = 0;
};

// Each returns false when it has no model for the requested form.
bool warp_curvature(const std::string& form, const Params& p, Vec2& uv);
bool shadow_cell_uv(const Params& p, const Fragment& f, Vec2& sample_uv);
bool fetch_aberration(const std::string& form, const Params& p, const Sampler& tex, const Fragment& f,
                      Vec2 sample_uv, Vec3& color);
void fetch_bloom(const Params& p, const Sampler& tex, Vec2 sample_uv, Vec3& color);
void tonemap_saturate(Vec3& color);
bool apply_scanlines(const std::string& form, const Params& p, const Fragment& f, Vec3& color);
bool apply_mask(const std::string& form, const Params& p, const Fragment& f, Vec3& color);
void apply_glow(const Params& p, const Fragment& f, Vec3& color);
bool apply_vignette(const std::string& form, const Params& p, const Fragment& f, Vec3& color);
void apply_bezel(const Params& p, const Fragment& f, Vec3& color);

}  // namespace crtforge::reference
