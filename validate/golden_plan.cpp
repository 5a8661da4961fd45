// golden/plan.toml -> the list of goldens: which presets, inputs, sizes and frames have a reference.
#include <filesystem>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "crtforge/files.hpp"
#include "crtforge/targets.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/validate/golden.hpp"
#include "crtforge/variant.hpp"
#include "generator/toml_reader.hpp"
#include "runtime/dawn/framework_check.hpp"

namespace crtforge {

namespace {

// One [[golden]] rule of the plan.
struct PlanRule {
    bool all_presets = false;   // every shipped preset
    bool stage_presets = false; // every stage-isolation preset (golden/stages/)
    bool tier_presets = false;  // every declared tier of a shipped preset (add_tier_presets)
    std::vector<std::string> except;  // presets left out of "all" / "stages"
    std::vector<std::string> presets;
    std::optional<Builtin> requires_builtin;  // only presets whose shaders read it
    std::vector<std::string> inputs;
    int width = 0, height = 0;
    std::vector<int> frames{0};
    std::optional<DisplayFit> fit;
    bool store = true;
    std::optional<std::pair<int, int>> input_size;
    // The configuration (see golden/plan.toml): the tag names it in the ids.
    std::string tag;
    std::vector<std::pair<std::string, Value>> params;  // set where the preset has them as uniforms
    int draws = 0;                                      // random draws of every uniform param
    uint64_t seed = 0;
    UniformSelection uniforms;
    Precision precision = Precision::High;
    double start_time = 0.0;
    bool full_matrix = false;
    std::vector<std::string> targets;
    std::optional<Tolerance> tolerance;
    std::vector<std::string> expect_fail_targets;
    std::string expect_fail_why;
    Tolerance expect_fail_bound;
    std::string host;  // godot = "defaults" | "material" | "screen", or one framework of `web`
    std::vector<std::string> web;  // web = "three" | [...]: a rule per framework (read(): tag-framework)
    int line = 0;
};

struct Plan {
    std::vector<PlanRule> rules;
};

class PlanReader {
public:
    explicit PlanReader(std::string path) : path_(std::move(path)) {}

    // A validation preset (golden/stages/<name>.toml: a stage alone, stage-*, or a pass-graph test,
    // graph-*): known by name even to a library that did not load them, which has no goldens of it
    // to plan. A library that did load them knows each by name, so a misspelt one is still an error there.
    bool is_stage_preset(const std::string& name, bool isolation_loaded) const {
        if (name.find('/') != std::string::npos) return false;
        const std::filesystem::path dir = std::filesystem::path(path_).parent_path() / "stages";
        return std::filesystem::is_regular_file(dir / (name + ".toml")) ||
               (!isolation_loaded && (name.rfind("stage-", 0) == 0 || name.rfind("graph-", 0) == 0));
    }

    // Whether the library holds golden/stages/'s presets (tier presets do not count).
    static bool validation_presets_loaded(const TemplateLibrary& library) {
        return std::any_of(library.presets().begin(), library.presets().end(),
                           [](const Preset& p) { return p.test_only && p.tier_of.empty(); });
    }

    Diagnostic error(const toml::node* node, const std::string& field, const std::string& message) const {
        return make_error(message, path_, node ? static_cast<int>(node->source().begin.line) : 0, field);
    }

    Result<std::vector<std::string>> names(const toml::table& t, const char* key, const std::string& field) const {
        const toml::node* node = t.get(key);
        const toml::array* a = node ? node->as_array() : nullptr;
        if (!a || a->empty()) return error(node ? node : &t, field, "must be a non-empty list of names");
        std::vector<std::string> out;
        for (const toml::node& n : *a) {
            if (!n.is_string()) return error(&n, field, "must be a list of names");
            out.push_back(std::string(*n.value<std::string>()));
        }
        return out;
    }

