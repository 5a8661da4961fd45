// Per-pass GPU timing of a scene against a same-size blit (see crtforge/validate/bench.hpp).
#include "crtforge/validate/bench.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "crtforge/exporter.hpp"
#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "crtforge/validate/target_render.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/scene_runner.hpp"

namespace crtforge {

namespace {

// The baseline: a copy of the source texture through the same full-screen triangle.
constexpr const char* kBlitFragment = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
void main() { fragColor = texture(source, vTexCoord); }
)";

const char* format_name(OutputFormat f) {
    switch (f) {
        case OutputFormat::Rgba8Unorm: return "rgba8";
        case OutputFormat::Rgba8Srgb: return "rgba8_srgb";
        case OutputFormat::Rgba16Float: return "rgba16f";
    }
    return "other";
}

// Median of `repeats` timings, and their spread.
Result<std::pair<double, double>> median_time(RenderEngine& engine, const RenderJob& job, const BenchOptions& o) {
    std::vector<double> samples;
    for (int i = 0; i < o.repeats; ++i) {
        auto ns = engine.time_draw(job, o.draws);
        if (!ns.ok()) return ns.error();
        samples.push_back(ns.value());
    }
    std::sort(samples.begin(), samples.end());
    const double median = samples[samples.size() / 2];
    return std::make_pair(median, median > 0 ? (samples.back() - samples.front()) / median : 0.0);
}

}  // namespace

ShaderCost SceneTiming::cost() const {
    ShaderCost sum;
    for (const PassTiming& p : passes) {
        sum.instructions += p.cost.instructions;
        sum.samples += p.cost.samples;
        sum.transcendentals += p.cost.transcendentals;
    }
    return sum;
}

double SceneTiming::total_ns() const {
    double sum = 0;
    for (const PassTiming& p : passes) sum += p.ns;
    return sum;
}

namespace {

int source_width_of(const Preset& p) { return p.scene.source_width ? p.scene.source_width : 320; }
int source_height_of(const Preset& p) { return p.scene.source_height ? p.scene.source_height : 240; }

// What makes two reference pictures the same: the preset's content (every pass's stages, forms and
// values), and the size, frame, input and samples per pixel.
std::string reference_key(const Preset& preset, const BenchOptions& o, int supersample) {
    std::string key = fmt::format("{}|{}x{}|{}|{}|{}", preset.name, o.width, o.height, o.frame, o.input, supersample);
    for (const Pass& pass : preset.passes) {
        key += "|" + pass.alias;
        for (const ResolvedStage& rs : pass.stages) {
            key += ";" + (rs.stage ? rs.stage->name : std::string()) + ":" + (rs.form ? rs.form->name : std::string());
            for (const auto& [name, value] : rs.values) key += "," + name + "=" + value_to_exact_string(value);
        }
    }
    return key;
}

}  // namespace

struct BenchSession::State {
    ConsumerEngines engines;
    SpirvBinary blit_fragment;
    std::map<std::string, Image> references;
    explicit State(EngineOptions vulkan) : engines(std::move(vulkan)) {}
};

BenchSession::BenchSession(const TemplateLibrary& library, EngineOptions vulkan)
    : library_(library), state_(std::make_unique<State>(std::move(vulkan))) {}
BenchSession::~BenchSession() = default;

size_t BenchSession::reference_renders() const { return state_->references.size(); }

Result<Image> BenchSession::reference(const Preset& preset, const BenchOptions& o, int supersample) {
    const std::string key = reference_key(preset, o, supersample);
    if (auto found = state_->references.find(key); found != state_->references.end()) return found->second;
    ReferenceSceneJob ref;
    ref.library = &library_;
    ref.preset = &preset;
    ref.source = [&](int frame) { return make_test_input(o.input, source_width_of(preset), source_height_of(preset), frame); };
    ref.width = o.width;
    ref.height = o.height;
    ref.frames = {o.frame};
    ref.supersample = supersample;
    auto rendered = render_reference_scene(ref);
    if (!rendered.ok()) return rendered.error();
    return state_->references[key] = std::move(rendered.value().front());
}

Result<SceneTiming> BenchSession::scene(const Preset& preset, const BenchOptions& o) { return measure(preset, preset, o); }

Result<SceneTiming> BenchSession::tier(const std::vector<PresetTier>& tiers, size_t index, const BenchOptions& o) {
    if (index >= tiers.size()) return make_error("no tier " + std::to_string(index));
    auto timing = measure(tiers[index].preset, tiers.front().preset, o);
    if (timing.ok() && tiers.size() > 1) {
        timing.value().tier = tiers[index].name;
        timing.value().tier_changes = tiers[index].changes;
    }
    return timing;
}

