// Per-pass GPU timing of a scene against a same-size blit (see crtforge/validate/bench.hpp).
#include "crtforge/validate/bench.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <fmt/format.h>

#include "crtforge/exporter.hpp"
#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "crtforge/validate/target_render.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/scene_runner.hpp"
#include "reference/reference_work.hpp"

namespace crtforge {

namespace {

// The baseline: a copy of the source texture through the same full-screen triangle.
constexpr const char* kBlitFragment = R"(#version 450
layout(location = 0) in vec2 vTexCoord;
layout(location = 0) out vec4 fragColor;
layout(set = 0, binding = 1) uniform sampler2D source;
void main() { fragColor = texture(source, vTexCoord); }
)";

// The preset's name of a job's target format (rgba8, rgba16f, ...).
const char* format_name(OutputFormat f) { return pixel_format_name(pixel_format(f)); }

// Both sides of a ratio are the fastest of their timings. On lavapipe on a shared machine a copy
// runs at one of two speeds, switching every second or so and from one pipeline to the next: at
// 1920x1080 the same blit takes 4.6 ms or 7.9 ms (rarely between); a shader bound by arithmetic
// moves by a few percent, one bound by memory (a palette lookup, the passthrough) as much as the
// copy. A median picks either mode, and the ratios with it (a preset read 2.1x and 3.7x in two
// runs, the passthrough 1.6x); the fastest is what each costs when nothing gets in the way. The blit
// is timed beside every timing of the pass, eight times more for a shape's first pass, and the
// ratio divides by the session's fastest; a scene whose blits all ran slow is timed again
// (BenchSession::measure()).
constexpr int kBaselineTimings = 5;
constexpr int kCalibrationTimings = 8;
constexpr double kQuiet = 1.5;

struct PassTimes {
    double fastest = 0, median = 0, spread = 0, fastest_blit = 0;
};

// The pass's `repeats` timings and, given a blit, at least kBaselineTimings of it, interleaved
// (each job built once for all its timings).
Result<PassTimes> time_pass(RenderEngine& engine, const RenderJob& job, const RenderJob* blit, const BenchOptions& o) {
    std::vector<TimedJob> timed{{&job, o.repeats}};
    if (blit) timed.push_back({blit, std::max(o.repeats, kBaselineTimings)});
    auto ns = engine.time_draws(timed, o.draws);
    if (!ns.ok()) return ns.error();
    std::vector<double>& samples = ns.value()[0];
    PassTimes out;
    if (blit) out.fastest_blit = *std::min_element(ns.value()[1].begin(), ns.value()[1].end());
    std::sort(samples.begin(), samples.end());
    out.fastest = samples.front();
    out.median = samples[samples.size() / 2];
    out.spread = out.fastest > 0 ? (samples.back() - samples.front()) / out.fastest : 0.0;
    return out;
}

// The error is measured on the whole frame up to 1280x960; above, on evenly spaced bands of
// kBandRows rows holding about half as many pixels (320 of 1080 rows, 192 of 4K's 2160): the fp64
// references of every tier at 1080p and 4K would otherwise take most of the run, and the bands
// see the screen's middle and its edges alike.
constexpr double kWholeFramePixels = 1280.0 * 960;
constexpr double kBandedPixels = 640.0 * 960;
constexpr int kBandRows = 64;

std::vector<std::pair<int, int>> error_rows(int width, int height) {
    const int bands = static_cast<int>(std::ceil(kBandedPixels / (double(width) * kBandRows)));
    if (double(width) * height <= kWholeFramePixels || bands * kBandRows >= height) return {};
    std::vector<std::pair<int, int>> rows;
    for (int i = 0; i < bands; ++i) {
        const int first = i * height / bands + (height / bands - kBandRows) / 2;
        rows.emplace_back(first, first + kBandRows);
    }
    return rows;
}

// `test` against `reference` on those rows: RMSE and max over their pixels, SSIM the mean of each
// band's (windows never straddle two bands).
Result<ImageMetrics> compare_rows(const Image& test, const Image& reference, const std::vector<std::pair<int, int>>& rows) {
    if (rows.empty()) return compare_images(test, reference);
    if (test.width != reference.width || test.height != reference.height)
        return make_error("image sizes differ: the frame against its reference");
    ImageMetrics out;
    double squares = 0, ssim = 0, pixels = 0;
    for (const auto& [first, end] : rows) {
        auto band = [&](const Image& from) {
            Image b = Image::make(from.width, end - first);
            std::copy(from.rgba.begin() + static_cast<std::ptrdiff_t>(first) * from.width * 4,
                      from.rgba.begin() + static_cast<std::ptrdiff_t>(end) * from.width * 4, b.rgba.begin());
            return b;
        };
        auto m = compare_images(band(test), band(reference));
        if (!m.ok()) return m.error();
        const double n = double(test.width) * (end - first);
        squares += m.value().rmse * m.value().rmse * n;
        ssim += m.value().ssim * n;
        pixels += n;
        if (m.value().max_abs > out.max_abs || pixels == n) {
            out.max_abs = m.value().max_abs;
            out.worst_x = m.value().worst_x;
            out.worst_y = m.value().worst_y + first;
        }
    }
    out.rmse = std::sqrt(squares / pixels);
    out.psnr = psnr_of(out.rmse);
    out.ssim = ssim / pixels;
    return out;
}

using BlitShape = std::tuple<int, int, int, int, std::string>;  // input size, output size, format

BlitShape shape_of(const PassTiming& p) { return {p.input_width, p.input_height, p.width, p.height, p.format}; }

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
// The preset by name, at the bench's size, frame and input: the references the session keeps at a time.
std::string picture_key(const Preset& preset, const BenchOptions& o) {
    return fmt::format("{}|{}x{}|{}|{}", preset.name, o.width, o.height, o.frame, o.input);
}

std::string reference_key(const Preset& preset, const BenchOptions& o, int supersample) {
    std::string key = picture_key(preset, o) + fmt::format("|{}", supersample);
    for (const Pass& pass : preset.passes) {
        key += fmt::format("|{}:{}x{}:{}", pass.alias, pass.scale_x.factor, pass.scale_y.factor, pass.supersample);
        for (const ResolvedStage& rs : pass.stages) {
            key += ";" + (rs.stage ? rs.stage->name : std::string()) + ":" + (rs.form ? rs.form->name : std::string());
            for (const auto& [name, value] : rs.values) key += "," + name + "=" + value_to_exact_string(value);
        }
    }
    return key;
}

// A scene's passes as rendered for the timed frame (each job's inputs as the scene gave them) and
// the frame itself.
struct SceneJobs {
    std::vector<RenderJob> jobs;
    Image frame;
};

}  // namespace