    Result<std::pair<int, int>> size(const toml::node* node, const std::string& field, bool source = false) const {
        const toml::array* a = node ? node->as_array() : nullptr;
        if (!a || a->size() != 2 || !a->get(0)->is_integer() || !a->get(1)->is_integer())
            return error(node, field, "must be [width, height]");
        const int64_t w = *a->get(0)->value<int64_t>(), h = *a->get(1)->value<int64_t>();
        if (w < 1 || h < 1 || w > kMaxImageDimension || h > kMaxImageDimension)
            return error(node, field, fmt::format("{}x{} is outside 1..{}", w, h, kMaxImageDimension));
        if (const std::string over = source ? source_budget_error(w, h) : render_budget_error(w, h); !over.empty())
            return error(node, field, fmt::format("{}x{} {}", w, h, over));
        return std::make_pair(static_cast<int>(w), static_cast<int>(h));
    }

    Result<Plan> read(const std::string& text, const TemplateLibrary& library) const {
        auto parsed = detail::TomlReader(path_).parse(text);
        if (!parsed.ok()) return parsed.error();
        const toml::table& root = parsed.value();
        Plan plan;
        const bool isolation_loaded = validation_presets_loaded(library);
        for (const auto& [key, node] : root)
            if (key != "golden") return error(&node, std::string(key.str()), "unknown key");
        const toml::node* rules = root.get("golden");
        const toml::array* array = rules ? rules->as_array() : nullptr;
        if (!array || !array->is_array_of_tables()) return error(rules ? rules : &root, "golden", "must be [[golden]] tables");
        for (const toml::node& node : *array) {
            const toml::table& t = *node.as_table();
            PlanRule rule;
            for (const auto& [key, value] : t) {
                static const char* known[] = {"why", "presets", "requires", "inputs", "size", "input_size", "frame", "frames", "fit",
                                              "store", "tag", "params", "draws", "seed", "uniforms", "precision", "time",
                                              "matrix", "targets", "tolerance", "expect_fail", "except", "godot", "web"};
                if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return key == k; }) == std::end(known))
                    return error(&value, "golden." + std::string(key.str()), "unknown key");
            }
            if (!t.get("why") || !t.get("why")->is_string()) return error(&node, "golden.why", "must say what the entry tests");
            if (const toml::node* p = t.get("presets"); p && p->is_string()) {
                const std::string which = *p->value<std::string>();
                if (which != "all" && which != "stages" && which != "tiers")
                    return error(p, "golden.presets", "must be \"all\", \"stages\", \"tiers\" or a list of presets");
                rule.all_presets = which == "all";
                rule.stage_presets = which == "stages";
                rule.tier_presets = which == "tiers";
            } else {
                auto list = names(t, "presets", "golden.presets");
                if (!list.ok()) return list.error();
                for (const auto& name : list.value())
                    if (!library.find_preset(name) && !is_stage_preset(name, isolation_loaded))
                        return error(t.get("presets"), "golden.presets", "unknown preset '" + name + "'");
                rule.presets = list.value();
            }
            if (t.get("except")) {
                if (!rule.all_presets && !rule.stage_presets && !rule.tier_presets)
                    return error(t.get("except"), "golden.except", "only with presets = \"all\", \"stages\" or \"tiers\"");
                auto list = names(t, "except", "golden.except");
                if (!list.ok()) return list.error();
                for (const auto& name : list.value())
                    if (!library.find_preset(name) && !is_stage_preset(name, isolation_loaded))
                        return error(t.get("except"), "golden.except", "unknown preset '" + name + "'");
                rule.except = list.value();
            }
            if (const toml::node* r = t.get("requires")) {
                const std::string what = r->is_string() ? *r->value<std::string>() : "";
                if (what != "time" && what != "frame_count")
                    return error(r, "golden.requires", "must be \"time\" or \"frame_count\"");
                rule.requires_builtin = what == "time" ? Builtin::Time : Builtin::FrameCount;
            }
            auto inputs = names(t, "inputs", "golden.inputs");
            if (!inputs.ok()) return inputs.error();
            for (const auto& name : inputs.value())
                if (test_input_doc(name).empty()) return error(t.get("inputs"), "golden.inputs", "unknown input '" + name + "'");
            rule.inputs = inputs.value();
            auto s = size(t.get("size") ? t.get("size") : &node, "golden.size");
            if (!s.ok()) return s.error();
            std::tie(rule.width, rule.height) = s.value();
            if (const toml::node* in = t.get("input_size")) {
                auto is = size(in, "golden.input_size", true);
                if (!is.ok()) return is.error();
                rule.input_size = is.value();
            }
            auto frame_number = [&](const toml::node& f) -> Result<int> {
                // Past 2^24 frame counters leave float32's integers (parity, modulo): the hard case.
                if (!f.is_integer() || *f.value<int64_t>() < 0 || *f.value<int64_t>() > (int64_t{1} << 30))
                    return error(&f, "golden.frame", "must be a frame number 0..2^30");
                return static_cast<int>(*f.value<int64_t>());
            };
            if (t.get("frame") && t.get("frames")) return error(t.get("frames"), "golden.frames", "give frame or frames, not both");
            if (const toml::node* f = t.get("frame")) {
                auto n = frame_number(*f);
                if (!n.ok()) return n.error();
                rule.frames = {n.value()};
            }
            if (const toml::node* f = t.get("frames")) {
                const toml::array* a = f->as_array();
                if (!a || a->empty()) return error(f, "golden.frames", "must be a non-empty list of frame numbers");
                rule.frames.clear();
                for (const toml::node& item : *a) {
                    auto n = frame_number(item);
                    if (!n.ok()) return n.error();
                    rule.frames.push_back(n.value());
                }
            }
            if (const toml::node* st = t.get("store")) {
                if (!st->is_boolean()) return error(st, "golden.store", "must be true or false");
                rule.store = *st->value<bool>();
            }
            if (const toml::node* f = t.get("fit")) {
                const std::string name = f->value<std::string>().value_or("");
                for (DisplayFit fit : {DisplayFit::Stretch, DisplayFit::Aspect, DisplayFit::Integer})
                    if (name == display_fit_name(fit)) rule.fit = fit;
                if (!rule.fit) return error(f, "golden.fit", "must be \"stretch\", \"aspect\" or \"integer\"");
            }
            rule.line = static_cast<int>(node.source().begin.line);
            if (auto s = read_configuration(t, library, rule); !s.ok()) return s.error();
            // `web` with several frameworks: a rule each, tagged "<tag>-<framework>".
            for (size_t k = 0; k < rule.web.size(); ++k) {
                PlanRule one = rule;
                one.host = rule.web[k];
                if (rule.web.size() > 1) one.tag += "-" + rule.web[k];
                plan.rules.push_back(std::move(one));
            }
            if (rule.web.empty()) plan.rules.push_back(std::move(rule));
        }
        return plan;
    }

    // The configuration keys of a rule: tag, params, draws, seed, uniforms, precision, time,
    // matrix, targets, tolerance.
    Status read_configuration(const toml::table& t, const TemplateLibrary& library, PlanRule& rule) const {
        static const char* config_keys[] = {"params", "draws", "uniforms", "precision", "time", "godot", "web"};
        const toml::node* tag = t.get("tag");
        if (tag) {
            const std::string text = tag->value<std::string>().value_or("");
            const bool word = !text.empty() && text.size() <= 32 &&
                              std::all_of(text.begin(), text.end(), [](char c) { return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '-'; });
            if (!word) return error(tag, "golden.tag", "must be 1..32 characters of a-z, 0-9 and '-' (it becomes part of file names)");
            rule.tag = text;
        }
        for (const char* key : config_keys)
            if (t.get(key) && rule.tag.empty()) return error(t.get(key), std::string("golden.") + key, "a configuration needs a tag (golden.tag) to name its goldens");
        if (const toml::node* p = t.get("params")) {
            const toml::table* table = p->as_table();
            if (!table || table->empty()) return error(p, "golden.params", "must be a table of param = value");
            for (const auto& [key, value] : *table) {
                const std::string name(key.str());
                const std::string field = "golden.params." + name;
                const ParamSpec* spec = library.find_param(name);
                if (!spec) return error(&value, field, "no stage has a param '" + name + "'");
                auto v = plan_value(value, *spec, field);
                if (!v.ok()) return v.error();
                rule.params.emplace_back(name, v.value());
            }
        }
        if (const toml::node* d = t.get("draws")) {
            if (!d->is_integer() || *d->value<int64_t>() < 1 || *d->value<int64_t>() > 64)
                return error(d, "golden.draws", "must be a number of draws 1..64");
            rule.draws = static_cast<int>(*d->value<int64_t>());
            const toml::node* seed = t.get("seed");
            if (!seed || !seed->is_integer() || *seed->value<int64_t>() < 0)
                return error(seed ? seed : d, "golden.seed", "draws need a fixed seed: a non-negative integer");
            rule.seed = static_cast<uint64_t>(*seed->value<int64_t>());
        } else if (t.get("seed")) {
            return error(t.get("seed"), "golden.seed", "a seed without draws");
        }
        if (rule.draws && !rule.params.empty()) return error(t.get("params"), "golden.params", "give params or draws, not both");
        if (const toml::node* u = t.get("uniforms")) {
            auto parsed = UniformSelection::parse(u->value<std::string>().value_or("?"));
            if (!parsed.ok() || parsed.value().mode == UniformSelection::Mode::Names)
                return error(u, "golden.uniforms", "must be \"default\", \"all\" or \"none\"");
            rule.uniforms = parsed.value();
        }
        if (const toml::node* pr = t.get("precision")) {
            const std::string name = pr->value<std::string>().value_or("");
            if (name != "high" && name != "medium") return error(pr, "golden.precision", "must be \"high\" or \"medium\"");
            rule.precision = name == "medium" ? Precision::Medium : Precision::High;
        }
        if (const toml::node* tm = t.get("time")) {
            const std::optional<double> v = tm->value<double>();
            if (!v || !(*v >= 0) || *v > 1e7) return error(tm, "golden.time", "must be seconds at frame 0, 0..1e7");
            rule.start_time = *v;
        }
        if (const toml::node* m = t.get("matrix")) {
            const std::string name = m->value<std::string>().value_or("");
            if (name != "main" && name != "full") return error(m, "golden.matrix", "must be \"main\" or \"full\"");
            rule.full_matrix = name == "full";
        }
        if (t.get("targets")) {
            auto list = names(t, "targets", "golden.targets");
            if (!list.ok()) return list.error();
            for (const auto& name : list.value())
                if (!find_target(name)) return error(t.get("targets"), "golden.targets", "unknown target '" + name + "'");
            rule.targets = list.value();
        }
        if (const toml::node* w = t.get("web")) {
            const char* what = "must be \"three\", \"pixi\", \"babylon\" or a list of them (the npm package's framework adapters)";
            std::vector<std::string> list;
            if (w->is_string()) list.push_back(*w->value<std::string>());
            else if (w->is_array()) {
                auto read = names(t, "web", "golden.web");
                if (!read.ok()) return error(w, "golden.web", what);
                list = read.value();
            }
            if (list.empty()) return error(w, "golden.web", what);
            for (const std::string& name : list) {
                if (!detail::is_web_framework(name)) return error(w, "golden.web", what);
                if (std::count(list.begin(), list.end(), name) > 1) return error(w, "golden.web", "names '" + name + "' twice");
            }
            if (t.get("godot")) return error(w, "golden.web", "a rule has one host: godot or web, not both");
            if (rule.targets != std::vector<std::string>{"wgsl"})
                return error(w, "golden.web", "a framework adapter runs the WGSL target: give targets = [\"wgsl\"]");
            rule.web = list;
        }
        if (const toml::node* gd = t.get("godot")) {
            const std::string mode = gd->value<std::string>().value_or("");
            if (mode != "defaults" && mode != "material" && mode != "screen")
                return error(gd, "golden.godot", "must be \"defaults\", \"material\" or \"screen\"");
            for (const std::string& target : rule.targets)
                if (target != "godot3" && target != "godot4")
                    return error(gd, "golden.godot", "a Godot host mode needs targets among [\"godot3\", \"godot4\"]");
            if (rule.targets.empty()) return error(gd, "golden.godot", "a Godot host mode needs targets among [\"godot3\", \"godot4\"]");
            rule.host = mode;
        }
        if (const toml::node* x = t.get("expect_fail")) {
            const toml::table* table = x->as_table();
            if (!table || !table->get("targets") || !table->get("why") || !table->get("why")->is_string() || !table->get("bound") ||
                table->size() != 3)
                return error(x, "golden.expect_fail",
                             "must be { targets = [names], why = \"the tracked defect\", bound = { rmse, pixel, outliers, ssim, tile } }");
            auto bound = tolerance(*table->get("bound"), "golden.expect_fail.bound", false);
            if (!bound.ok()) return bound.error();
            rule.expect_fail_bound = bound.value();
            auto list = names(*table, "targets", "golden.expect_fail.targets");
            if (!list.ok()) return list.error();
            for (const auto& name : list.value()) {
                const std::string base = name.substr(0, name.find('@'));  // "spirv@swiftshader": a second driver's
                if (!find_target(base)) return error(table->get("targets"), "golden.expect_fail.targets", "unknown target '" + name + "'");
            }
            rule.expect_fail_targets = list.value();
            rule.expect_fail_why = *table->get("why")->value<std::string>();
        }
        if (const toml::node* tol = t.get("tolerance")) {
            auto read = tolerance(*tol, "golden.tolerance", true);
            if (!read.ok()) return read.error();
            rule.tolerance = read.value();
        }
        return Ok{};
    }

    // A runtime param's value: a number in its range, or a colour "#rrggbb" / [r, g, b].
    Result<Value> plan_value(const toml::node& node, const ParamSpec& spec, const std::string& field) const {
        if (spec.type == ParamType::Color) {
            Color c{};
            if (const auto* text = node.as_string(); text && parse_hex_color(text->get(), c)) return Value{c};
            return error(&node, field, "must be a colour \"#rrggbb\"");
        }
        if (spec.type != ParamType::Float && spec.type != ParamType::Int)
            return error(&node, field, "only float, int and colour params can be set (they are the runtime ones)");
        const std::optional<double> v = node.value<double>();
        if (!v || (spec.type == ParamType::Int && !node.is_integer())) return error(&node, field, std::string("must be a ") + param_type_name(spec.type));
        // nan compares false with both bounds: without this it reached the manifest as null.
        if (!std::isfinite(*v)) return error(&node, field, "must be a finite number");
        if ((spec.min && *v < *spec.min) || (spec.max && *v > *spec.max))
            return error(&node, field, fmt::format("{} is outside the param's range {}..{}", *v, spec.min.value_or(*v), spec.max.value_or(*v)));
        if (spec.type == ParamType::Int) return Value{static_cast<int64_t>(*v)};
        return Value{*v};
    }

    // tolerance = { rmse, pixel, outliers, ssim, tile, why }: unset bounds keep the default's.
    Result<Tolerance> tolerance(const toml::node& node, const std::string& prefix, bool needs_why) const {
        const toml::table* t = node.as_table();
        if (!t) return error(&node, prefix, "must be a table { rmse, pixel, outliers, ssim, tile" + std::string(needs_why ? ", why }" : " }"));
        Tolerance out = make_golden_entry("p", "i", 1, 1, 1, 1, 0).tolerance;
        const std::pair<const char*, double*> bounds[] = {{"rmse", &out.max_rmse}, {"pixel", &out.outlier_threshold},
                                                          {"outliers", &out.max_outlier_fraction}, {"ssim", &out.min_ssim},
                                                          {"tile", &out.max_tile_rmse}};
        for (const auto& [key, value] : *t) {
            const std::string field = prefix + "." + std::string(key.str());
            if (key == "why" && needs_why) {
                if (!value.is_string() || value.value<std::string>()->size() < 20)
                    return error(&value, field, "must say, specifically, why this golden needs its own tolerance");
                out.why = *value.value<std::string>();
                continue;
            }
            auto b = std::find_if(std::begin(bounds), std::end(bounds), [&](const auto& kv) { return key == kv.first; });
            if (b == std::end(bounds)) return error(&value, field, "unknown key (rmse, pixel, outliers, ssim, tile, why)");
            const std::optional<double> v = value.value<double>();
            if (!v || !(*v >= 0) || *v > 1) return error(&value, field, "must be a number 0..1");
            *b->second = *v;
        }
        if (needs_why && !t->get("why")) return error(&node, prefix + ".why", "must say, specifically, why this golden needs its own tolerance");
        return out;
    }