Result<SceneTiming> BenchSession::measure(const Preset& preset, const Preset& supersampled, const BenchOptions& o) {
    if (o.draws < 1 || o.repeats < 1) return make_error("draws and repeats must be at least 1", {}, 0, "--draws");
    auto compiled = compile_scene(library_, preset, o.variant, Cache());
    if (!compiled.ok()) return compiled.error();
    const int source_width = source_width_of(preset), source_height = source_height_of(preset);
    if (state_->blit_fragment.empty()) {
        CompileOptions blit_options;
        blit_options.stage = ShaderStage::Fragment;
        blit_options.source_name = "<blit>";
        auto blit_fragment = compile_to_spirv(kBlitFragment, blit_options);
        if (!blit_fragment.ok()) return blit_fragment.error();
        state_->blit_fragment = std::move(blit_fragment.value());
    }
    ConsumerEngines& engines = state_->engines;
    auto engine = engines.vulkan();
    if (!engine.ok()) return engine.error();

    // The scene up to the frame, on Vulkan; the last frame's jobs are kept.
    std::vector<RenderJob> jobs;
    int current_frame = -1;
    SceneRenderRequest scene;
    scene.preset = &preset;
    scene.passes = &compiled.value();
    scene.target = TargetId::Spirv;
    scene.source = [&](int frame) -> Result<Image> {
        current_frame = frame;
        return make_test_input(o.input, source_width, source_height, frame);
    };
    scene.width = o.width;
    scene.height = o.height;
    scene.frames = {o.frame};
    auto rendered = run_scene(scene, [&](TargetRenderRequest r) -> Result<Image> {
        auto job = vulkan_job(std::move(r));
        if (!job.ok()) return job.error();
        if (current_frame == o.frame) jobs.push_back(job.value());
        return render_on_vulkan(job.value(), engines);
    });
    if (!rendered.ok()) return rendered.error();

    SceneTiming out;
    out.preset = preset.name;
    out.uniforms = o.uniforms_label;
    out.device = engine.value()->device().name;
    out.width = o.width;
    out.height = o.height;
    out.frame = o.frame;
    out.draws = o.draws;
    auto blit = [&](const Image& input, int width, int height, OutputFormat format) -> Result<std::pair<double, double>> {
        RenderJob job;
        job.vertex_spirv = compiled.value().front().vertex;
        job.fragment_spirv = state_->blit_fragment;
        job.input = input;
        job.width = width;
        job.height = height;
        job.format = format;
        return median_time(*engine.value(), job, o);
    };
    for (size_t i = 0; i < jobs.size(); ++i) {
        const RenderJob& job = jobs[i];
        PassTiming t;
        t.alias = preset.passes[i].alias;
        t.width = job.width;
        t.height = job.height;
        t.input_width = job.input.width;
        t.input_height = job.input.height;
        t.format = format_name(job.format);
        t.cost = spirv_cost(compiled.value()[i].fragment);
        auto time = median_time(*engine.value(), job, o);
        if (!time.ok()) return time.error();
        t.ns = time.value().first;
        t.spread = time.value().second;
        auto base = blit(job.input, job.width, job.height, job.format);
        if (!base.ok()) return base.error();
        t.blit_ns = base.value().first;
        out.passes.push_back(std::move(t));
    }
    // Speed against error: the frame just rendered on Vulkan against the two references.
    if (o.supersample > 0) {
        for (int n : {1, o.supersample}) {
            if (n == 1 && !o.point_reference) continue;
            auto reference = this->reference(n == 1 ? preset : supersampled, o, n);
            if (!reference.ok()) return reference.error();
            auto metrics = compare_images(rendered.value().front(), reference.value());
            if (!metrics.ok()) return metrics.error();
            (n == 1 ? out.vs_point : out.vs_supersampled) = metrics.value();
        }
        out.supersample = o.supersample;
    }
    auto source = make_test_input(o.input, source_width, source_height, o.frame);
    if (!source.ok()) return source.error();
    auto display = blit(source.value(), o.width, o.height, OutputFormat::Rgba16Float);
    if (!display.ok()) return display.error();
    out.display_blit_ns = display.value().first;
    return out;
}

Result<SceneTiming> bench_scene(const TemplateLibrary& library, const Preset& preset, const BenchOptions& options) {
    BenchSession session(library, options.vulkan);
    return session.scene(preset, options);
}

std::string format_scene_timing(const SceneTiming& t) {
    std::string s = fmt::format("{} at {}x{}, frame {}, on {} ({} draws per timing, median of the timings)\n", t.label(), t.width,
                                t.height, t.frame, t.device, t.draws);
    s += fmt::format("{:<14} {:>11} {:>11} {:>9} {:>12} {:>12} {:>8} {:>7} {:>7} {:>7} {:>6}\n", "pass", "input", "output", "format",
                     "us/draw", "blit us", "x blit", "spread", "instr", "samples", "transc");
    for (const PassTiming& p : t.passes)
        s += fmt::format("{:<14} {:>11} {:>11} {:>9} {:>12.1f} {:>12.1f} {:>8.2f} {:>6.0f}% {:>7} {:>7} {:>6}\n", p.alias,
                         fmt::format("{}x{}", p.input_width, p.input_height), fmt::format("{}x{}", p.width, p.height), p.format,
                         p.ns / 1000, p.blit_ns / 1000, p.ratio(), 100 * p.spread, p.cost.instructions, p.cost.samples,
                         p.cost.transcendentals);
    s += fmt::format("{:<14} {:>11} {:>11} {:>9} {:>12.1f} {:>12.1f} {:>8.2f}\n", "scene", "", fmt::format("{}x{}", t.width, t.height),
                     "", t.total_ns() / 1000, t.display_blit_ns / 1000, t.ratio());
    auto error_line = [](const char* label, const ImageMetrics& m) {
        return fmt::format("error vs {:<26} RMSE {:.5f}  PSNR {:5.1f} dB  max |d| {:.4f}  SSIM {:.4f}\n", label, m.rmse, m.psnr, m.max_abs, m.ssim);
    };
    if (t.vs_point) s += error_line("point-sampled fp64:", *t.vs_point);
    if (t.vs_supersampled) s += error_line(fmt::format("{0}x{0} supersampled fp64:", t.supersample).c_str(), *t.vs_supersampled);
    return s;
}

}  // namespace crtforge