struct BenchSession::Reference {
    Image image;
    std::optional<ReferenceDisplayPass> display_pass;  // the point reference's, for the tie check
};

struct BenchSession::State {
    ConsumerEngines engines;
    SpirvBinary blit_fragment, blit_vertex;
    std::string references_of;  // the preset, size, frame and input of every picture in `references`
    std::map<std::string, Reference> references;
    size_t reference_renders = 0;
    std::map<BlitShape, double> fastest_blit;  // over the whole session
    // The last scene rendered for timing, kept for a retime of the same scene (at 4K rendering a
    // scene's two frames through validation's path takes longer than timing it).
    std::string jobs_key;
    SceneJobs jobs;
    bool long_slow_spell = false;  // the last retime ran slow too; set back by a quiet scene
    double fastest(const BlitShape& shape, double ns) {
        auto [at, fresh] = fastest_blit.emplace(shape, ns);
        if (!fresh) at->second = std::min(at->second, ns);
        return at->second;
    }
    explicit State(EngineOptions vulkan) : engines(std::move(vulkan)) {}
};

BenchSession::BenchSession(const TemplateLibrary& library, EngineOptions vulkan)
    : library_(library), state_(std::make_unique<State>(std::move(vulkan))) {}
BenchSession::~BenchSession() = default;