private:
    std::string path_;
};

// Whether any pass of the preset reads the builtin.
bool reads_builtin(const TemplateLibrary& library, const Preset& preset, Builtin builtin) {
    for (size_t pass = 0; pass < preset.passes.size(); ++pass) {
        auto variant = make_variant(library, preset, {}, pass);
        if (!variant.ok()) continue;
        const auto& b = variant.value().builtins;
        if (std::find(b.begin(), b.end(), builtin) != b.end()) return true;
    }
    return false;
}

// splitmix64: a fixed, portable sequence (std's distributions differ between libraries).
struct DrawSource {
    uint64_t state;
    uint64_t next() {
        uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
};

uint64_t name_hash(const std::string& text) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ull;
    return h;
}

// A value across the param's range, on its step grid where it has one.
Value draw_value(const ParamSpec& spec, DrawSource& source) {
    if (spec.type == ParamType::Color) {
        Color c{};
        for (double& v : c) v = std::floor(source.unit() * 256.0) / 255.0;
        return c;
    }
    const double lo = spec.min.value_or(0.0), hi = spec.max.value_or(1.0);
    double v = lo + source.unit() * (hi - lo);
    if (spec.step && *spec.step > 0) v = std::min(hi, lo + std::round((v - lo) / *spec.step) * *spec.step);
    if (spec.type == ParamType::Int) return static_cast<int64_t>(std::llround(v));
    return v;
}

