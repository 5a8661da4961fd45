// The reference renderer: one pass evaluated per pixel in the generated main()'s hook order, with
// each stage's model in the variant's stage order; and a scene evaluated frame by frame.
#include "crtforge/reference/reference_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <thread>
#include <deque>

#include "crtforge/luts.hpp"
#include "crtforge/scene.hpp"
#include "crtforge/uniforms.hpp"
#include "reference/reference_stages.hpp"

namespace crtforge {

namespace reference {

namespace {

// The rule every generated shader applies to what it writes (docs/hard-cases.md): NaN becomes 0,
// anything beyond half's range its largest value.
float finite_output(double v) {
    if (std::isnan(v)) return 0.0f;
    return static_cast<float>(std::clamp(v, -65504.0, 65504.0));
}

ReferenceFault& fault_slot() {
    static ReferenceFault fault;
    return fault;
}
}  // namespace

const ReferenceFault& reference_fault() { return fault_slot(); }
void install_reference_fault(const ReferenceFault& fault) { fault_slot() = fault; }

Params::Params(const std::map<std::string, Value>& values, const MissingNames& missing) : missing_(missing) {
    size_t size = 16;
    while (size < 4 * values.size()) size *= 2;  // at most a quarter full: short probes
    slots_.assign(size, {std::string_view(), nullptr});
    for (const auto& [name, value] : values) {
        size_t i = slot_hash(name) & (size - 1);
        while (slots_[i].second) i = (i + 1) & (size - 1);
        slots_[i] = {name, &value};
    }
}

const Value* Params::value(std::string_view name) const {
    const size_t mask = slots_.size() - 1;
    for (size_t i = slot_hash(name) & mask; slots_[i].second; i = (i + 1) & mask)
        if (slots_[i].first == name) return slots_[i].second;
    return nullptr;
}

template <typename T>
const T* Params::find(std::string_view name, const char* type) const {
    const Value* v = value(name);
    const T* typed = v ? std::get_if<T>(v) : nullptr;
    if (!typed) missing_.note("param '" + std::string(name) + "' (" + type + ")");
    return typed;
}

double Params::num(std::string_view name) const {
    const double factor = name == reference_fault().scale_param ? reference_fault().factor : 1.0;
    const Value* v = value(name);  // one lookup: int or float
    if (auto i = v ? std::get_if<int64_t>(v) : nullptr) return static_cast<double>(*i) * factor;
    if (auto d = v ? std::get_if<double>(v) : nullptr) return *d * factor;
    missing_.note("param '" + std::string(name) + "' (a number)");
    return 0.0;
}
bool Params::flag(std::string_view name) const {
    const bool* b = find<bool>(name, "a bool");
    return b && *b;
}
Vec3 Params::color(std::string_view name) const {
    const Color* c = find<Color>(name, "a colour");
    if (!c) return {0, 0, 0};
    const double f = name == reference_fault().scale_param ? reference_fault().factor : 1.0;
    return {(*c)[0] * f, (*c)[1] * f, (*c)[2] * f};
}

const Sampler& Fragment::texture(const std::string& name) const {
    auto it = textures.find(name);
    if (it != textures.end() && it->second) return *it->second;
    if (missing) missing->note("texture '" + name + "'");
    static const Image black = Image::make(1, 1);
    static const Sampler none(black, SamplerFilter::Nearest);
    return none;
}

const StageModel* find_stage_model(const std::string& stage) {
    static const std::vector<StageModel> models = [] {
        std::vector<StageModel> all;
        for (auto family : {crt_stage_models, palette_stage_models, super_win_stage_models})
            for (const StageModel& m : family()) all.push_back(m);
        return all;
    }();
    for (const StageModel& m : models)
        if (stage == m.stage) return &m;
    return nullptr;
}

}  // namespace reference

using namespace reference;

namespace {

Diagnostic unmodelled(const ResolvedStage& rs, const char* hook) {
    return make_error("the reference renderer has no model of stage '" + rs.stage->name + "' form '" + rs.form->name + "' (" +
                      hook + "); add one in reference/");
}

// A stage of the pass with its model, checked against the hooks its form provides.
struct PlannedStage {
    const ResolvedStage* resolved;
    const StageModel* model;
    bool has(Hook hook) const { return !resolved->form->functions[static_cast<int>(hook)].empty(); }
};

// The stages of a pass with their models; an error names the first stage or hook without one.
Result<std::vector<PlannedStage>> plan_stages(const Pass& pass) {
    std::vector<PlannedStage> plan;
    for (const ResolvedStage& rs : pass.stages) {
        if (rs.stage->name == reference_fault().skip_stage) continue;
        const StageModel* model = find_stage_model(rs.stage->name);
        if (!model) return unmodelled(rs, "no model of the stage");
        PlannedStage s{&rs, model};
        const std::pair<Hook, bool> hooks[] = {{Hook::Warp, model->warp != nullptr},  {Hook::SampleUv, model->sample_uv != nullptr},
                                               {Hook::Fetch, model->fetch != nullptr}, {Hook::Color, model->color != nullptr},
                                               {Hook::Finish, model->finish != nullptr}, {Hook::Alpha, model->alpha != nullptr}};
        for (const auto& [hook, modelled] : hooks)
            if (s.has(hook) && !modelled) return unmodelled(rs, hook_name(hook));
        plan.push_back(s);
    }
    return plan;
}

// The value a half float holds for `v`: 11 significant bits, rounded to nearest even.
double half_of(double v) {
    if (!std::isfinite(v) || v == 0.0) return v;
    const double a = std::fabs(v);
    if (a >= 65520.0) return std::copysign(65504.0, v);  // the largest half (rounding would overflow)
    if (a < 0x1p-14) return std::nearbyint(v * 0x1p24) * 0x1p-24;  // subnormal halves: steps of 2^-24
    int e = 0;
    const double m = std::frexp(v, &e);                  // v = m * 2^e, 0.5 <= |m| < 1
    return std::nearbyint(m * 2048.0) / 2048.0 * std::ldexp(1.0, e);
}

// A UNORM channel of `bits` bits: clamped, then the nearest of its 2^bits - 1 steps.
double unorm_of(double v, int bits) {
    const double steps = std::ldexp(1.0, bits) - 1.0;
    return std::round(std::clamp(v, 0.0, 1.0) * steps) / steps;
}

// The value a framebuffer of `format` stores for `v` in `channel` (0 red .. 3 alpha), read back as
// linear. A channel the format lacks reads as 0 (colour) or 1 (alpha), as a sampler returns it.
double stored(double v, size_t channel, PixelFormat format) {
    switch (format) {
        case PixelFormat::Rgba8: return unorm_of(v, 8);
        case PixelFormat::Rgba8Srgb: {
            const double l = std::clamp(v, 0.0, 1.0);
            const double e = l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
            const double q = std::round(e * 255.0) / 255.0;
            return q <= 0.04045 ? q / 12.92 : std::pow((q + 0.055) / 1.055, 2.4);
        }
        case PixelFormat::Rgba16F: return half_of(v);
        case PixelFormat::Rgba32F: return static_cast<float>(v);
        case PixelFormat::Rgb10A2: return unorm_of(v, channel == 3 ? 2 : 10);
        case PixelFormat::R16F: return channel == 0 ? half_of(v) : channel == 3 ? 1.0 : 0.0;
        case PixelFormat::Rg16F: return channel < 2 ? half_of(v) : channel == 3 ? 1.0 : 0.0;
    }
    return v;
}

SamplerFilter sampler_filter(Filter f) { return f == Filter::Nearest ? SamplerFilter::Nearest : SamplerFilter::Linear; }

WrapMode wrap_mode(Wrap w) {
    switch (w) {
        case Wrap::Repeat: return WrapMode::Repeat;
        case Wrap::MirroredRepeat: return WrapMode::MirroredRepeat;
        case Wrap::ClampToBorder: return WrapMode::ClampToBorder;
        default: return WrapMode::ClampToEdge;
    }
}

Image lut_image(const LutImage& lut) {
    Image image = Image::make(lut.width, lut.height);
    for (size_t i = 0; i < lut.rgba.size(); ++i) image.rgba[i] = static_cast<float>(lut.rgba[i] / 255.0);
    return image;
}

}  // namespace

Result<Image> render_reference(const ReferenceJob& job) {
    if (!job.variant || !job.variant->preset || !job.variant->pass) return make_error("reference job without a variant");
    if (job.width <= 0 || job.height <= 0 || job.width > kMaxImageDimension || job.height > kMaxImageDimension ||
        !image_budget_error(job.width, job.height).empty())
        return make_error("output size " + std::to_string(job.width) + "x" + std::to_string(job.height) + " is outside 1.." +
                              std::to_string(kMaxImageDimension) + " per side or beyond the image memory budget",
                          {}, 0, "--size");
    if (job.supersample < 1 || job.supersample > 16) return make_error("supersampling must be 1..16 samples per side", {}, 0, "--supersample");
    if (job.input.width <= 0 || job.input.height <= 0 ||
        job.input.rgba.size() != static_cast<size_t>(job.input.width) * job.input.height * 4)
        return make_error("reference job has an empty or inconsistent input image");

    const Variant& variant = *job.variant;
    auto planned = plan_stages(*variant.pass);
    if (!planned.ok()) return planned.error();
    const std::vector<PlannedStage>& plan = planned.value();

    const auto values = effective_values(variant, job.overrides);
    const MissingNames missing;
    const Params params(values, missing);
    const Sampler source(job.input, job.filter, job.wrap, job.texel_jitter);
    std::map<std::string, Sampler> samplers;
    for (const std::string& name : variant.textures) {
        auto t = job.textures.find(name);
        if (t == job.textures.end()) return make_error("reference job lacks texture '" + name + "' of the pass");
        if (!t->second.image.consistent() || t->second.image.empty())
            return make_error("reference job's texture '" + name + "' is empty or inconsistent");
        samplers.emplace(name, Sampler(t->second.image, t->second.filter, t->second.wrap, job.texel_jitter));
    }

    const bool screen_pass = screen_pass_index(*variant.preset) == variant.pass_index;
    const auto scale = screen_pass ? source_uv_scale(*variant.preset) : std::array<double, 2>{1.0, 1.0};
    const bool maps_source = scale != std::array<double, 2>{1.0, 1.0};

    Image out = Image::make(job.width, job.height);
    Fragment base;
    base.output_size = {static_cast<double>(job.width), static_cast<double>(job.height)};
    base.source_size = {static_cast<double>(job.input.width), static_cast<double>(job.input.height)};
    base.source_scale = {scale[0], scale[1]};
    base.time = job.time;
    base.frame_count = job.frame_count;
    base.source = &source;
    base.missing = &missing;
    for (const auto& [name, sampler] : samplers) base.textures[name] = &sampler;
    auto failed = [&](const PlannedStage& s, Hook hook) -> std::optional<Diagnostic> { return unmodelled(*s.resolved, hook_name(hook)); };

    // Rows in parallel: every pixel is independent, so the image is the same for any split.
    // A warp model that has no form fails in the pixel loop first, so here it only warps.
    base.warp = [&](Vec2 uv) {
        for (const PlannedStage& s : plan)
            if (s.has(Hook::Warp)) s.model->warp(s.resolved->form->name, params, base, uv);
        return uv;
    };
    // One sample of the pass's math at output position (px, py), written finite into dst.
    auto shade = [&](Fragment& f, double px, double py, float* dst) -> std::optional<Diagnostic> {
        f.screen_uv = {px / job.width, py / job.height};
        f.pixel = {px, py};
        if (plan.empty()) {  // no stage: a passthrough blit, alpha included
            const Rgba c = source.sample(f.screen_uv);
            for (int i = 0; i < 4; ++i) dst[i] = finite_output(c[i]);
            return std::nullopt;
        }
        f.uv = f.screen_uv;
        for (const PlannedStage& s : plan)
            if (s.has(Hook::Warp) && !s.model->warp(s.resolved->form->name, params, f, f.uv)) return failed(s, Hook::Warp);
        f.centered = f.uv * 2.0 - Vec2{1, 1};
        Vec2 sample_uv = f.uv;
        for (const PlannedStage& s : plan)
            if (s.has(Hook::SampleUv) && !s.model->sample_uv(s.resolved->form->name, params, f, sample_uv)) return failed(s, Hook::SampleUv);
        if (maps_source) sample_uv = f.source_uv(sample_uv);
        Vec3 color = source.rgb(sample_uv);
        for (const PlannedStage& s : plan)
            if (s.has(Hook::Fetch) && !s.model->fetch(s.resolved->form->name, params, f, sample_uv, color)) return failed(s, Hook::Fetch);
        for (const PlannedStage& s : plan)
            if (s.has(Hook::Color) && !s.model->color(s.resolved->form->name, params, f, color)) return failed(s, Hook::Color);
        for (const PlannedStage& s : plan)
            if (s.has(Hook::Finish) && !s.model->finish(s.resolved->form->name, params, f, color)) return failed(s, Hook::Finish);
        double alpha = 1.0;
        for (const PlannedStage& s : plan)
            if (s.has(Hook::Alpha) && !s.model->alpha(s.resolved->form->name, params, f, alpha)) return failed(s, Hook::Alpha);
        dst[0] = finite_output(color.r);
        dst[1] = finite_output(color.g);
        dst[2] = finite_output(color.b);
        dst[3] = finite_output(alpha);
        return std::nullopt;
    };
    // The mean of `sample` at n x n points on a regular grid over the unit square at (x0, y0),
    // in double, written finite into dst.
    auto box_mean = [](int n, double x0, double y0, auto&& sample, float* dst) -> std::optional<Diagnostic> {
        double sum[4] = {0, 0, 0, 0};
        float one[4];
        for (int sy = 0; sy < n; ++sy)
            for (int sx = 0; sx < n; ++sx) {
                if (auto e = sample(x0 + (sx + 0.5) / n, y0 + (sy + 0.5) / n, one)) return e;
                for (int i = 0; i < 4; ++i) sum[i] += one[i];
            }
        for (int i = 0; i < 4; ++i) dst[i] = finite_output(sum[i] / (n * n));
        return std::nullopt;
    };
    // A supersampled pass (Pass::supersample) is the mean of its math at s x s points of the unit
    // square around the position, each finite, as its shader averages them.
    const int s = std::max(1, variant.pass ? variant.pass->supersample : 1);
    const int n = std::max(1, job.supersample);
    auto render_rows = [&](int y0, int y1) -> std::optional<Diagnostic> {
        Fragment f = base;  // each thread its own
        for (int y = y0; y < y1; ++y) {
            if (!job.rows.empty() &&
                std::none_of(job.rows.begin(), job.rows.end(), [y](const auto& r) { return y >= r.first && y < r.second; }))
                continue;
            for (int x = 0; x < job.width; ++x) {
                // The pixel's footprint: n x n samples, box-filtered (the mean of what a display
                // would integrate), each the pass's own mean of s x s.
                auto point = [&](double px, double py, float* dst) { return shade(f, px, py, dst); };
                auto pass_sample = [&](double px, double py, float* dst) {
                    return s == 1 ? point(px, py, dst) : box_mean(s, px - 0.5, py - 0.5, point, dst);
                };
                float* dst = out.at(x, y);
                if (auto e = n == 1 ? pass_sample(x + 0.5 + job.jitter[0], y + 0.5 + job.jitter[1], dst)
                                    : box_mean(n, x + job.jitter[0], y + job.jitter[1], pass_sample, dst))
                    return e;
            }
        }
        return std::nullopt;
    };
    const int threads = std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, std::max(1, job.height / 32));
    std::vector<std::optional<Diagnostic>> errors(static_cast<size_t>(threads));
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t)
        pool.emplace_back([&, t] { errors[t] = render_rows(job.height * t / threads, job.height * (t + 1) / threads); });
    errors[0] = render_rows(0, job.height / threads);
    for (auto& th : pool) th.join();
    for (const auto& e : errors)
        if (e) return *e;
    if (const auto names = missing.names(); !names.empty()) {
        std::string list;
        for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
        return make_error("the reference's models read " + list + ", which pass '" + variant.pass->alias + "' of preset '" +
                              variant.preset->name + "' does not have (renamed or removed in the templates?): no reference "
                              "image; approve a reviewed render instead (crtforge golden approve)",
                          variant.preset->where.file, variant.preset->where.line);
    }
    return out;
}