size_t BenchSession::reference_renders() const { return state_->reference_renders; }
const Image& BenchSession::last_frame() const { return state_->jobs.frame; }

Result<ImageMetrics> compare_on_8bit_display(const Image& test, const Image& reference) {
    auto display = [](const Image& image) {
        Image out = image;
        for (float& v : out.rgba) v = std::isnan(v) ? 0.0f : std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f;
        return out;
    };
    return compare_images(display(test), display(reference));
}

namespace {

// The fp64 picture of `preset`'s frame at the bench's size, on the rows the error is measured on.
ReferenceSceneJob reference_job(const TemplateLibrary& library, const Preset& preset, const BenchOptions& o, int supersample) {
    ReferenceSceneJob ref;
    ref.library = &library;
    ref.preset = &preset;
    ref.source = [&preset, o](int frame) { return make_test_input(o.input, source_width_of(preset), source_height_of(preset), frame); };
    ref.width = o.width;
    ref.height = o.height;
    ref.frames = {o.frame};
    ref.supersample = supersample;
    ref.display_rows = error_rows(o.width, o.height);
    return ref;
}

// The largest channel difference of two images at a pixel.
float pixel_distance(const Image& a, const Image& b, int x, int y) {
    float d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.at(x, y)[c] - b.at(x, y)[c]));
    return d;
}

// A difference from the point reference above this, on a pixel where the reference itself changes
// by as much under jitter, is a tie (golden update's unstable pixels use the same threshold).
constexpr float kTie = 0.01f;

}  // namespace

Result<const BenchSession::Reference*> BenchSession::reference(const Preset& preset, const BenchOptions& o, int supersample) {
    const std::string of = picture_key(preset, o);
    if (state_->references_of != of) {
        state_->references.clear();
        state_->references_of = of;
    }
    const std::string key = reference_key(preset, o, supersample);
    if (auto found = state_->references.find(key); found != state_->references.end()) return &found->second;
    Reference made;
    if (supersample == 1) made.display_pass.emplace();
    const ReferenceSceneJob job = reference_job(library_, preset, o, supersample);
    if (auto s = reference::check_reference_work(job); !s.ok()) return s.error();
    auto rendered = render_reference_scene(job, made.display_pass ? &*made.display_pass : nullptr);
    if (!rendered.ok()) return rendered.error();
    ++state_->reference_renders;
    made.image = std::move(rendered.value().front());
    return &(state_->references[key] = std::move(made));
}

