// Counts the work of a scene render (see reference_work.hpp). The loop lengths below are the
// reference's own (reference_super_win.cpp's ringing, reference_crt_stages.cpp's filtered masks,
// reference_palette.cpp's nearest colour), which the stages' GLSL runs the same way.
#include "reference/reference_work.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "crtforge/luts.hpp"

namespace crtforge::reference {

namespace {

double number(const ResolvedStage& s, const std::map<std::string, Value>& overrides, const std::string& name) {
    auto over = overrides.find(name);
    const Value* v = over != overrides.end() ? &over->second : nullptr;
    if (!v) {
        auto own = s.values.find(name);
        if (own == s.values.end()) return 0.0;
        v = &own->second;
    }
    if (const double* d = std::get_if<double>(v)) return *d;
    if (const int64_t* i = std::get_if<int64_t>(v)) return static_cast<double>(*i);
    return 0.0;
}

// The loop steps one sample of this stage runs, and the param (or texture) that sets them.
struct Loop {
    double steps = 0.0;
    std::string set_by;
    std::string field;  // under pass.<alias>
};

Loop stage_loop(const Pass& pass, const ResolvedStage& s, const std::map<std::string, Value>& overrides,
                const std::function<PixelSize(const std::string&)>& lut_size) {
    if (!s.stage || !s.form) return {};
    const std::string& stage = s.stage->name;
    const std::string& form = s.form->name;
    if (stage == "ringing" && form == "bands") {
        // Two reads per tap, each side.
        return {2.0 * std::max(0.0, number(s, overrides, "ringTaps")), "ringTaps", "stages.ringing.ringTaps"};
    }
    if (stage == "mask" && (form == "grille_filtered" || form == "shadow_filtered")) {
        // The pixel's square cut at every stripe edge (a stripe is maskSize px for the grille, a
        // third of it for the shadow mask), each piece integrated over its cell rows.
        const double size = number(s, overrides, "maskSize");
        if (!(size > 0.0)) return {};
        const double stripe = form == "grille_filtered" ? size : size / 3.0;
        const double rows = form == "grille_filtered" ? 1.0 : 2.0 + 1.0 / size;
        return {(2.0 + 1.0 / stripe) * rows, "maskSize", "stages.mask.maskSize"};
    }
    if (stage == "palette" && form == "nearest" && lut_size) {
        // Every palette entry, for every sample.
        for (const PassInput& in : pass.inputs)
            if (in.binding == "palette" && in.from.kind == TextureSource::Kind::Lut)
                return {static_cast<double>(lut_size(in.from.name).width), "the palette texture '" + in.from.name + "' (its width)",
                        "textures.palette"};
    }
    return {};
}

}  // namespace

double scene_work(const SceneWorkJob& job) {
    if (!job.preset) return 0.0;
    const Preset& preset = *job.preset;
    const PixelRect screen = screen_rect(preset, job.display, job.source, job.fit);
    const std::vector<PixelSize> sizes = pass_sizes(preset, job.source, {screen.width, screen.height});
    const double samples = static_cast<double>(job.supersample) * job.supersample;
    double work = 0.0;
    for (size_t i = 0; i < preset.passes.size() && i < sizes.size(); ++i) {
        double per_sample = 1.0;
        for (const ResolvedStage& s : preset.passes[i].stages) per_sample += stage_loop(preset.passes[i], s, job.overrides, job.lut_size).steps;
        work += static_cast<double>(sizes[i].width) * sizes[i].height * samples * per_sample;
    }
    return work;
}

Status check_scene_work(const SceneWorkJob& job) {
    if (!job.preset) return Ok{};
    const double work = scene_work(job);
    if (work <= kMaxSceneWork) return Ok{};
    // Name the loop that weighs most: where the user can make the render reasonable again.
    const Preset& preset = *job.preset;
    const Pass* worst_pass = nullptr;
    Loop worst;
    for (const Pass& pass : preset.passes)
        for (const ResolvedStage& s : pass.stages)
            if (Loop loop = stage_loop(pass, s, job.overrides, job.lut_size); loop.steps > worst.steps) {
                worst = loop;
                worst_pass = &pass;
            }
    const std::string why = worst_pass ? fmt::format("; most of it is pass '{}', whose {} sets {:.3g} loop steps per sample", worst_pass->alias,
                                                     worst.set_by, worst.steps)
                                       : std::string();
    return make_error(fmt::format("asks for {:.3g} samples x loop steps a frame ({}x{} display, {}x{} samples per pixel), beyond the "
                                  "{:.0e} a frame may{}",
                                  work, job.display.width, job.display.height, job.supersample, job.supersample,
                                  kMaxSceneWork, why),
                      worst_pass ? worst_pass->where.file : preset.where.file, worst_pass ? worst_pass->where.line : preset.where.line,
                      worst_pass ? "pass." + worst_pass->alias + "." + worst.field : "preset");
}

Result<SceneWorkJob> scene_work_job(const ReferenceSceneJob& job, std::optional<PixelSize> source) {
    if (!job.preset || !job.source || job.frames.empty()) return make_error("reference scene job without a preset, source or frames");
    if (!source) {
        auto first = job.source(job.frames.front());
        if (!first.ok()) return first.error();
        source = PixelSize{first.value().width, first.value().height};
    }
    SceneWorkJob out;
    out.preset = job.preset;
    out.overrides = job.overrides;
    out.source = *source;
    out.display = {job.width, job.height};
    out.fit = job.fit;
    out.supersample = job.supersample;
    const Preset* preset = job.preset;
    const std::map<std::string, SharedImage> files = job.file_luts;
    out.lut_size = [preset, files](const std::string& name) -> PixelSize {
        if (auto f = files.find(name); f != files.end()) return {f->second->width, f->second->height};
        for (const LutSpec& lut : preset->luts)
            if (lut.name == name && !lut.generator.empty())
                if (auto made = generate_lut(lut.generator, lut.params); made.ok()) return {made.value().width, made.value().height};
        return {1, 1};
    };
    return out;
}

Status check_reference_work(const ReferenceSceneJob& job, std::optional<PixelSize> source) {
    auto work = scene_work_job(job, source);
    if (!work.ok()) return work.error();
    return check_scene_work(work.value());
}

}  // namespace crtforge::reference
