// The per-pixel pipeline of the reference renderer, in the CRT-effect document's pass order:
// warp -> (cell-quantised) sample -> aberration/bloom taps -> tone-map -> scanlines -> mask ->
// glow -> vignette -> bezel.
#include "crtforge/reference/reference_renderer.hpp"

#include "crtforge/uniforms.hpp"
#include "reference/reference_stages.hpp"

namespace crtforge {

using namespace reference;

namespace {

struct StagePlan {
    std::string stage, form;
};

Diagnostic unmodelled(const StagePlan& s) {
    return make_error("the reference renderer has no model of stage '" + s.stage + "' form '" + s.form +
                      "'; add one in reference/reference_stages.cpp");
}

}  // namespace

Result<Image> render_reference(const ReferenceJob& job) {
    if (!job.variant || !job.variant->preset) return make_error("reference job without a variant");
    if (job.width <= 0 || job.height <= 0 || job.width > kMaxImageDimension || job.height > kMaxImageDimension)
        return make_error("output size " + std::to_string(job.width) + "x" + std::to_string(job.height) +
                          " is outside 1.." + std::to_string(kMaxImageDimension), {}, 0, "--size");
    if (job.input.width <= 0 || job.input.height <= 0 ||
        job.input.rgba.size() != static_cast<size_t>(job.input.width) * job.input.height * 4)
        return make_error("reference job has an empty or inconsistent input image");

    const auto values = effective_values(*job.variant, job.overrides);
    const Params params(values);
    const Sampler tex(job.input, job.filter);
    std::vector<StagePlan> plan;
    for (const ResolvedStage& rs : job.variant->pass->stages) plan.push_back({rs.stage->name, rs.form->name});
    auto find = [&](const char* stage) -> const StagePlan* {
        for (const auto& s : plan)
            if (s.stage == stage) return &s;
        return nullptr;
    };
    const StagePlan* curvature = find("curvature");
    const StagePlan* aberration = find("aberration");
    const StagePlan* bloom = find("bloom");
    const StagePlan* tonemap = find("tonemap");
    const StagePlan* scanlines = find("scanlines");
    const StagePlan* mask = find("mask");
    const StagePlan* glow = find("glow");
    const StagePlan* vignette = find("vignette");
    for (const auto& s : plan) {
        static const char* known[] = {"curvature", "aberration", "bloom", "tonemap", "scanlines", "mask", "glow", "vignette"};
        if (std::find(std::begin(known), std::end(known), s.stage) == std::end(known)) return unmodelled(s);
    }

    Image out = Image::make(job.width, job.height);
    Fragment f;
    f.output_size = {static_cast<double>(job.width), static_cast<double>(job.height)};
    f.source_size = {static_cast<double>(job.input.width), static_cast<double>(job.input.height)};
    f.time = job.time;
    for (int y = 0; y < job.height; ++y) {
        for (int x = 0; x < job.width; ++x) {
            f.screen_uv = {(x + 0.5) / job.width, (y + 0.5) / job.height};
            f.pixel = {x + 0.5, y + 0.5};
            float* dst = out.at(x, y);
            if (plan.empty()) {  // CRT off: passthrough, alpha included
                const Rgba c = tex.sample(f.screen_uv);
                for (int i = 0; i < 4; ++i) dst[i] = static_cast<float>(c[i]);
                continue;
            }
            f.uv = f.screen_uv;
            if (curvature && !warp_curvature(curvature->form, params, f.uv)) return unmodelled(*curvature);
            f.centered = f.uv * 2.0 - Vec2{1, 1};
            Vec2 sample_uv = f.uv;
            if (mask && mask->form == "shadow") shadow_cell_uv(params, f, sample_uv);
            Vec3 color = tex.rgb(sample_uv);
            if (aberration && !fetch_aberration(aberration->form, params, tex, f, sample_uv, color)) return unmodelled(*aberration);
            if (bloom) fetch_bloom(params, tex, sample_uv, color);
            if (tonemap) tonemap_saturate(color);
            if (scanlines && !apply_scanlines(scanlines->form, params, f, color)) return unmodelled(*scanlines);
            if (mask && !apply_mask(mask->form, params, f, color)) return unmodelled(*mask);
            if (glow) apply_glow(params, f, color);
            if (vignette && !apply_vignette(vignette->form, params, f, color)) return unmodelled(*vignette);
            if (curvature) apply_bezel(params, f, color);
            dst[0] = static_cast<float>(color.r);
            dst[1] = static_cast<float>(color.g);
            dst[2] = static_cast<float>(color.b);
            dst[3] = 1.0f;
        }
    }
    return out;
}

}  // namespace crtforge