// A point sample exactly on a discontinuity is a tie, not an error: at 1920x1080 a 240-row source
// is 4.5 px a texel, so every ninth row samples a nearest-filtered texel edge, where fp32 and fp64
// may each take either texel. On the rows where `frame` is off the reference by more than kTie,
// the display pass is rendered again jittered along a diagonal both ways (kJitterPixels ...; the
// passes before it keep their pictures: a six-pass scene at 4K would otherwise render twelve
// passes for each jitter), and along the other diagonal where a pixel the jitter flipped still
// matches neither render (a corner of four texels). A pixel the jitter flips is judged against
// whichever render is nearest; `ties` counts those pixels.
Result<std::optional<Image>> BenchSession::tie_tolerant(const Reference& point, const BenchOptions& o, const Image& frame, int& ties) {
    ties = 0;
    const Image& reference = point.image;
    if (frame.width != reference.width || frame.height != reference.height || !point.display_pass) return std::optional<Image>();
    std::vector<std::pair<int, int>> measured = error_rows(o.width, o.height);
    if (measured.empty()) measured.emplace_back(0, reference.height);
    std::vector<std::pair<int, int>> rows;  // the rows with a pixel off by more than kTie, merged
    for (const auto& [first, end] : measured)
        for (int y = first; y < end; ++y) {
            bool off = false;
            for (int x = 0; x < frame.width && !off; ++x) off = pixel_distance(frame, reference, x, y) > kTie;
            if (!off) continue;
            if (!rows.empty() && rows.back().second == y) rows.back().second = y + 1;
            else rows.emplace_back(y, y + 1);
        }
    if (rows.empty()) return std::optional<Image>();
    ReferenceSceneJob job;
    job.display_rows = rows;
    std::vector<Image> moved;
    // Whether a pixel the diagonal jitters flipped matches neither render.
    auto corner_left = [&] {
        for (const auto& [first, end] : rows)
            for (int y = first; y < end; ++y)
                for (int x = 0; x < frame.width; ++x) {
                    float best = pixel_distance(frame, reference, x, y);
                    bool flipped = false;
                    for (const Image& m : moved) {
                        best = std::min(best, pixel_distance(frame, m, x, y));
                        flipped = flipped || pixel_distance(m, reference, x, y) > kTie;
                    }
                    if (flipped && best > kTie) return true;
                }
        return false;
    };
    for (const auto& [sign, sign_y] : {std::pair{1.0, 1.0}, {-1.0, -1.0}, {1.0, -1.0}, {-1.0, 1.0}}) {
        if (moved.size() == 2 && !corner_left()) break;
        auto rendered = render_display_pass(*point.display_pass, jittered(job, sign, sign_y));
        if (!rendered.ok()) return rendered.error();
        moved.push_back(std::move(rendered.value()));
    }
    Image patched = reference;
    for (const auto& [first, end] : rows)
        for (int y = first; y < end; ++y)
            for (int x = 0; x < frame.width; ++x) {
                const Image* nearest = nullptr;
                float best = pixel_distance(frame, reference, x, y);
                if (best <= kTie) continue;
                for (const Image& m : moved)
                    if (pixel_distance(m, reference, x, y) > kTie && pixel_distance(frame, m, x, y) < best) {
                        best = pixel_distance(frame, m, x, y);
                        nearest = &m;
                    }
                if (!nearest) continue;
                std::copy_n(nearest->at(x, y), 4, patched.at(x, y));
                ++ties;
            }
    if (ties == 0) return std::optional<Image>();
    return std::optional<Image>(std::move(patched));
}

Result<SceneTiming> BenchSession::scene(const Preset& preset, const BenchOptions& o) { return measure(preset, preset, o); }

Result<SceneTiming> BenchSession::tier(const std::vector<PresetTier>& tiers, size_t index, const BenchOptions& o) {
    if (index >= tiers.size()) return make_error("no tier " + std::to_string(index));
    auto timing = measure(tiers[index].preset, point_tier(tiers).preset, o);
    if (timing.ok() && tiers.size() > 1) {
        timing.value().tier = tiers[index].name;
        timing.value().tier_changes = tiers[index].changes;
    }
    return timing;
}

namespace {

// A scene run up to the timed frame on Vulkan: that frame's jobs, one per pass, and its picture.
Result<SceneJobs> scene_jobs(const Preset& preset, const std::vector<CompiledVariant>& compiled, ConsumerEngines& engines,
                             const BenchOptions& o) {
    SceneJobs out;
    int current_frame = -1;
    SceneRenderRequest scene;
    scene.preset = &preset;
    scene.passes = &compiled;
    scene.target = TargetId::Spirv;
    scene.source = [&](int frame) -> Result<Image> {
        current_frame = frame;
        return make_test_input(o.input, source_width_of(preset), source_height_of(preset), frame);
    };
    scene.width = o.width;
    scene.height = o.height;
    scene.frames = {o.frame};
    auto luts = read_file_luts(preset);  // an imported preset's LUT pictures
    if (!luts.ok()) return luts.error();
    scene.file_luts = std::move(luts.value());
    auto rendered = run_scene(scene, [&](TargetRenderRequest r) -> Result<Image> {
        auto job = vulkan_job(std::move(r));
        if (!job.ok()) return job.error();
        if (current_frame == o.frame) out.jobs.push_back(job.value());
        return render_on_vulkan(job.value(), engines);
    });
    if (!rendered.ok()) return rendered.error();
    out.frame = std::move(rendered.value().front());
    return out;
}

}  // namespace