// The params that are uniforms of the preset's variant under `options`, in every pass that reads them.
Result<std::set<std::string>> uniform_params(const TemplateLibrary& library, const Preset& preset, const VariantOptions& options) {
    std::set<std::string> out;
    for (size_t pass = 0; pass < preset.passes.size(); ++pass) {
        auto variant = make_variant(library, preset, options, pass);
        if (!variant.ok()) return variant.error();
        for (const VariantParam* p : variant.value().uniforms()) out.insert(p->spec->name);
    }
    return out;
}

// The configurations a rule asks of one preset: none when the preset lacks what it sets.
Result<std::vector<GoldenEntry>> configurations(const TemplateLibrary& library, const Preset& preset, const PlanRule& rule,
                                                const std::string& plan_path) {
    GoldenEntry base;
    base.config = rule.tag;
    base.uniforms = rule.uniforms;
    base.precision = rule.precision;
    base.start_time = rule.start_time;
    base.full_matrix = rule.full_matrix;
    base.targets = rule.targets;
    base.host = rule.host;
    base.expect_fail_targets = rule.expect_fail_targets;
    base.expect_fail_why = rule.expect_fail_why;
    base.expect_fail_bound = rule.expect_fail_bound;
    base.expect_fail_bound.why = rule.expect_fail_why;
    if (!rule.host.empty() && rule.web.empty()) {
        // Godot's shaders used alone: only a single pass that reads nothing but its picture has them.
        auto variant = make_variant(library, preset, base.variant_options());
        if (!preset.single_pass() || !variant.ok() || !variant.value().textures.empty()) return std::vector<GoldenEntry>{};
    }
    if (rule.params.empty() && !rule.draws) return std::vector<GoldenEntry>{base};
    auto uniforms = uniform_params(library, preset, base.variant_options());
    if (!uniforms.ok()) {
        Diagnostic d = uniforms.error();
        return make_error(preset.name + ": " + d.message, plan_path, rule.line, "golden.uniforms");
    }
    std::vector<GoldenEntry> out;
    if (!rule.params.empty()) {
        for (const auto& [name, value] : rule.params)
            if (uniforms.value().count(name)) base.overrides[name] = value;
        if (!base.overrides.empty()) out.push_back(base);
        return out;
    }
    if (uniforms.value().empty()) return out;
    for (int k = 0; k < rule.draws; ++k) {
        DrawSource source{rule.seed ^ name_hash(preset.name) ^ (0x632be59bd9b4e019ull * static_cast<uint64_t>(k + 1))};
        GoldenEntry e = base;
        e.config = rule.tag + std::to_string(k + 1);
        for (const std::string& name : uniforms.value()) e.overrides[name] = draw_value(*library.find_param(name), source);
        out.push_back(std::move(e));
    }
    return out;
}

}  // namespace

