#include "crtforge/validate/golden.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/cache.hpp"
#include "crtforge/exporter.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/uniforms.hpp"
#include "crtforge/files.hpp"
#include "crtforge/lut_file.hpp"
#include "crtforge/validate/target_render.hpp"
#include "generator/toml_reader.hpp"
#include "reference/reference_work.hpp"

namespace crtforge {

using json = nlohmann::ordered_json;

namespace {


}  // namespace

// The default tolerance rests on what every consumer measures against the fp64 reference over
// every shipped golden (its `why` gives the figures): each bound is a small multiple of that floor,
// so a wrong constant, one wrong row or a small patch fails (tests/validate_test.cpp), while a
// pixel may differ by its golden's local variation where the math is discontinuous — floor() in
// masks and cell quantising, the bezel edge, texel steps — and another driver's rounding can put a
// sample on the other side of the edge.
Tolerance default_tolerance() {
    Tolerance t;
    t.max_rmse = 0.0015;
    t.outlier_threshold = 0.01;
    t.max_outlier_fraction = 0.001;
    t.min_ssim = 0.99;
    t.max_tile_rmse = 0.005;
    t.why = "fp32 GPU vs fp64 reference, measured over every golden on lavapipe, Mesa GL/GLES, Dawn and the Godot 4 shim: "
            "RMSE <= 0.00038 (0.0011 where a palette's dither steps on 8-bit passes), so RMSE <= 0.0015; the largest error "
            "where the golden is flat 0.004, so 0.01 per pixel plus the golden's own variation around the pixel (the most a "
            "sub-pixel shift at a discontinuity can move it), with 0 pixels measured beyond it, so at most 0.1%; the "
            "RMS over any 16x16 tile of the error beyond that edge allowance measures <= 0.0004 on lavapipe and SwiftShader, "
            "so 0.005; luma SSIM >= 0.99. A consumer that "
            "displays 8-bit values (Godot 3) adds its step (1/255) per pixel and its RMS (1/255/sqrt 3) to the RMSEs.";
    return t;
}

GoldenEntry make_golden_entry(const std::string& preset, const std::string& input, int w, int h, int input_width,
                              int input_height, int frame, std::optional<DisplayFit> fit) {
    GoldenEntry e;
    e.preset = preset;
    e.input = input;
    e.width = w;
    e.height = h;
    e.input_width = input_width;
    e.input_height = input_height;
    e.fit = fit;
    e.frame = frame;
    e.id = golden_id(e);
    e.tolerance = default_tolerance();
    return e;
}

std::string golden_id(const GoldenEntry& e) {
    return fmt::format("{}.{}.{}x{}{}{}.f{}", e.preset, e.input, e.width, e.height, e.fit ? std::string(".") + display_fit_name(*e.fit) : "",
                       e.config.empty() ? "" : "." + e.config, e.frame);
}

std::string GoldenEntry::sequence() const {
    return fmt::format("{}.{}.{}x{}.{}x{}.{}.{}", preset, input, width, height, input_width, input_height,
                       fit ? display_fit_name(*fit) : "preset", config);
}

bool GoldenEntry::expected_to_fail(const std::string& target) const {
    return std::find(expect_fail_targets.begin(), expect_fail_targets.end(), target) != expect_fail_targets.end();
}

bool GoldenEntry::judged_by(const std::string& target) const {
    return targets.empty() || std::find(targets.begin(), targets.end(), target) != targets.end();
}

namespace {

// Param values in the manifest: numbers (floats keep a decimal point, ints do not), booleans,
// enum names, colours as [r, g, b].
json value_json(const Value& value) {
    if (auto d = std::get_if<double>(&value)) return *d;
    if (auto i = std::get_if<int64_t>(&value)) return *i;
    if (auto b = std::get_if<bool>(&value)) return *b;
    if (auto c = std::get_if<Color>(&value)) return json::array({(*c)[0], (*c)[1], (*c)[2]});
    return std::get<std::string>(value);
}

Value json_value(const json& j) {
    if (j.is_boolean()) return j.get<bool>();
    if (j.is_number_integer()) return j.get<int64_t>();
    if (j.is_number()) return j.get<double>();
    if (j.is_array()) return Color{j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
    return j.get<std::string>();
}

}  // namespace

SceneRenderRequest golden_scene_request(const std::vector<const GoldenEntry*>& sequence, const Preset& preset,
                                        const std::vector<CompiledVariant>& passes, TargetId target,
                                        const std::vector<TargetOutput>* outputs) {
    const GoldenEntry& first = *sequence.front();
    SceneRenderRequest r;
    r.preset = &preset;
    r.passes = &passes;
    r.target = target;
    r.outputs = outputs;
    // The entry outlives the request: validate and approve keep their plans for the whole run.
    r.source = [entry = &first](int frame) { return golden_input(*entry, frame); };
    r.width = first.width;
    r.height = first.height;
    r.fit = first.fit;
    r.overrides = first.overrides;
    r.start_time = first.start_time;
    r.host = first.host;
    for (const GoldenEntry* e : sequence) r.frames.push_back(e->frame);
    return r;
}

std::vector<std::vector<const GoldenEntry*>> golden_sequences(const std::vector<const GoldenEntry*>& entries) {
    std::vector<std::vector<const GoldenEntry*>> out;
    std::map<std::string, size_t> index;
    for (const GoldenEntry* e : entries) {
        auto [it, fresh] = index.emplace(e->sequence(), out.size());
        if (fresh) out.emplace_back();
        out[it->second].push_back(e);
    }
    return out;
}

Result<Image> golden_input(const GoldenEntry& entry, int frame) {
    return make_test_input(entry.input, entry.input_width, entry.input_height, frame);
}

namespace {

// A change under jitter below the per-pixel limit needs no allowance: the limit covers it.
constexpr double kFlip = 0.01;

Result<std::vector<Image>> render_references(const TemplateLibrary& library, const std::vector<const GoldenEntry*>& sequence,
                                             double jitter_sign) {
    if (sequence.empty()) return std::vector<Image>{};
    const GoldenEntry& first = *sequence.front();
    const Preset* preset = library.find_preset(first.preset);
    if (!preset) return make_error("golden '" + first.id + "' names unknown preset '" + first.preset + "'");
    ReferenceSceneJob job;
    job.library = &library;
    job.preset = preset;
    job.source = [&first](int frame) { return golden_input(first, frame); };
    job.width = first.width;
    job.height = first.height;
    job.fit = first.fit;
    job.overrides = first.overrides;
    job.start_time = first.start_time;
    for (const GoldenEntry* e : sequence) job.frames.push_back(e->frame);
    if (auto s = reference::check_reference_work(job); !s.ok()) return s.error();
    return render_reference_scene(jitter_sign == 0.0 ? job : jittered(job, jitter_sign, jitter_sign));
}


}  // namespace

Result<std::vector<Image>> render_golden_references(const TemplateLibrary& library, const std::vector<const GoldenEntry*>& sequence) {
    return render_references(library, sequence, 0.0);
}

Result<std::vector<Image>> render_golden_unstable(const TemplateLibrary& library, const std::vector<const GoldenEntry*>& sequence,
                                                  const std::vector<Image>& references) {
    std::vector<Image> out;
    for (const Image& r : references) out.push_back(Image::make(r.width, r.height, {0, 0, 0, 1}));
    for (const double sign : {1.0, -1.0}) {
        auto moved = render_references(library, sequence, sign);
        if (!moved.ok()) return moved.error();
        for (size_t f = 0; f < references.size(); ++f) {
            const Image& a = references[f];
            const Image& b = moved.value()[f];
            for (int y = 0; y < a.height; ++y)
                for (int x = 0; x < a.width; ++x) {
                    float change = 0;
                    for (int c = 0; c < 3; ++c) change = std::max(change, std::abs(a.at(x, y)[c] - b.at(x, y)[c]));
                    if (change < kFlip) continue;
                    float* o = out[f].at(x, y);
                    // Stored as 8 bits, rounded up, at most 1.
                    const float v = static_cast<float>(std::ceil(std::min(1.0f, std::max(o[0], change)) * 255.0f) / 255.0);
                    o[0] = o[1] = o[2] = v;
                }
        }
    }
    return out;
}

Result<Image> load_golden_unstable(const GoldenEntry& entry, const std::string& dir) {
    if (entry.unstable == 0) return Image{};
    auto image = read_image(dir + "/" + entry.unstable_file());
    if (!image.ok()) return image.error();
    if (image.value().width != entry.width || image.value().height != entry.height)
        return make_error("the unstable-pixel map of golden " + entry.id + " is not " + std::to_string(entry.width) + "x" +
                              std::to_string(entry.height) + ": run crtforge golden update",
                          dir + "/" + entry.unstable_file());
    return image;
}

namespace {

// What a half-float OpenEXR keeps of a value (write_exr clamps magnitudes to the largest half).
float to_half(float v) { return static_cast<float>(static_cast<_Float16>(std::clamp(v, -65504.0f, 65504.0f))); }

// What the golden's file keeps of an image: 16-bit codes of 0..1 (PNG) or half floats (EXR).
void quantise_golden(Image& image, bool hdr) {
    for (float& v : image.rgba)
        v = hdr ? to_half(v) : static_cast<float>(std::lround(std::clamp(static_cast<double>(v), 0.0, 1.0) * 65535.0) / 65535.0);
}

// Whether the reference leaves 0..1 anywhere in RGB.
bool leaves_unit_range(const Image& image) {
    for (size_t i = 0; i < image.rgba.size(); ++i)
        if (i % 4 != 3 && (image.rgba[i] < 0.0f || image.rgba[i] > 1.0f)) return true;
    return false;
}

}  // namespace

std::string golden_hash(const Image& image, bool hdr) {
    std::string bytes;
    bytes.reserve(image.rgba.size() * 2);
    for (float v : image.rgba) {
        uint16_t code = 0;
        if (hdr) {
            const _Float16 h = static_cast<_Float16>(std::clamp(v, -65504.0f, 65504.0f));
            std::memcpy(&code, &h, sizeof code);
        } else {
            code = static_cast<uint16_t>(std::lround(std::clamp(static_cast<double>(v), 0.0, 1.0) * 65535.0));
        }
        bytes += static_cast<char>(code & 0xffu);
        bytes += static_cast<char>(code >> 8);
    }
    return Cache::key({hdr ? "golden-half" : "golden-16bit", std::to_string(image.width), std::to_string(image.height), bytes});
}

Result<std::string> golden_inputs_hash(const TemplateLibrary& library, const GoldenEntry& entry) {
    const Preset* preset = library.find_preset(entry.preset);
    if (!preset) return make_error("golden " + entry.id + " names preset '" + entry.preset + "', which the templates do not have");
    // Everything the golden follows from, as text: the oracle's code, the input, the sizes, and the
    // preset as resolved (scene, LUTs, passes, every stage's form and values), with the stage
    // specs and snippets it uses and the shared prelude.
    std::vector<std::string> parts = {"golden-inputs/1", reference_source_hash(), entry.input,
                                      fmt::format("{}x{} {}x{} f{} {}", entry.width, entry.height, entry.input_width,
                                                  entry.input_height, entry.frame, entry.fit ? display_fit_name(*entry.fit) : "-")};
    // The configuration: what the host sets and the variant the targets compile.
    std::string config = fmt::format("config {} start {} uniforms {} precision {} host {}", entry.config, entry.start_time,
                                     entry.uniforms.str(), precision_name(entry.precision), entry.host);
    for (const auto& [name, value] : entry.overrides) config += " " + name + "=" + value_to_exact_string(value);
    parts.push_back(config);
    const SceneSettings& sc = preset->scene;
    parts.push_back(fmt::format("scene {}x{} {}:{} {} {} {}:{} {}", sc.source_width, sc.source_height, sc.pixel_aspect_x,
                                sc.pixel_aspect_y, source_fit_name(sc.source_fit), display_fit_name(sc.fit), sc.screen_aspect_x,
                                sc.screen_aspect_y, sc.fps));
    for (const LutSpec& lut : preset->luts) {
        std::string text = "lut " + lut.name + " " + lut.generator + " " + lut.file + " " + filter_name(lut.filter) + " " + wrap_name(lut.wrap);
        for (const auto& [name, value] : lut.params) text += fmt::format(" {}={}", name, value);
        if (!lut.generator.empty()) parts.push_back(text);
        else if (lut.bytes) parts.push_back(text + "\n" + *lut.bytes);
        else if (auto data = read_text_file(lut_file_path(lut), kMaxLutFileBytes); data.ok()) parts.push_back(text + "\n" + data.value());
        else return data.error();
    }
    std::map<std::string, const StageSpec*> stages;
    for (const Pass& pass : preset->passes) {
        std::string text = fmt::format("pass {} {} {} {} {} {} {} mod {} supersample {}", pass.alias, scale_type_name(pass.scale_x.type),
                                       pass.scale_x.factor, scale_type_name(pass.scale_y.type), pass.scale_y.factor,
                                       pixel_format_name(pass.format), preset->filter == Filter::Nearest ? "nearest" : "linear",
                                       pass.frame_count_mod, pass.supersample);
        for (const PassInput& in : pass.inputs)
            text += fmt::format(" [{} {} {} {} {}{}]", in.binding, in.from.str(), filter_name(in.filter), wrap_name(in.wrap), in.mipmap,
                                in.mipmap ? std::string(" ") + filter_name(in.mip_filter) : std::string());
        for (const ResolvedStage& st : pass.stages) {
            text += "\n  " + st.stage->name + "/" + st.form->name;
            for (const auto& [name, value] : st.values) text += " " + name + "=" + value_to_exact_string(value);
            // A program form (an imported RetroArch pass) carries its own two files.
            if (st.form->program()) text += "\n" + st.form->vertex_source + "\n" + st.form->fragment_source;
            stages[st.stage->name] = st.stage;
        }
        parts.push_back(text);
    }
    for (const auto& [name, stage] : stages) {
        auto spec = read_text_file(stage->where.file, detail::kMaxTomlBytes);
        if (!spec.ok()) return spec.error();
        parts.push_back(spec.value());
        parts.push_back(stage->glsl_source);
    }
    // The declared tiers: a golden of the preset stands for them too (their changes, as resolved).
    for (const DeclaredTier& tier : preset->tiers) {
        std::string text = "tier " + tier.name;
        for (const std::string& change : tier.changes) text += "\n  " + change;
        parts.push_back(text);
    }
    parts.push_back(library.prelude_source());
    parts.push_back(library.vertex_source());  // fullscreen.vert: every pass's vertex stage
    std::string all;  // length-prefixed, so no two lists of parts join to the same text
    for (const std::string& part : parts) all += std::to_string(part.size()) + ":" + part;
    return Cache::key({all});
}

Status check_golden_current(const TemplateLibrary& library, const GoldenEntry& entry, const std::string& dir) {
    auto inputs = golden_inputs_hash(library, entry);
    if (!inputs.ok()) return inputs.error();
    if (inputs.value() != entry.inputs_hash)
        return make_error("golden " + entry.id + " is stale (its preset, stage specs, templates, input or the reference changed "
                          "since it was made): run crtforge golden " +
                              (entry.approved ? "approve --filter " + entry.id + " after reviewing a render" : "update"),
                          dir + "/manifest.json");
    return Ok{};
}

Result<Image> load_golden_image(const TemplateLibrary& library, const GoldenEntry& entry, const std::string& dir) {
    if (auto current = check_golden_current(library, entry, dir); !current.ok()) return current.error();
    if (entry.stored) return read_image(dir + "/" + entry.file());
    // An entry that a filtered update never rendered has nothing to check the reference against.
    if (entry.hash.empty())
        return make_error("golden " + entry.id + " has never been rendered (no hash): run 'crtforge golden update'", dir + "/manifest.json");
    auto image = render_golden_reference(library, entry);
    if (!image.ok()) return image;
    quantise_golden(image.value(), entry.hdr);
    if (golden_hash(image.value(), entry.hdr) != entry.hash)
        return make_error("golden " + entry.id + " is rendered, not stored, and the reference no longer renders it as it did "
                          "at 'crtforge golden update': review the change and run it",
                          dir + "/manifest.json");
    return image;
}

Result<Image> render_golden_reference(const TemplateLibrary& library, const GoldenEntry& entry) {
    auto images = render_golden_references(library, {&entry});
    if (!images.ok()) return images.error();
    return std::move(images.value().front());
}

Result<std::vector<GoldenEntry>> load_golden_manifest(const std::string& dir) {
    const std::string path = dir + "/manifest.json";
    auto text = read_text_file(path, kMaxDataFileBytes);
    if (!text.ok() && std::filesystem::exists(path)) return text.error();
    if (!text.ok()) return make_error("no golden manifest (run 'crtforge golden update')", path);
    json j = json::parse(text.value(), nullptr, false);
    if (j.is_discarded() || !j.contains("goldens")) return make_error("not a golden manifest", path);
    std::vector<GoldenEntry> out;
    try {
        for (const auto& g : j["goldens"]) {
            std::optional<DisplayFit> fit;
            if (g.contains("fit")) {
                const std::string name = g.at("fit");
                for (DisplayFit f : {DisplayFit::Stretch, DisplayFit::Aspect, DisplayFit::Integer})
                    if (name == display_fit_name(f)) fit = f;
                if (!fit) return make_error("golden fit '" + name + "' is not stretch, aspect or integer", path);
            }
            GoldenEntry e = make_golden_entry(g.at("preset"), g.at("input"), g.at("width"), g.at("height"),
                                              g.at("inputWidth"), g.at("inputHeight"), g.at("frame"), fit);
            e.config = g.value("config", "");
            if (g.contains("overrides"))
                for (const auto& [name, value] : g.at("overrides").items()) e.overrides[name] = json_value(value);
            auto uniforms = UniformSelection::parse(g.value("uniforms", "default"));
            if (!uniforms.ok()) return make_error("golden " + e.config + ": " + uniforms.error().message, path);
            e.uniforms = uniforms.value();
            e.precision = g.value("precision", "high") == "medium" ? Precision::Medium : Precision::High;
            e.start_time = g.value("startTime", 0.0);
            e.full_matrix = g.value("matrix", "main") == "full";
            e.targets = g.value("targets", std::vector<std::string>{});
            e.host = g.value("host", "");
            e.shares = g.value("shares", "");
            if (g.contains("expectFail")) {
                const auto& x = g.at("expectFail");
                e.expect_fail_targets = x.at("targets").get<std::vector<std::string>>();
                e.expect_fail_why = x.at("why");
                e.expect_fail_bound = e.tolerance;  // a manifest from before bounds: the strict tolerance
                if (x.contains("bound")) {
                    const auto& b = x.at("bound");
                    e.expect_fail_bound = {b.at("maxRmse"), b.at("outlierThreshold"), b.at("maxOutlierFraction"), b.at("minSsim"),
                                           b.at("maxTileRmse"), e.expect_fail_why};
                }
            }
            e.id = golden_id(e);
            e.stored = g.value("stored", true);
            e.hash = g.value("hash", "");
            e.inputs_hash = g.value("inputsHash", "");
            e.hdr = g.value("format", "png") == "exr";
            e.approved = g.value("origin", "reference") == "approved";
            e.unstable = g.value("unstable", 0);
            const auto& t = g.at("tolerance");
            e.tolerance = {t.at("maxRmse"), t.at("outlierThreshold"), t.at("maxOutlierFraction"), t.at("minSsim"),
                           t.value("maxTileRmse", 0.0), t.at("why")};
            if (g.at("id") != e.id) return make_error("golden id '" + g.at("id").get<std::string>() + "' does not match its fields", path);
            out.push_back(std::move(e));
        }
    } catch (const std::exception& ex) {
        return make_error(std::string("malformed golden manifest: ") + ex.what(), path);
    }
    return out;
}

Result<std::vector<GoldenEntry>> golden_plan_with_state(const TemplateLibrary& library, const std::string& dir) {
    auto planned = golden_plan(library, dir);
    if (!planned.ok()) return planned.error();
    std::vector<GoldenEntry> plan = std::move(planned.value());
    std::map<std::string, const GoldenEntry*> old;
    auto manifest = load_golden_manifest(dir);
    // No manifest yet is a fresh start; one that does not load must not silently lose every
    // golden's recorded state.
    if (!manifest.ok() && std::filesystem::exists(dir + "/manifest.json")) return manifest.error();
    if (manifest.ok())
        for (const GoldenEntry& e : manifest.value()) old[e.id] = &e;
    for (GoldenEntry& e : plan)
        if (auto it = old.find(e.id); it != old.end()) {
            e.hash = it->second->hash;
            e.inputs_hash = it->second->inputs_hash;
            e.hdr = it->second->hdr;
            e.approved = it->second->approved;
            e.unstable = it->second->unstable;
        }
    return plan;
}

void store_golden_pixels(GoldenEntry& entry, Image& image) {
    entry.hdr = leaves_unit_range(image);
    quantise_golden(image, entry.hdr);
    entry.hash = golden_hash(image, entry.hdr);
}

namespace {

// Writes an entry's image file (PNG or EXR as entry.hdr says), removing the other format's file.
Status write_golden_file(const std::string& dir, const GoldenEntry& entry, const Image& image) {
    GoldenEntry other = entry;
    other.hdr = !entry.hdr;
    std::error_code ec;
    std::filesystem::remove(dir + "/" + other.file(), ec);
    return entry.hdr ? write_exr(dir + "/" + entry.file(), image) : write_png(dir + "/" + entry.file(), image, 16);
}

}  // namespace

Result<GoldenUpdate> update_goldens(const TemplateLibrary& library, const std::string& dir, const std::string& filter) {
    auto planned = golden_plan_with_state(library, dir);
    if (!planned.ok()) return planned.error();
    std::vector<GoldenEntry>& plan = planned.value();
    GoldenUpdate result;
    result.planned = plan.size();
    // Render everything first: a failure must not leave a half-updated golden set. An entry that
    // shares its owner's reference (GoldenEntry::shares) takes the owner's pixels: each image is
    // rendered once, its owner rendered too when only the sharer is chosen.
    std::map<std::string, GoldenEntry*> by_id;
    for (GoldenEntry& e : plan) by_id[e.id] = &e;
    std::vector<GoldenEntry*> chosen;
    std::vector<const GoldenEntry*> owners;
    std::set<std::string> rendering;  // ids in `chosen`
    for (GoldenEntry& e : plan) {
        if (!filter.empty() && e.id.find(filter) == std::string::npos) continue;
        const Preset* preset = library.find_preset(e.preset);
        if (auto models = preset ? reference_models(*preset) : Status(Ok{}); !models.ok()) {
            // A user's own stage: only an approved golden can stand for it.
            if (!e.approved) {
                result.unmodelled.push_back(e.id);
                if (result.unmodelled_reason.empty()) result.unmodelled_reason = models.error().message;
            }
            continue;
        }
        // The owner writes the files its sharers read, so it is updated with them.
        GoldenEntry* owner = e.shares.empty() ? &e : by_id.at(e.shares);
        for (GoldenEntry* x : {owner, &e})
            if (rendering.insert(x->id).second) chosen.push_back(x);
        if (std::find(owners.begin(), owners.end(), owner) == owners.end()) owners.push_back(owner);
    }
    std::map<std::string, std::pair<Image, Image>> pictures;  // owner id -> (reference, unstable map)
    // A line on stderr at most every 10 s while it renders: long work is never silent.
    const auto sequences = golden_sequences(owners);
    auto last_said = std::chrono::steady_clock::now();
    size_t sequences_done = 0;
    for (const auto& sequence : sequences) {
        if (std::chrono::steady_clock::now() - last_said >= std::chrono::seconds(10)) {
            std::fprintf(stderr, "golden update: %zu/%zu sequences rendered\n", sequences_done, sequences.size());
            last_said = std::chrono::steady_clock::now();
        }
        ++sequences_done;
        auto rendered = render_golden_references(library, sequence);
        if (!rendered.ok()) return rendered.error();
        auto flips = render_golden_unstable(library, sequence, rendered.value());
        if (!flips.ok()) return flips.error();
        for (size_t i = 0; i < sequence.size(); ++i)
            pictures[sequence[i]->id] = {std::move(rendered.value()[i]), std::move(flips.value()[i])};
    }
    for (GoldenEntry* entry : chosen) {
        auto made_of = golden_inputs_hash(library, *entry);
        if (!made_of.ok()) return made_of.error();
        entry->inputs_hash = made_of.value();
        entry->approved = false;
        Image image = pictures.at(entry->shares.empty() ? entry->id : entry->shares).first;
        const Image& flips = pictures.at(entry->shares.empty() ? entry->id : entry->shares).second;
        store_golden_pixels(*entry, image);
        // The unstable-pixel map is kept for every golden (small: mostly black), stored or not.
        entry->unstable = 0;
        for (int y = 0; y < flips.height; ++y)
            for (int x = 0; x < flips.width; ++x) entry->unstable += flips.at(x, y)[0] > 0;
        if (!entry->shares.empty()) continue;  // its owner writes the files
        std::error_code ec;
        std::filesystem::remove(dir + "/" + entry->unstable_file(), ec);
        if (entry->unstable)
            if (auto written = write_png(dir + "/" + entry->unstable_file(), flips, 8); !written.ok()) return written.error();
        if (!entry->stored) continue;
        if (auto written = write_golden_file(dir, *entry, image); !written.ok()) return written.error();
    }
    if (auto s = write_golden_manifest(dir, plan); !s.ok()) return s.error();
    result.written = chosen.size();
    return result;
}

Result<GoldenUpdate> approve_goldens(const TemplateLibrary& library, const std::string& dir, const std::string& filter,
                                     const EngineOptions& vulkan) {
    auto planned = golden_plan_with_state(library, dir);
    if (!planned.ok()) return planned.error();
    std::vector<GoldenEntry>& plan = planned.value();
    std::vector<const GoldenEntry*> chosen;
    for (const GoldenEntry& e : plan)
        if (e.id.find(filter) != std::string::npos) chosen.push_back(&e);
    if (chosen.empty()) return make_error("no planned golden's id contains '" + filter + "'", dir + "/plan.toml", 0, "--filter");
    // A golden the reference can render stays the reference's: a Vulkan render approved in its
    // place would make validate judge Vulkan against itself. Refused before anything is written.
    for (const GoldenEntry* e : chosen)
        if (const Preset* preset = library.find_preset(e->preset); preset && reference_models(*preset).ok())
            return make_error("golden '" + e->id + "' is rendered by the reference (crtforge golden update); approve only goldens of "
                              "stages the reference has no model of (narrow the filter)",
                              dir + "/plan.toml", 0, "--filter");
    TargetRenderer renderer(vulkan);
    Cache cache;
    std::vector<std::pair<const GoldenEntry*, Image>> images;
    for (const auto& sequence : golden_sequences(chosen)) {
        const GoldenEntry& first = *sequence.front();
        const Preset* preset = library.find_preset(first.preset);
        if (!preset) return make_error("golden '" + first.id + "' names unknown preset '" + first.preset + "'");
        auto passes = compile_scene(library, *preset, first.variant_options(), cache);
        if (!passes.ok()) return passes.error();
        SceneRenderRequest request = golden_scene_request(sequence, *preset, passes.value(), TargetId::Spirv);
        auto luts = read_file_luts(*preset);
        if (!luts.ok()) return luts.error();
        request.file_luts = std::move(luts.value());
        auto rendered = renderer.render_scene(request);
        if (!rendered.ok()) return rendered.error();
        for (size_t i = 0; i < sequence.size(); ++i) images.emplace_back(sequence[i], std::move(rendered.value()[i]));
    }
    for (auto& [entry_ptr, image] : images) {
        GoldenEntry& entry = const_cast<GoldenEntry&>(*entry_ptr);  // an element of `plan`
        auto made_of = golden_inputs_hash(library, entry);
        if (!made_of.ok()) return made_of.error();
        entry.inputs_hash = made_of.value();
        entry.approved = true;
        entry.stored = true;  // nothing else can render it again
        entry.unstable = 0;
        std::error_code ec;
        std::filesystem::remove(dir + "/" + entry.unstable_file(), ec);
        store_golden_pixels(entry, image);
        if (auto written = write_golden_file(dir, entry, image); !written.ok()) return written.error();
    }
    if (auto s = write_golden_manifest(dir, plan); !s.ok()) return s.error();
    GoldenUpdate result;
    result.written = images.size();
    result.planned = plan.size();
    return result;
}

Status write_golden_manifest(const std::string& dir, const std::vector<GoldenEntry>& entries) {
    json manifest;
    manifest["note"] = "Reference images from the CPU double-precision renderer (reference/), or approved by a user where "
                       "marked (origin: approved). Regenerate only with: crtforge golden update / crtforge golden approve";
    manifest["goldens"] = json::array();
    for (const GoldenEntry& e : entries) {
        json entry{{"id", e.id}, {"file", e.file()}, {"format", e.hdr ? "exr" : "png"}, {"preset", e.preset}, {"input", e.input},
                   {"width", e.width}, {"height", e.height}, {"inputWidth", e.input_width}, {"inputHeight", e.input_height}};
        if (e.fit) entry["fit"] = display_fit_name(*e.fit);
        entry["frame"] = e.frame;
        if (!e.config.empty()) entry["config"] = e.config;
        if (!e.overrides.empty()) {
            json o = json::object();
            for (const auto& [name, value] : e.overrides) o[name] = value_json(value);
            entry["overrides"] = o;
        }
        if (e.uniforms.mode != UniformSelection::Mode::Default) entry["uniforms"] = e.uniforms.str();
        if (e.precision != Precision::High) entry["precision"] = precision_name(e.precision);
        if (e.start_time != 0) entry["startTime"] = e.start_time;
        if (e.full_matrix) entry["matrix"] = "full";
        if (!e.targets.empty()) entry["targets"] = e.targets;
        if (!e.host.empty()) entry["host"] = e.host;
        if (!e.shares.empty()) entry["shares"] = e.shares;
        if (!e.expect_fail_targets.empty()) {
            const Tolerance& b = e.expect_fail_bound;
            entry["expectFail"] = {{"targets", e.expect_fail_targets}, {"why", e.expect_fail_why},
                                   {"bound", {{"maxRmse", b.max_rmse}, {"outlierThreshold", b.outlier_threshold},
                                              {"maxOutlierFraction", b.max_outlier_fraction}, {"minSsim", b.min_ssim},
                                              {"maxTileRmse", b.max_tile_rmse}}}};
        }
        if (!e.stored) entry["stored"] = false;
        if (e.approved) entry["origin"] = "approved";
        if (e.unstable) entry["unstable"] = e.unstable;
        if (!e.hash.empty()) entry["hash"] = e.hash;
        if (!e.inputs_hash.empty()) entry["inputsHash"] = e.inputs_hash;
        entry["tolerance"] = {{"maxRmse", e.tolerance.max_rmse}, {"outlierThreshold", e.tolerance.outlier_threshold},
                              {"maxOutlierFraction", e.tolerance.max_outlier_fraction}, {"minSsim", e.tolerance.min_ssim},
                              {"maxTileRmse", e.tolerance.max_tile_rmse}, {"why", e.tolerance.why}};
        manifest["goldens"].push_back(std::move(entry));
    }
    return write_file_atomic(dir + "/manifest.json", manifest.dump(2) + "\n");
}

Tolerance with_filter_step(Tolerance t, double step) {
    if (step <= 0) return t;
    const double rms = step / std::sqrt(12.0);
    t.max_rmse += rms;
    if (t.max_tile_rmse > 0) t.max_tile_rmse += rms;  // 0: no tile bound
    t.why += fmt::format(" Plus {:.5f} on the RMSE bounds: this consumer's linear samples of 8-bit textures come in steps of {:.5f}.",
                         rms, step);
    return t;
}

Result<Verdict> judge(const Image& render, const Image& reference, const Tolerance& t, double output_quantum, const Image* unstable) {
    if (unstable && !unstable->empty() && (unstable->width != reference.width || unstable->height != reference.height))
        return make_error("the unstable-pixel map does not have the golden's size");
    // Values are compared as they are, HDR included; a consumer whose display is 8-bit cannot show
    // what leaves 0..1, so there both sides are clamped.
    Image clamped = render;
    Image clamped_golden;
    const bool clamp = output_quantum > 0;
    if (clamp) {
        clamped_golden = reference;
        for (float& v : clamped.rgba) v = std::clamp(v, 0.0f, 1.0f);
        for (float& v : clamped_golden.rgba) v = std::clamp(v, 0.0f, 1.0f);
        // Such a display also composites: the golden's alpha over the black its hosts draw first.
        for (size_t p = 0; p < clamped_golden.pixel_count(); ++p) {
            float* px = clamped_golden.rgba.data() + p * 4;
            for (int c = 0; c < 3; ++c) px[c] *= px[3];
            px[3] = 1.0f;
        }
    }
    const Image& golden = clamp ? clamped_golden : reference;
    auto metrics = compare_images(clamped, golden);
    if (!metrics.ok()) return metrics.error();
    Verdict v;
    v.metrics = metrics.value();
    const int w = golden.width, h = golden.height;
    // Per pixel: the error d and the golden's own variation around it, the most a sub-pixel shift
    // of the sampling (another driver's rounding at a discontinuity) can move the value.
    std::vector<float> d(static_cast<size_t>(w) * h), edge(static_cast<size_t>(w) * h);
    double squares = 0;
    const float* r = clamped.rgba.data();
    const float* g = golden.rgba.data();
    const size_t stride = static_cast<size_t>(w) * 4;
    for (int y = 0; y < h; ++y) {
        const int y0 = std::max(0, y - 1), y1 = std::min(h - 1, y + 1);
        for (int x = 0; x < w; ++x) {
            const int x0 = std::max(0, x - 1), x1 = std::min(w - 1, x + 1);
            const size_t at = static_cast<size_t>(y) * stride + static_cast<size_t>(x) * 4;
            float worst = 0, around = 0;
            const float flip = unstable && !unstable->empty() ? unstable->at(x, y)[0] : 0.0f;
            for (int c = 0; c < 3; ++c) {
                // Above 1 (HDR) errors are relative: half floats, every consumer's output, keep a
                // relative step.
                const float scale = std::max(1.0f, std::abs(g[at + c]));
                const float e = std::abs(r[at + c] - g[at + c]) / scale;
                worst = std::max(worst, e);
                // The RMSE counts what a flip of the reference under jitter does not explain.
                const double beyond = std::max(0.0f, e - flip);
                squares += beyond * beyond;
            }
            for (int ny = y0; ny <= y1; ++ny) {
                const float* row = g + static_cast<size_t>(ny) * stride;
                for (int nx = x0; nx <= x1; ++nx)
                    for (int c = 0; c < 3; ++c)
                        around = std::max(around, std::abs(row[nx * 4 + c] - g[at + c]) / std::max(1.0f, std::abs(g[at + c])));
            }
            around = std::max(around, flip);
            d[static_cast<size_t>(y) * w + x] = worst;
            edge[static_cast<size_t>(y) * w + x] = around;
        }
    }
    // The judged RMSE: relative above 1, beyond the reference's own flips (compare_images's plain
    // RMSE stays in the metrics' max and SSIM).
    v.metrics.rmse = std::sqrt(squares / std::max<size_t>(1, d.size() * 3));
    // SSIM, like the RMSE, over what the reference's own flips do not explain: a pixel whose
    // error is within its jitter allowance counts as the golden's (a mask cell edge exactly on a
    // pixel centre, every 11th column at maskSize 5.5, would otherwise weigh on the structure).
    if (unstable && !unstable->empty()) {
        Image explained = clamped;
        bool any = false;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t i = static_cast<size_t>(y) * w + x;
                const float flip = unstable->at(x, y)[0];
                if (flip > 0 && d[i] <= flip) {
                    for (int c = 0; c < 3; ++c) explained.rgba[i * 4 + c] = g[i * 4 + c];
                    any = true;
                }
            }
        if (any) {
            auto m = compare_images(explained, golden);
            if (!m.ok()) return m.error();
            v.metrics.ssim = m.value().ssim;
        }
    }
    size_t outliers = 0;
    for (size_t i = 0; i < d.size(); ++i) {
        if (d[i] > t.outlier_threshold + output_quantum + edge[i]) ++outliers;
        if (edge[i] <= 0.01f) v.flat_max = std::max(v.flat_max, static_cast<double>(d[i]));
    }
    v.outlier_fraction = d.empty() ? 0.0 : static_cast<double>(outliers) / d.size();
    // Tiles measure the error a discontinuity does not explain (beyond the pixel's edge allowance),
    // so flips along a bezel or mask edge are not counted twice, while a wrong row or patch in a
    // smooth area counts in full.
    constexpr int kTile = 16;
    for (int ty = 0; ty < h; ty += kTile)
        for (int tx = 0; tx < w; tx += kTile) {
            double sum = 0;
            int count = 0;
            for (int y = ty; y < std::min(h, ty + kTile); ++y)
                for (int x = tx; x < std::min(w, tx + kTile); ++x) {
                    const size_t i = static_cast<size_t>(y) * w + x;
                    const double e = std::max(0.0f, d[i] - edge[i]);
                    sum += e * e;
                    ++count;
                }
            v.max_tile_rmse = std::max(v.max_tile_rmse, std::sqrt(sum / count));
        }
    // Alpha: what the shader writes reaches the user's compositor, so a wrong alpha is a wrong
    // picture there. A pixel may differ where the golden's alpha changes within 3x3 (the bezel edge).
    if (!clamp) {
        size_t alpha_off = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t at = (static_cast<size_t>(y) * w + x) * 4 + 3;
                float around = 0;
                for (int ny = std::max(0, y - 1); ny <= std::min(h - 1, y + 1); ++ny)
                    for (int nx = std::max(0, x - 1); nx <= std::min(w - 1, x + 1); ++nx)
                        around = std::max(around, std::abs(g[(static_cast<size_t>(ny) * w + nx) * 4 + 3] - g[at]));
                alpha_off += std::abs(r[at] - g[at]) > 0.01f + around;
            }
        v.alpha_outlier_fraction = static_cast<double>(alpha_off) / std::max<size_t>(1, d.size());
    }
    std::vector<std::string> failures;
    if (v.alpha_outlier_fraction > t.max_outlier_fraction)
        failures.push_back(fmt::format("{:.3f}% of pixels have an alpha off by more than 0.01 (allowed {:.2f}%)",
                                       100 * v.alpha_outlier_fraction, 100 * t.max_outlier_fraction));
    const double quantum_rms = output_quantum / std::sqrt(3.0);
    const double max_rmse = t.max_rmse + quantum_rms, max_tile = t.max_tile_rmse + quantum_rms;
    if (v.metrics.rmse > max_rmse) failures.push_back(fmt::format("RMSE {:.5f} > {:.5f}", v.metrics.rmse, max_rmse));
    if (t.max_tile_rmse > 0 && v.max_tile_rmse > max_tile)
        failures.push_back(fmt::format("a 16x16 tile has RMSE {:.4f} > {:.4f}", v.max_tile_rmse, max_tile));
    if (v.outlier_fraction > t.max_outlier_fraction)
        failures.push_back(fmt::format("{:.3f}% of pixels off by more than {:.4f} plus their edge allowance (allowed {:.2f}%)",
                                       100 * v.outlier_fraction, t.outlier_threshold + output_quantum, 100 * t.max_outlier_fraction));
    if (v.metrics.ssim < t.min_ssim) failures.push_back(fmt::format("SSIM {:.4f} < {}", v.metrics.ssim, t.min_ssim));
    v.passed = failures.empty();
    for (const auto& f : failures) v.reason += (v.reason.empty() ? "" : "; ") + f;
    return v;
}

}  // namespace crtforge
