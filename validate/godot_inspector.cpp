// Godot inspector metadata read back from the exported files (see validate/godot_inspector.hpp).
#include "crtforge/validate/godot_inspector.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

#include <fmt/format.h>

namespace crtforge {

namespace {

struct Declared {
    std::string type, hints, value;  // as written: "float", "hint_range(0.0, 1.0, 0.01)", "0.5"
};

std::string trim(std::string s) {
    const auto first = s.find_first_not_of(" \t"), last = s.find_last_not_of(" \t");
    return first == std::string::npos ? std::string() : s.substr(first, last - first + 1);
}

// The numbers of a call's argument list: "vec3(1.0, 0.5, 0)" -> {1, 0.5, 0}; "0.25" -> {0.25}.
std::optional<std::vector<double>> numbers(const std::string& text) {
    std::string inner = trim(text);
    if (const size_t open = inner.find('('); open != std::string::npos) {
        if (inner.back() != ')') return std::nullopt;
        inner = inner.substr(open + 1, inner.size() - open - 2);
    }
    std::vector<double> out;
    std::istringstream parts(inner);
    for (std::string part; std::getline(parts, part, ',');) {
        part = trim(part);
        char* end = nullptr;
        const double v = std::strtod(part.c_str(), &end);
        if (part.empty() || *end != '\0' || !std::isfinite(v)) return std::nullopt;
        out.push_back(v);
    }
    return out;
}

bool same(double a, double b) { return std::fabs(a - b) <= 1e-6 * std::max(1.0, std::fabs(b)); }

std::map<std::string, Declared> shader_uniforms(const std::string& text) {
    static const std::regex uniform(R"(^\s*uniform\s+(\w+)\s+(\w+)\s*(?::\s*([^=;]*?))?\s*(?:=\s*([^;]*?))?\s*;)");
    std::map<std::string, Declared> out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (std::smatch m; std::regex_search(line, m, uniform)) out[m[2]] = {m[1], m[3], m[4]};
    return out;
}

std::map<std::string, std::string> material_values(const std::string& text, int version) {
    const std::regex entry(std::string(R"(^)") + (version >= 4 ? "shader_parameter/" : "shader_param/") + R"((\w+)\s*=\s*(.*?)\s*$)");
    std::map<std::string, std::string> out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (std::smatch m; std::regex_search(line, m, entry)) out[m[1]] = m[2];
    return out;
}

// What the value text says against the preset's value, "" when they agree.
std::string value_problem(const ParamSpec& spec, const Value& value, const std::string& text, bool colour_has_alpha) {
    if (spec.type == ParamType::Bool) {
        const bool* flag = std::get_if<bool>(&value);
        if (!flag) return "has a value of an unexpected kind";
        const bool b = *flag;
        return text == (b ? "true" : "false") ? "" : fmt::format("is {}, the preset's value is {}", text, b);
    }
    auto n = numbers(text);
    if (!n) return "is '" + text + "', not a number or a list of numbers";
    if (spec.type == ParamType::Color) {
        const Color* colour = std::get_if<Color>(&value);
        if (!colour) return "has a value of an unexpected kind";
        const Color& c = *colour;
        const size_t want = colour_has_alpha ? 4 : 3;
        if (n->size() != want) return fmt::format("has {} components, {} expected", n->size(), want);
        if (!same((*n)[0], c[0]) || !same((*n)[1], c[1]) || !same((*n)[2], c[2]))
            return fmt::format("is ({}, {}, {}), the preset's colour is ({}, {}, {})", (*n)[0], (*n)[1], (*n)[2], c[0], c[1], c[2]);
        if (colour_has_alpha && (*n)[3] != 1.0) return fmt::format("has alpha {}; a colour param is opaque (alpha 1)", (*n)[3]);
        return "";
    }
    if (n->size() != 1) return "is '" + text + "', one number expected";
    double want = 0.0;
    if (auto d = std::get_if<double>(&value)) want = *d;
    else if (auto i = std::get_if<int64_t>(&value)) want = static_cast<double>(*i);
    else if (auto e = std::get_if<std::string>(&value)) want = spec.enum_index(*e);  // an enum is its value's index
    else return "has a value of an unexpected kind";
    if (spec.type != ParamType::Float && (*n)[0] != std::round((*n)[0])) return "is " + text + ", not a whole number";
    return same((*n)[0], want) ? "" : fmt::format("is {}, the preset's value is {}", text, want);
}

// The inspector's slider against the spec's range and step.
std::string hint_problem(const ParamSpec& spec, const std::string& hints, int version) {
    if (spec.type == ParamType::Color) {
        const char* want = version >= 4 ? "source_color" : "hint_color";
        return hints == want ? "" : fmt::format("has hint '{}'; a colour shows as a colour picker with '{}'", hints, want);
    }
    if (spec.type == ParamType::Bool || spec.type == ParamType::Enum) return hints.empty() ? "" : "has hint '" + hints + "', none expected";
    if (hints.rfind("hint_range", 0) != 0 || !spec.min || !spec.max) return "has no hint_range: the inspector shows no slider of the spec's range";
    auto n = numbers(hints);
    if (!n || n->size() < 2 || n->size() > 3) return "has a malformed " + hints;
    if (!same((*n)[0], *spec.min) || !same((*n)[1], *spec.max))
        return fmt::format("has range [{}, {}], the spec's is [{}, {}]", (*n)[0], (*n)[1], *spec.min, *spec.max);
    if (n->size() == 3) {
        const double step = (*n)[2];
        if (spec.step ? !same(step, *spec.step) : !(step > 0.0 && step <= *spec.max - *spec.min))
            return fmt::format("has step {}, the spec's is {}", step, spec.step ? fmt::format("{}", *spec.step) : "unset (any step inside the range)");
        if (spec.type == ParamType::Int && step != std::round(step)) return fmt::format("has step {} for an int", step);
    } else if (spec.step) {
        return fmt::format("has no step, the spec's is {}", *spec.step);
    }
    return "";
}

const char* godot_type(ParamType type, int version) {
    switch (type) {
        case ParamType::Float: return "float";
        case ParamType::Int:
        case ParamType::Enum: return "int";
        case ParamType::Bool: return "bool";
        case ParamType::Color: return version >= 4 ? "vec3" : "vec4";
    }
    return "";
}

void check_pair(const Variant& variant, const OutputFile& shader, const OutputFile* material, int version, std::vector<std::string>& out) {
    const auto declared = shader_uniforms(shader.data);
    const auto values = material ? material_values(material->data, version) : std::map<std::string, std::string>{};
    const std::string file = shader.path.empty() ? shader.suffix : shader.path;
    const std::string material_file = material ? (material->path.empty() ? material->suffix : material->path) : "";
    for (const VariantParam& p : variant.params) {
        const ParamSpec& spec = *p.spec;
        auto d = declared.find(spec.name);
        if (!p.uniform) {
            if (d != declared.end()) out.push_back(file + ": '" + spec.name + "' is a uniform, but the preset bakes it");
            continue;
        }
        if (d == declared.end()) {
            out.push_back(file + ": runtime param '" + spec.name + "' is not a uniform the inspector shows");
            continue;
        }
        auto say = [&](const std::string& where, const std::string& problem) {
            if (!problem.empty()) out.push_back(where + ": '" + spec.name + "' " + problem);
        };
        if (d->second.type != godot_type(spec.type, version))
            say(file, fmt::format("is declared {}, a {} param is {}", d->second.type, param_type_name(spec.type), godot_type(spec.type, version)));
        say(file, hint_problem(spec, d->second.hints, version));
        if (d->second.value.empty()) say(file, "has no default: the inspector starts from zero, not the preset's value");
        else say(file, value_problem(spec, p.value, d->second.value, spec.type == ParamType::Color && version < 4));
        if (!material) continue;
        auto v = values.find(spec.name);
        if (v == values.end()) say(material_file, "is missing from the material");
        else say(material_file, value_problem(spec, p.value, v->second, spec.type == ParamType::Color));
    }
    for (const auto& [name, text] : values)
        if (!declared.count(name)) out.push_back(material_file + ": '" + name + "' is set, but the shader declares no such uniform");
}

}  // namespace

std::vector<std::string> godot_inspector_problems(const Variant& variant, const TargetOutput& out, int godot_version) {
    std::vector<std::string> problems;
    auto role = [&](const char* name) -> const OutputFile* {
        for (const OutputFile& f : out.files)
            if (f.manifest_role() == name) return &f;
        return nullptr;
    };
    for (const auto& [shader_role, material_role] : {std::pair{"shader", "material"}, std::pair{"screenShader", "screenMaterial"}}) {
        const OutputFile* shader = role(shader_role);
        if (!shader) continue;
        check_pair(variant, *shader, role(material_role), godot_version, problems);
    }
    if (!role("shader")) problems.push_back("the pass has no Godot shader file");
    return problems;
}

}  // namespace crtforge
