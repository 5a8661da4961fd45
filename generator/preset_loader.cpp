// Parses preset files (templates/presets/<name>.toml) and resolves inheritance into a Preset.
#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "crtforge/template_library.hpp"
#include "generator/toml_reader.hpp"

namespace crtforge {

using detail::TomlReader;

const char* filter_name(Filter filter) { return filter == Filter::Linear ? "linear" : "nearest"; }

const ResolvedStage* Preset::find_stage(const std::string& stage_name) const {
    for (const auto& s : stages)
        if (s.stage->name == stage_name) return &s;
    return nullptr;
}

namespace {

bool is_preset_name(const std::string& name) {
    if (name.empty() || name.size() > 64 || !std::isalnum(static_cast<unsigned char>(name[0]))) return false;
    for (char c : name)
        if (!(std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
            return false;
    return true;
}

}  // namespace

Result<PresetFile> parse_preset_file(const std::string& text, const std::string& path,
                                     const TemplateLibrary* library) {
    TomlReader r(path);
    auto parsed = r.parse(text);
    if (!parsed.ok()) return parsed.error();
    const toml::table& root = parsed.value();
    if (auto s = r.only_keys(root, {"name", "doc", "base", "filter", "stages"}, ""); !s.ok()) return s.error();

    PresetFile file;
    file.where = {path, 1};
    auto name = r.string(root, "name", "", true);
    if (!name.ok()) return name.error();
    file.name = name.value();
    if (!is_preset_name(file.name))
        return r.error(root.get("name"), "name",
                       "'" + file.name + "' must be lower-case letters, digits, '-' or '_' (it becomes a file name)");
    auto doc = r.string(root, "doc", "", true);
    if (!doc.ok()) return doc.error();
    file.doc = doc.value();
    if (file.doc.empty() || file.doc.find('\n') != std::string::npos)
        return r.error(root.get("doc"), "doc", "must be one non-empty line");
    auto base = r.string(root, "base", "", false);
    if (!base.ok()) return base.error();
    file.base = base.value();
    auto filter = r.string(root, "filter", "", false);
    if (!filter.ok()) return filter.error();
    if (filter.value() == "linear") file.filter = Filter::Linear;
    else if (filter.value() == "nearest") file.filter = Filter::Nearest;
    else if (!filter.value().empty())
        return r.error(root.get("filter"), "filter", "must be \"linear\" or \"nearest\"");

    if (const toml::node* stages = root.get("stages")) {
        const toml::table* st = stages->as_table();
        if (!st) return r.error(stages, "stages", "must be a table of [stages.<name>] sections");
        // toml++ tables are sorted by key; keep the file's order for readable diagnostics.
        std::vector<std::pair<std::string, const toml::node*>> entries;
        for (const auto& [key, node] : *st) entries.emplace_back(std::string(key.str()), &node);
        std::sort(entries.begin(), entries.end(), [&](const auto& a, const auto& b) {
            return r.line_of(*a.second) < r.line_of(*b.second);
        });
        for (const auto& [stage_name, node] : entries) {
            const std::string field = "stages." + stage_name;
            const toml::table* t = node->as_table();
            if (!t) return r.error(node, field, "must be a table");
            const StageSpec* spec = library ? library->find_stage(stage_name) : nullptr;
            if (library && !spec) {
                std::vector<std::string> names;
                for (const auto& s : library->stages()) names.push_back(s.name);
                const std::string list = join_list(names);
                return r.error(node, field, "unknown stage (stages: " + list + ")");
            }
            PresetStageEntry entry;
            entry.stage = stage_name;
            entry.line = r.line_of(*node);
            for (const auto& [key, value] : *t) {
                const std::string param = std::string(key.str());
                const std::string pfield = field + "." + param;
                if (param == "enabled") {
                    if (!value.is_boolean()) return r.error(&value, pfield, "must be true or false");
                    entry.enabled = value.as_boolean()->get();
                    continue;
                }
                const ParamSpec* pspec = spec ? spec->find_param(param) : nullptr;
                if (!pspec) {
                    std::vector<std::string> names;
                    if (spec)
                        for (const auto& p : spec->params) names.push_back(p.name);
                    return r.error(&value, pfield, "unknown param of stage '" + stage_name + "' (params: " + join_list(names) + ")");
                }
                auto v = r.param_value(value, *pspec, pfield);
                if (!v.ok()) return v.error();
                entry.values[param] = v.value();
                entry.value_lines[param] = r.line_of(value);
            }
            if (!entry.enabled && !entry.values.empty())
                return r.error(node, field, "a disabled stage cannot also set params");
            file.stages.push_back(std::move(entry));
        }
    }
    return file;
}

Result<Preset> TemplateLibrary::resolve(const std::vector<PresetFile>& files, const std::string& name) const {
    auto find_file = [&](const std::string& n) -> const PresetFile* {
        for (const auto& f : files)
            if (f.name == n) return &f;
        return nullptr;
    };
    const PresetFile* leaf = find_file(name);
    if (!leaf) return make_error("unknown preset '" + name + "'");

    // Walk to the root of the inheritance chain, refusing cycles.
    std::vector<const PresetFile*> chain{leaf};
    std::set<std::string> seen{leaf->name};
    while (!chain.back()->base.empty()) {
        const PresetFile* child = chain.back();
        const PresetFile* base = find_file(child->base);
        if (!base) return make_error("base preset '" + child->base + "' does not exist", child->where.file, child->where.line, "base");
        if (!seen.insert(base->name).second)
            return make_error("inheritance cycle through '" + base->name + "'", child->where.file, child->where.line, "base");
        chain.push_back(base);
    }

    Preset preset;
    preset.name = leaf->name;
    preset.doc = leaf->doc;
    preset.where = leaf->where;
    for (const auto* f : chain) preset.lineage.push_back(f->name);

    // Apply from the root down: later (more derived) files override.
    std::map<std::string, std::map<std::string, Value>> enabled;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        if ((*it)->filter) preset.filter = *(*it)->filter;
        for (const auto& entry : (*it)->stages) {
            if (!entry.enabled) {
                enabled.erase(entry.stage);
                continue;
            }
            auto& values = enabled[entry.stage];
            for (const auto& [k, v] : entry.values) values[k] = v;
        }
    }

    for (const StageSpec& spec : stages_) {
        auto found = enabled.find(spec.name);
        if (found == enabled.end()) continue;
        const auto& set_values = found->second;
        ResolvedStage rs;
        rs.stage = &spec;
        if (spec.selector.empty()) {
            rs.form = &spec.forms.front();
        } else {
            auto sel = set_values.find(spec.selector);
            const Value& v = sel != set_values.end() ? sel->second : spec.find_param(spec.selector)->default_value;
            rs.form = spec.find_form(std::get<std::string>(v));
        }
        std::vector<std::string> reads = spec.common_params;
        reads.insert(reads.end(), rs.form->params.begin(), rs.form->params.end());
        if (!spec.selector.empty()) reads.push_back(spec.selector);
        for (const auto& p : reads) {
            auto v = set_values.find(p);
            rs.values[p] = v != set_values.end() ? v->second : spec.find_param(p)->default_value;
        }
        // A value this file sets that the chosen form never reads is almost always a mistake.
        for (const auto& entry : leaf->stages) {
            if (entry.stage != spec.name) continue;
            for (const auto& [k, v] : entry.values) {
                if (!rs.values.count(k)) {
                    const std::string list = join_list(reads);
                    return make_error(fmt::format("is not read by form '{}' of stage '{}' (it reads: {})",
                                                  rs.form->name, spec.name, list),
                                      leaf->where.file, entry.value_lines.at(k), "stages." + spec.name + "." + k);
                }
            }
        }
        preset.stages.push_back(std::move(rs));
    }
    return preset;
}

}  // namespace crtforge