// Each enabled stage of each pass turned off in turn, and that pass timed again.
Result<std::vector<StageCost>> BenchSession::stage_costs(const Preset& preset, const SceneTiming& timed, const BenchOptions& o) {
    std::vector<StageCost> costs;
    auto engine = state_->engines.vulkan();
    if (!engine.ok()) return engine.error();
    for (size_t p = 0; p < preset.passes.size() && p < timed.passes.size(); ++p) {
        for (size_t s = 0; s < preset.passes[p].stages.size(); ++s) {
            const ResolvedStage& stage = preset.passes[p].stages[s];
            Preset without = preset;
            Pass& pass = without.passes[p];
            pass.stages.erase(pass.stages.begin() + static_cast<std::ptrdiff_t>(s));
            // The textures only that stage read are no longer bound.
            const std::vector<std::string> reads = pass.texture_names();
            std::erase_if(pass.inputs, [&](const PassInput& in) {
                return in.binding != "source" && std::find(reads.begin(), reads.end(), in.binding) == reads.end();
            });
            auto compiled = compile_scene(library_, without, o.variant, Cache());
            if (!compiled.ok()) return compiled.error();
            auto run = scene_jobs(without, compiled.value(), state_->engines, o);
            if (!run.ok()) return run.error();
            if (run.value().jobs.size() != preset.passes.size())
                return make_error(fmt::format("{} without {}: the scene ran {} passes, not {}", preset.name, stage.stage ? stage.stage->name : "?",
                                              run.value().jobs.size(), preset.passes.size()));
            auto times = time_pass(*engine.value(), run.value().jobs[p], nullptr, o);
            if (!times.ok()) return times.error();
            StageCost cost;
            cost.pass = preset.passes[p].alias;
            cost.stage = stage.stage ? stage.stage->name : std::string();
            cost.form = stage.form ? stage.form->name : std::string();
            cost.ns = timed.passes[p].ns - times.value().fastest;
            cost.blit_ns = timed.passes[p].blit_ns;
            costs.push_back(std::move(cost));
        }
    }
    return costs;
}

Result<SceneTiming> BenchSession::measure(const Preset& preset, const Preset& supersampled, const BenchOptions& o) {
    auto timing = measure_once(preset, supersampled, o);
    if (!timing.ok()) return timing;
    if (quiet(timing.value())) {
        state_->long_slow_spell = false;
        return timing;
    }
    // The blits beside the passes all ran slow: the machine was in a slow spell. Once more; the
    // picture is the same, so its error is not measured again. Not while the last retime ran slow
    // too: in a long slow spell a retime is as slow and only doubles the run.
    if (state_->long_slow_spell) return timing;
    BenchOptions timing_only = o;
    timing_only.supersample = 0;
    auto again = measure_once(preset, supersampled, timing_only);
    if (!again.ok()) return again;
    state_->long_slow_spell = !quiet(again.value());
    again.value().retimed = true;
    again.value().vs_point = timing.value().vs_point;
    again.value().vs_supersampled = timing.value().vs_supersampled;
    again.value().supersample = timing.value().supersample;
    again.value().error_rows = timing.value().error_rows;
    again.value().point_ties = timing.value().point_ties;
    return again;
}