Status reference_models(const Preset& preset) {
    for (const Pass& pass : preset.passes)
        if (auto planned = plan_stages(pass); !planned.ok()) return planned.error();
    return Ok{};
}

namespace {

// Display rows [first, end) as the rows of a pass drawn into `screen`; a pass none falls on shades none.
std::vector<std::pair<int, int>> pass_rows(const std::vector<std::pair<int, int>>& display_rows, const PixelRect& screen, int pass_height) {
    std::vector<std::pair<int, int>> rows;
    for (const auto& [first, end] : display_rows)
        if (std::min(end - screen.y, pass_height) > std::max(first - screen.y, 0))
            rows.emplace_back(std::max(first - screen.y, 0), std::min(end - screen.y, pass_height));
    if (rows.empty()) rows.emplace_back(0, 0);
    return rows;
}

// The last pass's picture in the screen's rectangle of a width x height display over opaque black.
Image on_display(const Image& last_pass, const PixelRect& screen, int width, int height) {
    if (screen.width == width && screen.height == height) return last_pass;
    Image display = Image::make(width, height, {0, 0, 0, 1});
    for (int y = 0; y < screen.height; ++y)
        for (int x = 0; x < screen.width; ++x) display.set_pixel(screen.x + x, screen.y + y, last_pass.pixel(x, y));
    return display;
}

void scale_rgb(Image& image, double gain) {
    for (size_t c = 0; c < image.rgba.size(); ++c)
        if (c % 4 != 3) image.rgba[c] = static_cast<float>(image.rgba[c] * gain);
}

}  // namespace

