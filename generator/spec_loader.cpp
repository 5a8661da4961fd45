// Parses and validates one stage spec (templates/stages/<stage>.toml).
#include <algorithm>
#include <cmath>
#include <set>
#include <filesystem>

#include <fmt/format.h>

#include "crtforge/files.hpp"
#include "crtforge/template_library.hpp"
#include "generator/reserved_words.hpp"
#include "generator/toml_reader.hpp"
#include "crtforge/runtime/image.hpp"

namespace crtforge {

using detail::join_field;
using detail::TomlReader;

const char* hook_name(Hook hook) {
    switch (hook) {
        case Hook::Warp: return "warp";
        case Hook::SampleUv: return "sample_uv";
        case Hook::Fetch: return "fetch";
        case Hook::Color: return "color";
        case Hook::Finish: return "finish";
        case Hook::Alpha: return "alpha";
    }
    return "?";
}

const char* param_role_name(ParamRole role) {
    switch (role) {
        case ParamRole::None: return "";
        case ParamRole::AngularSpeed: return "angular_speed";
    }
    return "?";
}

const char* builtin_name(Builtin builtin) {
    switch (builtin) {
        case Builtin::OutputSize: return "outputSize";
        case Builtin::SourceSize: return "sourceSize";
        case Builtin::Time: return "time";
        case Builtin::FrameCount: return "frameCount";
        case Builtin::ViewportSize: return "viewportSize";
    }
    return "?";
}

const char* builtin_doc(Builtin builtin) {
    switch (builtin) {
        case Builtin::OutputSize: return "output size in pixels (width, height)";
        case Builtin::SourceSize: return "source texture size in texels (width, height)";
        case Builtin::Time: return "seconds since start; keep it continuous";
        case Builtin::FrameCount: return "frames since start (modulo the pass's frame_count_mod)";
        case Builtin::ViewportSize: return "the screen's size in pixels (width, height): what the last pass draws";
    }
    return "?";
}

bool parse_builtin(const std::string& text, Builtin& out) {
    for (Builtin b : kAllBuiltins) {
        if (text == builtin_name(b)) {
            out = b;
            return true;
        }
    }
    return false;
}

int ParamSpec::enum_index(const std::string& value) const {
    for (size_t i = 0; i < enum_values.size(); ++i)
        if (enum_values[i] == value) return static_cast<int>(i);
    return -1;
}

const ParamSpec* StageSpec::find_param(const std::string& param) const {
    for (const auto& p : params)
        if (p.name == param) return &p;
    return nullptr;
}

const FormSpec* StageSpec::find_form(const std::string& form) const {
    for (const auto& f : forms)
        if (f.name == form) return &f;
    return nullptr;
}

namespace {

Result<ParamSpec> parse_param(const TomlReader& r, const toml::table& t, const std::string& prefix) {
    if (auto s = r.only_keys(t, {"name", "type", "range", "step", "values", "default", "unit", "doc", "runtime", "role"}, prefix); !s.ok())
        return s.error();
    ParamSpec p;
    p.where = {r.path(), r.line_of(t)};
    auto name = r.string(t, "name", prefix, true);
    if (!name.ok()) return name.error();
    p.name = name.value();
    if (!detail::is_identifier(p.name))
        return r.error(t.get("name"), join_field(prefix, "name"), detail::not_identifier(p.name));
    if (const std::string language = detail::reserving_language(p.name); !language.empty())
        return r.error(t.get("name"), "param." + p.name,
                       "'" + p.name + "' is a keyword or builtin of " + language +
                           " (a param becomes a uniform of its name in every target): choose another name");
    if (p.name.rfind("crtStage_", 0) == 0)
        return r.error(t.get("name"), "param." + p.name, "names starting with crtStage_ are the uber-shader's stage switches: choose another name");
    const std::string field = "param." + p.name;

    auto type = r.string(t, "type", field, true);
    if (!type.ok()) return type.error();
    if (!parse_param_type(type.value(), p.type))
        return r.error(t.get("type"), join_field(field, "type"),
                       "'" + type.value() + "' is not a type (float, int, bool, enum, color)");

    if (p.type == ParamType::Enum) {
        auto values = r.strings(t, "values", field);
        if (!values.ok()) return values.error();
        p.enum_values = values.value();
        if (p.enum_values.empty())
            return r.error(t.get("values") ? t.get("values") : &t, join_field(field, "values"),
                           "an enum param needs a non-empty values list");
        std::set<std::string> seen;
        for (const auto& v : p.enum_values)
            if (!detail::is_identifier(v) || !seen.insert(v).second)
                return r.error(t.get("values"), join_field(field, "values"),
                               "'" + v + "' is not a valid, unique enum value name");
    } else if (t.get("values")) {
        return r.error(t.get("values"), join_field(field, "values"), "only enum params have values");
    }

    const bool numeric = p.type == ParamType::Float || p.type == ParamType::Int;
    if (const toml::node* range = t.get("range")) {
        const toml::array* a = range->as_array();
        if (!numeric) return r.error(range, join_field(field, "range"), "only float and int params have a range");
        if (!a || a->size() != 2 || !(a->get(0)->is_number()) || !(a->get(1)->is_number()))
            return r.error(range, join_field(field, "range"), "must be [min, max]");
        p.min = a->get(0)->value<double>();
        p.max = a->get(1)->value<double>();
        // Bounds reach generated code (Godot's hint_range) and the validator's sweeps: finite, and
        // within float32 so every target reads the same number.
        for (const std::optional<double>& bound : {p.min, p.max})
            if (!bound || !std::isfinite(*bound) || std::fabs(*bound) > 3.0e38)
                return r.error(range, join_field(field, "range"), "bounds must be finite numbers within float range");
        if (!(*p.min < *p.max)) return r.error(range, join_field(field, "range"), "min must be below max");
    } else if (numeric) {
        return r.error(&t, join_field(field, "range"), "a float or int param needs a range [min, max]");
    }
    if (const toml::node* step = t.get("step")) {
        if (!numeric || !step->is_number() || !(step->value<double>().value_or(0) > 0) || !std::isfinite(*step->value<double>()))
            return r.error(step, join_field(field, "step"), "must be a positive number on a float or int param");
        p.step = step->value<double>();
    }

    const toml::node* def = t.get("default");
    if (!def) return r.error(&t, join_field(field, "default"), "is required but missing");
    auto value = r.param_value(*def, p, join_field(field, "default"));
    if (!value.ok()) return value.error();
    p.default_value = value.value();

    auto unit = r.string(t, "unit", field, false);
    if (!unit.ok()) return unit.error();
    p.unit = unit.value();
    auto doc = r.string(t, "doc", field, true);
    if (!doc.ok()) return doc.error();
    p.doc = doc.value();
    if (p.doc.empty() || p.doc.find('\n') != std::string::npos)
        return r.error(t.get("doc"), join_field(field, "doc"), "must be one non-empty line");
    auto runtime = r.boolean(t, "runtime", field);
    if (!runtime.ok()) return runtime.error();
    p.runtime = runtime.value().value_or(false);
    auto role = r.string(t, "role", field, false);
    if (!role.ok()) return role.error();
    if (role.value() == param_role_name(ParamRole::AngularSpeed)) {
        if (p.type != ParamType::Float)
            return r.error(t.get("role"), join_field(field, "role"), "an angular_speed param must be a float");
        p.role = ParamRole::AngularSpeed;
    } else if (!role.value().empty()) {
        return r.error(t.get("role"), join_field(field, "role"),
                       "'" + role.value() + "' is not a role (angular_speed: radians per second multiplied by time)");
    }
    // Enums and bools select code at generation time; WGSL also has no bool in uniform buffers.
    if (p.runtime && (p.type == ParamType::Enum || p.type == ParamType::Bool))
        return r.error(t.get("runtime"), join_field(field, "runtime"),
                       std::string("a ") + param_type_name(p.type) + " param selects code at generation time and cannot be a runtime uniform");
    return p;
}

// A program form's two files, named relative to the stage's file and inside its folder.
Result<FormSpec> parse_program_files(const TomlReader& r, const toml::table& t, const std::string& field, FormSpec f) {
    namespace fs = std::filesystem;
    const fs::path folder = fs::path(r.path()).parent_path();
    for (const char* key : {"vertex", "fragment"}) {
        auto name = r.string(t, key, field, true);
        if (!name.ok()) return name.error();
        const fs::path relative(name.value());
        bool inside = !relative.empty() && relative.is_relative();
        for (const auto& part : relative) inside = inside && part != "..";
        if (!inside)
            return r.error(t.get(key), join_field(field, key), "'" + name.value() + "' must be a path below the stage file's folder");
        const std::string path = (folder / relative).string();
        auto text = read_text_file(path);
        if (!text.ok()) return make_error(text.error().message, r.path(), r.line_of(*t.get(key)), join_field(field, key));
        (std::string(key) == "vertex" ? f.vertex_path : f.fragment_path) = path;
        (std::string(key) == "vertex" ? f.vertex_source : f.fragment_source) = std::move(text.value());
    }
    return f;
}

Result<FormSpec> parse_form(const TomlReader& r, const toml::table& t, const StageSpec& stage) {
    const std::string prefix = "form";
    if (stage.program) {
        if (auto s = r.only_keys(t, {"name", "doc", "params", "builtins", "textures", "vertex", "fragment"}, prefix); !s.ok())
            return s.error();
    } else if (auto s = r.only_keys(t, {"name", "doc", "params", "builtins", "textures", "texture_sizes", "quality_of", "warp", "sample_uv", "fetch", "color", "finish", "alpha"}, prefix); !s.ok()) {
        return s.error();
    }
    FormSpec f;
    f.where = {r.path(), r.line_of(t)};
    auto name = r.string(t, "name", prefix, true);
    if (!name.ok()) return name.error();
    f.name = name.value();
    if (!detail::is_identifier(f.name))
        return r.error(t.get("name"), "form.name", detail::not_identifier(f.name));
    const std::string field = "form." + f.name;
    auto doc = r.string(t, "doc", field, true);
    if (!doc.ok()) return doc.error();
    f.doc = doc.value();
    auto params = r.strings(t, "params", field);
    if (!params.ok()) return params.error();
    f.params = params.value();
    for (const auto& p : f.params)
        if (!stage.find_param(p))
            return r.error(t.get("params"), join_field(field, "params"), "'" + p + "' is not a param of this stage");
    auto builtins = r.strings(t, "builtins", field);
    if (!builtins.ok()) return builtins.error();
    for (const auto& b : builtins.value()) {
        Builtin builtin{};
        if (!parse_builtin(b, builtin))
            return r.error(t.get("builtins"), join_field(field, "builtins"),
                           "'" + b + "' is not a builtin (outputSize, sourceSize, time, frameCount, viewportSize)");
        f.builtins.push_back(builtin);
    }
    auto textures = r.strings(t, "textures", field);
    if (!textures.ok()) return textures.error();
    for (const auto& name : textures.value()) {
        if (!detail::is_identifier(name) || name == "source")
            return r.error(t.get("textures"), join_field(field, "textures"),
                           "'" + name + "' must be an identifier other than source (the main input)");
        if (std::find(f.textures.begin(), f.textures.end(), name) != f.textures.end())
            return r.error(t.get("textures"), join_field(field, "textures"), "'" + name + "' is listed twice");
        f.textures.push_back(name);
    }
    if (stage.program) return parse_program_files(r, t, field, f);
    if (const toml::node* sizes = t.get("texture_sizes")) {
        const toml::table* table = sizes->as_table();
        if (!table) return r.error(sizes, join_field(field, "texture_sizes"), "must be a table: texture = [width, height]");
        for (const auto& [key, value] : *table) {
            const std::string name(key.str());
            const std::string where = join_field(field, "texture_sizes." + name);
            if (std::find(f.textures.begin(), f.textures.end(), name) == f.textures.end())
                return r.error(&value, where, "'" + name + "' is not one of the form's textures");
            const toml::array* a = value.as_array();
            auto dimension = [&](size_t i) -> int64_t {
                const toml::node* n = a && a->size() == 2 ? a->get(i) : nullptr;
                return n && n->is_integer() ? *n->value<int64_t>() : 0;
            };
            const int64_t w = dimension(0), h = dimension(1);
            if (w < 1 || h < 1 || w > kMaxImageDimension || h > kMaxImageDimension)
                return r.error(&value, where, "must be [width, height], each 1.." + std::to_string(kMaxImageDimension));
            f.texture_sizes[name] = {static_cast<int>(w), static_cast<int>(h)};
        }
    }
    auto quality_of = r.string(t, "quality_of", field, false);
    if (!quality_of.ok()) return quality_of.error();
    f.quality_of = quality_of.value();
    bool any = false;
    for (Hook hook : kAllHooks) {
        auto fn = r.string(t, hook_name(hook), field, false);
        if (!fn.ok()) return fn.error();
        if (!fn.value().empty() && !detail::is_identifier(fn.value()))
            return r.error(t.get(hook_name(hook)), join_field(field, hook_name(hook)), "must name a GLSL function");
        f.functions[static_cast<int>(hook)] = fn.value();
        any = any || !fn.value().empty();
    }
    if (!any)
        return r.error(&t, field, "a form needs at least one function (warp, sample_uv, fetch, color, finish or alpha)");
    return f;
}

}  // namespace

Result<StageSpec> parse_stage_spec(const std::string& text, const std::string& path) {
    TomlReader r(path);
    auto parsed = r.parse(text);
    if (!parsed.ok()) return parsed.error();
    const toml::table& root = parsed.value();
    if (auto s = r.only_keys(root, {"name", "doc", "kind", "order", "selector", "common", "param", "form"}, ""); !s.ok())
        return s.error();

    StageSpec stage;
    stage.where = {path, 1};
    auto name = r.string(root, "name", "", true);
    if (!name.ok()) return name.error();
    stage.name = name.value();
    if (!detail::is_identifier(stage.name))
        return r.error(root.get("name"), "name", detail::not_identifier(stage.name));
    auto doc = r.string(root, "doc", "", true);
    if (!doc.ok()) return doc.error();
    stage.doc = doc.value();
    auto kind = r.string(root, "kind", "", false);
    if (!kind.ok()) return kind.error();
    if (kind.value() != "" && kind.value() != "hooks" && kind.value() != "program")
        return r.error(root.get("kind"), "kind", "'" + kind.value() + "' is not a stage kind (hooks, program)");
    stage.program = kind.value() == "program";
    auto order = r.integer(root, "order", "");
    if (!order.ok()) return order.error();
    if (stage.program) {
        if (order.value()) return r.error(root.get("order"), "order", "a program stage runs alone in its pass and has no order");
    } else {
        if (!order.value()) return r.error(&root, "order", "is required but missing");
        stage.order = static_cast<int>(*order.value());
    }

    if (const toml::node* params = root.get("param")) {
        const toml::array* a = params->as_array();
        if (!a || !a->is_array_of_tables()) return r.error(params, "param", "must be [[param]] tables");
        for (const toml::node& node : *a) {
            auto p = parse_param(r, *node.as_table(), "param");
            if (!p.ok()) return p.error();
            if (stage.find_param(p.value().name))
                return r.error(&node, "param." + p.value().name, "is declared twice");
            stage.params.push_back(std::move(p.value()));
        }
    }

    auto common = r.strings(root, "common", "");
    if (!common.ok()) return common.error();
    stage.common_params = common.value();
    for (const auto& p : stage.common_params)
        if (!stage.find_param(p)) return r.error(root.get("common"), "common", "'" + p + "' is not a param of this stage");

    const toml::node* forms = root.get("form");
    if (!forms) return r.error(&root, "form", "a stage needs at least one [[form]]");
    const toml::array* fa = forms->as_array();
    if (!fa || !fa->is_array_of_tables()) return r.error(forms, "form", "must be [[form]] tables");
    for (const toml::node& node : *fa) {
        auto f = parse_form(r, *node.as_table(), stage);
        if (!f.ok()) return f.error();
        if (stage.find_form(f.value().name))
            return r.error(&node, "form." + f.value().name, "is declared twice");
        stage.forms.push_back(std::move(f.value()));
    }

    auto selector = r.string(root, "selector", "", false);
    if (!selector.ok()) return selector.error();
    stage.selector = selector.value();
    if (stage.selector.empty()) {
        if (stage.forms.size() != 1)
            return r.error(&root, "selector", "a stage with several forms needs a selector enum param");
    } else {
        const ParamSpec* sel = stage.find_param(stage.selector);
        if (!sel || sel->type != ParamType::Enum)
            return r.error(root.get("selector"), "selector", "'" + stage.selector + "' must name an enum param of this stage");
        std::vector<std::string> names;
        for (const auto& f : stage.forms) names.push_back(f.name);
        if (names != sel->enum_values)
            return r.error(root.get("selector"), "selector",
                           "the values of '" + stage.selector + "' must be the form names, in the same order");
    }

    // A quality tier stands in for its point-sampled form: same params, builtins and textures.
    for (const auto& f : stage.forms) {
        if (f.quality_of.empty()) continue;
        const std::string field = "form." + f.name + ".quality_of";
        const FormSpec* base = stage.find_form(f.quality_of);
        if (!base || base == &f)
            return make_error("'" + f.quality_of + "' is not another form of this stage", path, f.where.line, field);
        if (!base->quality_of.empty())
            return make_error("'" + f.quality_of + "' is itself a quality tier (of '" + base->quality_of + "'): name the point-sampled form",
                              path, f.where.line, field);
        auto sorted = [](std::vector<std::string> v) { std::sort(v.begin(), v.end()); return v; };
        if (sorted(f.params) != sorted(base->params) || f.textures != base->textures || f.builtins != base->builtins)
            return make_error("a quality tier must read the same params, builtins and textures as '" + f.quality_of + "'",
                              path, f.where.line, field);
    }

    // A speed multiplied by time belongs to forms that read time.
    for (const auto& p : stage.params) {
        if (p.role != ParamRole::AngularSpeed) continue;
        for (const auto& f : stage.forms) {
            const bool reads = std::find(f.params.begin(), f.params.end(), p.name) != f.params.end() ||
                               std::find(stage.common_params.begin(), stage.common_params.end(), p.name) != stage.common_params.end();
            if (reads && std::find(f.builtins.begin(), f.builtins.end(), Builtin::Time) == f.builtins.end())
                return make_error("has role angular_speed but form '" + f.name + "' reads it without the time builtin",
                                  path, p.where.line, "param." + p.name + ".role");
        }
    }
    // Every param must be read by something; an unused param is a spec bug.
    for (const auto& p : stage.params) {
        bool used = p.name == stage.selector ||
                    std::find(stage.common_params.begin(), stage.common_params.end(), p.name) != stage.common_params.end();
        for (const auto& f : stage.forms)
            used = used || std::find(f.params.begin(), f.params.end(), p.name) != f.params.end();
        if (!used)
            return make_error("is not read by any form (list it in a form's params or in common)", path,
                              p.where.line, "param." + p.name);
    }
    ParamSpec& sw = stage.stage_switch;
    sw.name = "crtStage_" + stage.name;
    sw.type = ParamType::Int;
    sw.min = 0.0;
    sw.max = static_cast<double>(stage.forms.size());
    sw.step = 1.0;
    sw.default_value = int64_t{0};
    sw.doc = "uber-shader switch: 0 off";
    for (size_t i = 0; i < stage.forms.size(); ++i) sw.doc += fmt::format(", {} {}", i + 1, stage.forms[i].name);
    sw.runtime = true;
    sw.where = stage.where;
    return stage;
}

}  // namespace crtforge