Result<SceneTiming> BenchSession::measure_once(const Preset& preset, const Preset& supersampled, const BenchOptions& o) {
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
        // The library's full-screen triangle: a program pass (an imported RetroArch shader) has a
        // vertex stage of its own, which reads its uniform block; the blit has none.
        blit_options.stage = ShaderStage::Vertex;
        blit_options.source_name = library_.vertex_path();
        auto blit_vertex = compile_to_spirv(library_.vertex_source(), blit_options);
        if (!blit_vertex.ok()) return blit_vertex.error();
        state_->blit_vertex = std::move(blit_vertex.value());
    }
    auto engine = state_->engines.vulkan();
    if (!engine.ok()) return engine.error();
    const std::string jobs_key = reference_key(preset, o, 0) + "|" + o.variant.uniforms.str() + "|" + precision_name(o.variant.precision) +
                                 (o.variant.optimize ? "|optimized" : "|glslang");
    if (state_->jobs_key != jobs_key) {
        state_->jobs_key.clear();
        auto run = scene_jobs(preset, compiled.value(), state_->engines, o);
        if (!run.ok()) return run.error();
        state_->jobs = std::move(run.value());
        state_->jobs_key = jobs_key;
    }
    const SceneJobs& run = state_->jobs;
    const std::vector<RenderJob>& jobs = run.jobs;

    SceneTiming out;
    out.preset = preset.name;
    out.uniforms = o.uniforms_label;
    out.device = engine.value()->device().name;
    out.width = o.width;
    out.height = o.height;
    out.frame = o.frame;
    out.draws = o.draws;
    auto blit_job = [&](const Image& input, int width, int height, OutputFormat format) {
        RenderJob job;
        job.vertex_spirv = state_->blit_vertex;
        job.fragment_spirv = state_->blit_fragment;
        job.input = input;
        job.width = width;
        job.height = height;
        job.format = format;
        return job;
    };
    // A shape's first blit is timed alone for a while (seconds: long enough to meet the copy's fast
    // mode), so the first pass of that shape is judged against a fastest that means something.
    auto calibrate = [&](const BlitShape& shape, const RenderJob& blit) -> Status {
        if (state_->fastest_blit.count(shape)) return Ok{};
        auto ns = engine.value()->time_draws({{&blit, kCalibrationTimings}}, o.draws);
        if (!ns.ok()) return ns.error();
        for (double t : ns.value()[0]) state_->fastest(shape, t);
        return Ok{};
    };
    for (size_t i = 0; i < jobs.size(); ++i) {
        const RenderJob& job = jobs[i];
        PassTiming t;
        t.alias = preset.passes[i].alias;
        t.width = job.width;
        t.height = job.height;
        t.input_width = job.input->width;
        t.input_height = job.input->height;
        t.format = format_name(job.format);
        t.cost = spirv_cost(compiled.value()[i].fragment);
        const RenderJob blit = blit_job(*job.input, job.width, job.height, job.format);
        if (auto calibrated = calibrate(shape_of(t), blit); !calibrated.ok()) return calibrated.error();
        auto times = time_pass(*engine.value(), job, &blit, o);
        if (!times.ok()) return times.error();
        t.ns = times.value().fastest;
        t.median_ns = times.value().median;
        t.spread = times.value().spread;
        t.own_blit_ns = times.value().fastest_blit;
        t.blit_ns = state_->fastest(shape_of(t), times.value().fastest_blit);
        out.passes.push_back(std::move(t));
    }
    // Speed against error: the frame just rendered on Vulkan against the two references. An
    // imported RetroArch pass (a whole program) has no double-precision model, nor has a read
    // through a mip chain: timed only.
    const bool modelled =
        std::none_of(compiled.value().begin(), compiled.value().end(),
                     [](const CompiledVariant& pass) { return pass.variant.program_form() != nullptr; }) &&
        std::none_of(preset.passes.begin(), preset.passes.end(), [](const Pass& pass) {
            return std::any_of(pass.inputs.begin(), pass.inputs.end(), [](const PassInput& input) { return input.mipmap; });
        });
    if (o.supersample > 0 && modelled) {
        for (int n : {1, o.supersample}) {
            if (n == 1 && !o.point_reference) continue;
            auto reference = this->reference(n == 1 ? preset : supersampled, o, n);
            if (!reference.ok()) return reference.error();
            Result<std::optional<Image>> patched = n == 1 ? tie_tolerant(*reference.value(), o, run.frame, out.point_ties)
                                                          : Result<std::optional<Image>>(std::optional<Image>());
            if (!patched.ok()) return patched.error();
            auto metrics = compare_rows(run.frame, patched.value() ? *patched.value() : reference.value()->image, error_rows(o.width, o.height));
            if (!metrics.ok()) return metrics.error();
            (n == 1 ? out.vs_point : out.vs_supersampled) = metrics.value();
        }
        out.supersample = o.supersample;
        for (const auto& [first, end] : error_rows(o.width, o.height)) out.error_rows += end - first;
    }
    // The display blit: the source onto the whole display, a pass's shape for single-pass scenes.
    const BlitShape display{source_width, source_height, o.width, o.height, format_name(OutputFormat::Rgba16Float)};
    if (!state_->fastest_blit.count(display)) {
        auto source = make_test_input(o.input, source_width, source_height, o.frame);
        if (!source.ok()) return source.error();
        if (auto calibrated = calibrate(display, blit_job(source.value(), o.width, o.height, OutputFormat::Rgba16Float)); !calibrated.ok())
            return calibrated.error();
    }
    out.display_blit_ns = state_->fastest_blit.at(display);
    out.source_width = source_width;
    out.source_height = source_height;
    if (o.stage_costs) {
        auto costs = stage_costs(preset, out, o);
        if (!costs.ok()) return costs.error();
        out.stage_costs = std::move(costs.value());
    }
    return out;
}