Result<Image> render_display_pass(const ReferenceDisplayPass& pass, const ReferenceSceneJob& perturbation) {
    ReferenceJob rj = pass.job;
    rj.variant = &pass.variant;
    rj.jitter = perturbation.jitter;
    rj.texel_jitter = perturbation.texel_jitter;
    rj.supersample = perturbation.supersample;
    if (!perturbation.display_rows.empty()) rj.rows = pass_rows(perturbation.display_rows, pass.screen, rj.height);
    if (perturbation.input_gain != 1.0)
        for (const std::string& name : pass.originals) scale_rgb(name == "source" ? rj.input : rj.textures.at(name).image, perturbation.input_gain);
    auto image = render_reference(rj);
    if (!image.ok()) return image.error();
    return on_display(image.value(), pass.screen, pass.display_width, pass.display_height);
}

Result<std::vector<Image>> render_reference_scene(const ReferenceSceneJob& job, ReferenceDisplayPass* display_pass) {
    if (!job.library || !job.preset || !job.source) return make_error("reference scene job without a preset or a source");
    if (job.width <= 0 || job.height <= 0 || job.width > kMaxImageDimension || job.height > kMaxImageDimension ||
        !image_budget_error(job.width, job.height).empty())
        return make_error("display size " + std::to_string(job.width) + "x" + std::to_string(job.height) + " is outside 1.." +
                              std::to_string(kMaxImageDimension) + " per side or beyond the image memory budget",
                          {}, 0, "--size");
    if (job.frames.empty()) return std::vector<Image>{};
    const Preset& preset = *job.preset;
    // The reference samples each texture at level 0: a level of detail needs the screen-space
    // derivatives a rasteriser has and a per-pixel evaluation has not. A mipmapped read would make
    // goldens the drivers never match, so it is refused.
    for (const Pass& pass : preset.passes)
        for (const PassInput& input : pass.inputs)
            if (input.mipmap)
                return make_error("pass '" + pass.alias + "' reads " + input.from.str() +
                                      " through a mip chain, which the reference does not model: render it on Vulkan instead of "
                                      "approving a golden",
                                  pass.where.file, input.line ? input.line : pass.where.line,
                                  "pass." + pass.alias + (input.binding == "source" ? ".mipmap" : ".textures." + input.binding));
    std::vector<Variant> variants;
    for (size_t i = 0; i < preset.passes.size(); ++i) {
        auto v = make_variant(*job.library, preset, {}, i);
        if (!v.ok()) return v.error();
        variants.push_back(std::move(v.value()));
    }
    std::map<std::string, Image> luts;
    for (const LutSpec& lut : preset.luts) {
        if (lut.generator.empty()) {
            auto file = job.file_luts.find(lut.name);
            if (file == job.file_luts.end()) return make_error("reference scene job lacks the image of file LUT '" + lut.name + "'");
            luts[lut.name] = *file->second;
            continue;
        }
        auto image = generate_lut(lut.generator, lut.params);
        if (!image.ok()) return image.error();
        luts[lut.name] = lut_image(image.value());
    }

    // With state between frames every frame up to the last kept one runs; without, only the kept ones.
    const bool stateful = preset.keeps_state();
    int last = 0;
    for (int f : job.frames) {
        if (f < 0) return make_error("frame " + std::to_string(f) + " is negative", {}, 0, "--frames");
        last = std::max(last, f);
    }
    std::vector<int> run;
    if (stateful)
        for (int f = 0; f <= last; ++f) run.push_back(f);
    else
        run = job.frames;

    std::map<int, Image> kept;
    std::map<std::string, Image> previous;  // each pass's output of the previous frame
    std::deque<Image> history;              // the originals of earlier frames, newest first
    for (int frame : run) {
        auto original = job.source(frame);
        if (!original.ok()) return original.error();
        if (job.input_gain != 1.0) scale_rgb(original.value(), job.input_gain);
        const PixelSize source{original.value().width, original.value().height};
        const PixelRect screen = screen_rect(preset, {job.width, job.height}, source, job.fit);
        const std::vector<PixelSize> sizes = pass_sizes(preset, source, {screen.width, screen.height});
        if (auto s = check_pass_sizes(preset, sizes, {screen.width, screen.height}); !s.ok()) return s.error();
        std::map<std::string, Image> current;
        auto black = [](PixelSize size) { return Image::make(size.width, size.height, {0, 0, 0, 0}); };
        auto resolve = [&](const TextureSource& from) -> Image {
            switch (from.kind) {
                case TextureSource::Kind::Original:
                    if (from.frames_back == 0) return original.value();
                    return static_cast<size_t>(from.frames_back) <= history.size() ? history[from.frames_back - 1] : black(source);
                case TextureSource::Kind::Pass: return current.at(from.name);
                case TextureSource::Kind::Feedback: {
                    auto p = previous.find(from.name);
                    if (p != previous.end()) return p->second;
                    for (size_t i = 0; i < preset.passes.size(); ++i)
                        if (preset.passes[i].alias == from.name) return black(sizes[i]);
                    return black({1, 1});
                }
                case TextureSource::Kind::Lut: return luts.at(from.name);
            }
            return black({1, 1});
        };
        for (size_t i = 0; i < preset.passes.size(); ++i) {
            const Pass& pass = preset.passes[i];
            ReferenceJob rj;
            rj.variant = &variants[i];
            rj.overrides = job.overrides;  // a name the pass does not read is never looked up
            const PassInput& main = pass.inputs.front();
            rj.input = resolve(main.from);
            rj.filter = sampler_filter(main.filter);
            rj.wrap = wrap_mode(main.wrap);
            for (size_t k = 1; k < pass.inputs.size(); ++k)
                rj.textures[pass.inputs[k].binding] = {resolve(pass.inputs[k].from), sampler_filter(pass.inputs[k].filter),
                                                       wrap_mode(pass.inputs[k].wrap)};
            rj.width = sizes[i].width;
            rj.height = sizes[i].height;
            rj.time = job.start_time + frame / preset.scene.fps;
            rj.jitter = job.jitter;
            rj.texel_jitter = job.texel_jitter;
            // Every pass box-filtered over its own pixels: what a pass drawn at the display's size
            // aliases (atari-chain's CRT pass under its palette pass) shows in the display's
            // picture, as it would not if only the last pass were supersampled.
            rj.supersample = job.supersample;
            rj.frame_count = pass.frame_count_mod ? frame % pass.frame_count_mod : frame;
            const bool display_pass_now = i + 1 == preset.passes.size() && frame == run.back();
            if (!job.display_rows.empty() && display_pass_now) rj.rows = pass_rows(job.display_rows, screen, rj.height);
            if (display_pass && display_pass_now) {
                display_pass->variant = variants[i];
                display_pass->job = rj;
                display_pass->job.variant = nullptr;
                display_pass->job.rows.clear();
                display_pass->originals.clear();
                for (const PassInput& in : pass.inputs)
                    if (in.from.kind == TextureSource::Kind::Original && in.from.frames_back == 0) display_pass->originals.push_back(in.binding);
                display_pass->screen = screen;
                display_pass->display_width = job.width;
                display_pass->display_height = job.height;
            }
            auto image = render_reference(rj);
            if (!image.ok()) return image.error();
            // Every framebuffer but the display's stores its format; the last pass is compared unrounded.
            if (i + 1 < preset.passes.size())
                for (size_t c = 0; c < image.value().rgba.size(); ++c)
                    image.value().rgba[c] = static_cast<float>(stored(image.value().rgba[c], c % 4, pass.format));
            current[pass.alias] = std::move(image.value());
        }
        if (std::find(job.frames.begin(), job.frames.end(), frame) != job.frames.end()) {
            kept[frame] = on_display(current.at(preset.passes.back().alias), screen, job.width, job.height);
        }
        if (stateful) {
            previous = std::move(current);
            history.push_front(original.value());
            while (static_cast<int>(history.size()) > preset.history_depth()) history.pop_back();
        }
    }
    std::vector<Image> out;
    for (int f : job.frames) out.push_back(kept.at(f));
    return out;
}

Status set_reference_fault(const std::string& text) {
    reference::ReferenceFault fault;
    const size_t colon = text.find(':');
    const std::string kind = text.substr(0, colon), rest = colon == std::string::npos ? "" : text.substr(colon + 1);
    try {
        if (text.empty()) {
        } else if (kind == "scale" && rest.find(':') != std::string::npos) {
            fault.scale_param = rest.substr(0, rest.find(':'));
            fault.factor = std::stod(rest.substr(rest.find(':') + 1));
        } else if (kind == "skip" && !rest.empty()) {
            fault.skip_stage = rest;
        } else if (kind == "sampler-shift" && !rest.empty()) {
            fault.sampler_shift = std::stod(rest);
        } else {
            return make_error("unknown reference fault '" + text + "' (scale:<param>:<factor>, skip:<stage>, sampler-shift:<texels>)");
        }
    } catch (const std::exception&) {
        return make_error("reference fault '" + text + "' has no number where one belongs");
    }
    reference::install_reference_fault(fault);
    return Ok{};
}

}  // namespace crtforge