namespace {

// Entries with the same reference image share one set of files (GoldenEntry::shares): the first
// stored one of each group owns them (or the first, when none is stored).
void share_reference_images(std::vector<GoldenEntry>& entries) {
    std::map<std::string, std::vector<GoldenEntry*>> groups;
    std::vector<std::string> order;
    for (GoldenEntry& e : entries) {
        std::string key = fmt::format("{}|{}|{}x{}|{}x{}|{}|{}|{}", e.preset, e.input, e.width, e.height, e.input_width, e.input_height,
                                      e.fit ? display_fit_name(*e.fit) : "-", e.frame, e.start_time);
        for (const auto& [name, value] : e.overrides) key += "|" + name + "=" + value_to_exact_string(value);
        if (!groups.count(key)) order.push_back(key);
        groups[key].push_back(&e);
    }
    for (const std::string& key : order) {
        auto& group = groups[key];
        GoldenEntry* owner = group.front();
        for (GoldenEntry* e : group)
            if (e->stored) {
                owner = e;
                break;
            }
        for (GoldenEntry* e : group)
            if (e != owner) {
                e->shares = owner->id;
                e->stored = owner->stored;
            }
    }
}

}  // namespace

Status add_golden_presets(TemplateLibrary& library, const std::string& golden_dir) {
    if (auto s = library.add_test_presets(golden_dir + "/stages"); !s.ok()) return s;
    return library.add_tier_presets();
}