bool BenchSession::quiet(const SceneTiming& timing) const {
    for (const PassTiming& p : timing.passes) {
        auto known = state_->fastest_blit.find(shape_of(p));
        if (known != state_->fastest_blit.end() && p.own_blit_ns > kQuiet * known->second) return false;
    }
    return true;
}

void BenchSession::rebase(SceneTiming& timing) const {
    for (PassTiming& p : timing.passes)
        if (auto known = state_->fastest_blit.find(shape_of(p)); known != state_->fastest_blit.end()) p.blit_ns = known->second;
    const BlitShape display{timing.source_width, timing.source_height, timing.width, timing.height,
                            format_name(OutputFormat::Rgba16Float)};
    if (auto known = state_->fastest_blit.find(display); known != state_->fastest_blit.end()) timing.display_blit_ns = known->second;
    for (StageCost& c : timing.stage_costs)
        for (const PassTiming& p : timing.passes)
            if (p.alias == c.pass) c.blit_ns = p.blit_ns;
}

Result<SceneTiming> bench_scene(const TemplateLibrary& library, const Preset& preset, const BenchOptions& options) {
    BenchSession session(library, options.vulkan);
    return session.scene(preset, options);
}

std::string format_scene_timing(const SceneTiming& t) {
    std::string s = fmt::format("{} at {}x{}, frame {}, on {} ({} draws per timing, the fastest of the timings{})\n", t.label(), t.width,
                                t.height, t.frame, t.device, t.draws, t.rounds > 1 ? fmt::format(" of {} rounds", t.rounds) : "");
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
    // What each stage adds to its pass: the pass's time less the pass's time with the stage off.
    for (const StageCost& c : t.stage_costs)
        s += fmt::format("{:<14} {:>23} {:>9} {:>12.1f} {:>12} {:>8.2f}\n", "+ " + c.stage, c.form + (t.passes.size() > 1 ? " in " + c.pass : ""),
                         "", c.ns / 1000, "", c.ratio());
    if (t.vs_point) s += error_line("point-sampled fp64:", *t.vs_point);
    if (t.point_ties > 0) s += fmt::format("{} pixels sample a discontinuity (ties: judged against the nearest jittered reference)\n", t.point_ties);
    if (t.vs_supersampled) s += error_line(fmt::format("{0}x{0} supersampled fp64:", t.supersample).c_str(), *t.vs_supersampled);
    if (t.retroarch_compile_ns > 0)
        s += fmt::format("{:.2f}x RetroArch's compile ({:.1f} us per frame); the frame against its frame, on 8 bits: PSNR {:.1f} dB\n",
                         t.speedup_vs_retroarch(), t.retroarch_compile_ns / 1000, t.vs_retroarch_compile ? t.vs_retroarch_compile->psnr : 0.0);
    return s;
}

}  // namespace crtforge
