// golden/plan.toml -> the list of goldens: which presets, inputs, sizes and frames have a reference.
#include <algorithm>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "crtforge/files.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/validate/golden.hpp"
#include "crtforge/variant.hpp"

namespace crtforge {

namespace {

// One [[golden]] rule of the plan.
struct PlanRule {
    bool all_presets = false;
    std::vector<std::string> presets;
    bool requires_time = false;
    std::vector<std::string> inputs;
    int width = 0, height = 0;
    std::vector<int> frames{0};
    std::optional<DisplayFit> fit;
    bool store = true;
    std::optional<std::pair<int, int>> input_size;
};

struct Plan {
    std::vector<PlanRule> rules;
};

class PlanReader {
public:
    explicit PlanReader(std::string path) : path_(std::move(path)) {}

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

    Result<std::pair<int, int>> size(const toml::node* node, const std::string& field) const {
        const toml::array* a = node ? node->as_array() : nullptr;
        if (!a || a->size() != 2 || !a->get(0)->is_integer() || !a->get(1)->is_integer())
            return error(node, field, "must be [width, height]");
        const int64_t w = *a->get(0)->value<int64_t>(), h = *a->get(1)->value<int64_t>();
        if (w < 1 || h < 1 || w > kMaxImageDimension || h > kMaxImageDimension)
            return error(node, field, fmt::format("{}x{} is outside 1..{}", w, h, kMaxImageDimension));
        return std::make_pair(static_cast<int>(w), static_cast<int>(h));
    }

    Result<Plan> read(const std::string& text, const TemplateLibrary& library) const {
        toml::table root;
        try {
            root = toml::parse(text, path_);
        } catch (const toml::parse_error& e) {
            return make_error(std::string(e.description()), path_, static_cast<int>(e.source().begin.line));
        }
        Plan plan;
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
                                              "store"};
                if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return key == k; }) == std::end(known))
                    return error(&value, "golden." + std::string(key.str()), "unknown key");
            }
            if (!t.get("why") || !t.get("why")->is_string()) return error(&node, "golden.why", "must say what the entry tests");
            if (const toml::node* p = t.get("presets"); p && p->is_string()) {
                if (*p->value<std::string>() != "all") return error(p, "golden.presets", "must be \"all\" or a list of presets");
                rule.all_presets = true;
            } else {
                auto list = names(t, "presets", "golden.presets");
                if (!list.ok()) return list.error();
                for (const auto& name : list.value())
                    if (!library.find_preset(name)) return error(t.get("presets"), "golden.presets", "unknown preset '" + name + "'");
                rule.presets = list.value();
            }
            if (const toml::node* r = t.get("requires")) {
                if (!r->is_string() || *r->value<std::string>() != "time") return error(r, "golden.requires", "must be \"time\"");
                rule.requires_time = true;
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
                auto is = size(in, "golden.input_size");
                if (!is.ok()) return is.error();
                rule.input_size = is.value();
            }
            auto frame_number = [&](const toml::node& f) -> Result<int> {
                if (!f.is_integer() || *f.value<int64_t>() < 0 || *f.value<int64_t>() > 1000000)
                    return error(&f, "golden.frame", "must be a frame number 0..1000000");
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
            plan.rules.push_back(std::move(rule));
        }
        return plan;
    }

private:
    std::string path_;
};

bool reads_time(const TemplateLibrary& library, const Preset& preset) {
    auto variant = make_variant(library, preset, {});
    if (!variant.ok()) return false;
    const auto& b = variant.value().builtins;
    return std::find(b.begin(), b.end(), Builtin::Time) != b.end();
}

}  // namespace

Result<std::vector<GoldenEntry>> golden_plan(const TemplateLibrary& library, const std::string& golden_dir) {
    const std::string path = golden_dir + "/plan.toml";
    auto text = read_text_file(path);
    if (!text.ok()) return text.error();
    auto plan = PlanReader(path).read(text.value(), library);
    if (!plan.ok()) return plan.error();
    std::vector<GoldenEntry> out;
    for (const Preset& p : library.presets()) {
        const bool time = reads_time(library, p);
        for (const PlanRule& rule : plan.value().rules) {
            const bool named = std::find(rule.presets.begin(), rule.presets.end(), p.name) != rule.presets.end();
            if (!(rule.all_presets || named) || (rule.requires_time && !time)) continue;
            for (const std::string& input : rule.inputs) {
                auto [iw, ih] = rule.input_size.value_or(std::make_pair(rule.width, rule.height));
                // A scene that states its source size is fed pictures of that size.
                if (p.scene.source_width) std::tie(iw, ih) = std::make_pair(p.scene.source_width, p.scene.source_height);
                for (int frame : rule.frames) {
                    out.push_back(make_golden_entry(p.name, input, rule.width, rule.height, iw, ih, frame, rule.fit));
                    out.back().stored = rule.store;
                }
            }
        }
    }
    return out;
}

}  // namespace crtforge