Result<std::vector<GoldenEntry>> golden_plan(const TemplateLibrary& library, const std::string& golden_dir) {
    const std::string path = golden_dir + "/plan.toml";
    auto text = read_text_file(path, detail::kMaxTomlBytes);
    if (!text.ok()) return text.error();
    auto plan = PlanReader(path).read(text.value(), library);
    if (!plan.ok()) return plan.error();
    std::vector<GoldenEntry> out;
    std::set<std::string> ids;
    for (const Preset& p : library.presets()) {

        for (const PlanRule& rule : plan.value().rules) {
            const bool named = std::find(rule.presets.begin(), rule.presets.end(), p.name) != rule.presets.end();
            const bool excepted = std::find(rule.except.begin(), rule.except.end(), p.name) != rule.except.end();
            const bool selected = !p.test_only ? rule.all_presets : p.tier_of.empty() ? rule.stage_presets : rule.tier_presets;
            const bool chosen = named || (!excepted && selected);
            if (!chosen || (rule.requires_builtin && !reads_builtin(library, p, *rule.requires_builtin))) continue;
            auto configs = configurations(library, p, rule, path);
            if (!configs.ok()) return configs.error();
            for (const GoldenEntry& config : configs.value())
                for (const std::string& input : rule.inputs) {
                    auto [iw, ih] = rule.input_size.value_or(std::make_pair(rule.width, rule.height));
                    // A scene that states its source size is fed pictures of that size.
                    if (p.scene.source_width) std::tie(iw, ih) = std::make_pair(p.scene.source_width, p.scene.source_height);
                    for (int frame : rule.frames) {
                        // A scene with feedback or history runs every frame before the one shown: the
                        // reference draws a 32x24 super-win frame in ~22 ms, so frames x pixels is bounded
                        // (a golden then takes at most a minute or two).
                        constexpr double kMaxSequencePixelFrames = 4e6;
                        const double work = (static_cast<double>(frame) + 1.0) * rule.width * rule.height;
                        if (p.keeps_state() && work > kMaxSequencePixelFrames)
                            return make_error(fmt::format("frame {} of '{}' at {}x{}: it keeps state between frames, so every frame "
                                                          "before it is drawn too; (frame + 1) x width x height may be at most {:.0f}",
                                                          frame, p.name, rule.width, rule.height, kMaxSequencePixelFrames),
                                              path, rule.line, "golden.frame");
                        // The configuration's entry, placed: make_golden_entry gives the rest.
                        const GoldenEntry placed = make_golden_entry(p.name, input, rule.width, rule.height, iw, ih, frame, rule.fit);
                        GoldenEntry e = config;
                        e.preset = placed.preset;
                        e.input = placed.input;
                        e.width = placed.width;
                        e.height = placed.height;
                        e.input_width = placed.input_width;
                        e.input_height = placed.input_height;
                        e.fit = placed.fit;
                        e.frame = placed.frame;
                        e.tolerance = rule.tolerance.value_or(placed.tolerance);
                        e.stored = rule.store;
                        e.id = golden_id(e);
                        if (!ids.insert(e.id).second)
                            return make_error("two rules make golden " + e.id + ": give one of them a tag", path, rule.line, "golden.tag");
                        out.push_back(std::move(e));
                    }
                }
        }
    }
    share_reference_images(out);
    return out;
}

}  // namespace crtforge
