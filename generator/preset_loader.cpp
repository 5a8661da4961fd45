// Parses preset files (templates/presets/<name>.toml): stages, passes, the scene's source, display
// and time, LUTs. Resolving inheritance and the pass graph is preset_resolver.cpp.
#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "crtforge/template_library.hpp"
#include "crtforge/luts.hpp"
#include "crtforge/runtime/image.hpp"
#include "generator/preset_migration.hpp"
#include "generator/toml_reader.hpp"

namespace crtforge {

bool is_preset_name(const std::string& name) {
    if (name.empty() || name.size() > 64 || !std::isalnum(static_cast<unsigned char>(name[0]))) return false;
    for (char c : name)
        if (!(std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
            return false;
    return true;
}

using detail::TomlReader;
using detail::migrate_glitch_preset;
using detail::preset_format;

namespace {

// The [stages.<name>] tables of a preset or of a pass: each stage's enable flag and param values.
Result<std::vector<PresetStageEntry>> parse_stage_entries(const TomlReader& r, const toml::node& stages,
                                                          const std::string& prefix, const TemplateLibrary* library) {
    std::vector<PresetStageEntry> out;
    const toml::table* st = stages.as_table();
    if (!st) return r.error(&stages, prefix, "must be a table of [" + prefix + ".<name>] sections");
    // toml++ tables are sorted by key; keep the file's order for readable diagnostics.
    std::vector<std::pair<std::string, const toml::node*>> entries;
    for (const auto& [key, node] : *st) entries.emplace_back(std::string(key.str()), &node);
    std::sort(entries.begin(), entries.end(), [&](const auto& a, const auto& b) {
        return r.line_of(*a.second) < r.line_of(*b.second);
    });
    for (const auto& [stage_name, node] : entries) {
        const std::string field = prefix + "." + stage_name;
        const toml::table* t = node->as_table();
        if (!t) return r.error(node, field, "must be a table");
        const StageSpec* spec = library ? library->find_stage(stage_name) : nullptr;
        if (library && !spec) {
            std::vector<std::string> names;
            for (const auto& s : library->stages()) names.push_back(s.name);
            return r.error(node, field, "unknown stage (stages: " + join_list(names) + ")");
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
        if (!entry.enabled && !entry.values.empty()) return r.error(node, field, "a disabled stage cannot also set params");
        out.push_back(std::move(entry));
    }
    return out;
}

constexpr std::initializer_list<const char*> kFilters = {"linear", "nearest"};
constexpr std::initializer_list<const char*> kWraps = {"clamp_to_edge", "clamp_to_border", "repeat", "mirrored_repeat"};
// In PixelFormat's order (the choice's index is the enum's value).
constexpr std::initializer_list<const char*> kFormats = {"rgba8", "rgba8_srgb", "rgba16f", "rgba32f", "rgb10a2", "r16f", "rg16f"};
constexpr std::initializer_list<const char*> kScaleTypes = {"source", "viewport", "absolute"};

// scale_type / scale (a number or [x, y]) / scale_type_x / scale_type_y of a [[pass]].
Status parse_scale(const TomlReader& r, const toml::table& t, const std::string& prefix, PassEntry& pass) {
    auto both = r.choice(t, "scale_type", prefix, kScaleTypes);
    if (!both.ok()) return both.error();
    auto tx = r.choice(t, "scale_type_x", prefix, kScaleTypes);
    if (!tx.ok()) return tx.error();
    auto ty = r.choice(t, "scale_type_y", prefix, kScaleTypes);
    if (!ty.ok()) return ty.error();
    if (both.value() && (tx.value() || ty.value()))
        return r.error(t.get("scale_type"), prefix + ".scale_type", "give scale_type or scale_type_x/_y, not both");
    std::optional<double> fx, fy;
    if (const toml::node* scale = t.get("scale")) {
        if (const toml::array* a = scale->as_array()) {
            if (a->size() != 2 || !a->get(0)->is_number() || !a->get(1)->is_number())
                return r.error(scale, prefix + ".scale", "must be a number or [x, y]");
            fx = a->get(0)->value<double>();
            fy = a->get(1)->value<double>();
        } else if (scale->is_number()) {
            fx = fy = scale->value<double>();
        } else {
            return r.error(scale, prefix + ".scale", "must be a number or [x, y]");
        }
        for (double f : {*fx, *fy})
            if (!(f > 0.0 && f <= kMaxSceneDimension))
                return r.error(scale, prefix + ".scale", fmt::format("a scale must be above 0 (and at most {})", kMaxSceneDimension));
    }
    auto type_of = [](const std::optional<size_t>& i) { return static_cast<PassScale::Type>(*i); };
    if (both.value() || tx.value() || fx) {
        PassScale s;
        s.type = tx.value() ? type_of(tx.value()) : both.value() ? type_of(both.value()) : PassScale::Type::Source;
        s.factor = fx.value_or(1.0);
        pass.scale_x = s;
    }
    if (both.value() || ty.value() || fy) {
        PassScale s;
        s.type = ty.value() ? type_of(ty.value()) : both.value() ? type_of(both.value()) : PassScale::Type::Source;
        s.factor = fy.value_or(1.0);
        pass.scale_y = s;
    }
    for (const auto& s : {pass.scale_x, pass.scale_y})
        if (s && s->type == PassScale::Type::Absolute && std::floor(s->factor) != s->factor)
            return r.error(t.get("scale"), prefix + ".scale", "an absolute scale is a whole number of pixels");
    return Ok{};
}

// `supersample` of a [[pass]] or a [passes.<alias>] table: samples per pixel side, 1..4.
Result<std::optional<int>> parse_supersample(const TomlReader& r, const toml::table& t, const std::string& prefix) {
    auto n = r.integer(t, "supersample", prefix);
    if (!n.ok()) return n.error();
    if (!n.value()) return std::optional<int>();
    if (*n.value() < 1 || *n.value() > 4)
        return r.error(t.get("supersample"), prefix + ".supersample", "must be 1..4 (samples per pixel side the pass averages)");
    return std::optional<int>(static_cast<int>(*n.value()));
}

// filter, wrap and (with_mipmap) mipmap and mip_filter of a table, each where given: a pass's main
// input, one of its [pass.textures] written as a table, or a LUT.
Result<TextureSampling> parse_sampling(const TomlReader& r, const toml::table& t, const std::string& field, bool with_mipmap) {
    TextureSampling out;
    auto filter = r.choice(t, "filter", field, kFilters);
    if (!filter.ok()) return filter.error();
    if (filter.value()) out.filter = static_cast<Filter>(*filter.value());
    auto wrap = r.choice(t, "wrap", field, kWraps);
    if (!wrap.ok()) return wrap.error();
    if (wrap.value()) out.wrap = static_cast<Wrap>(*wrap.value());
    if (!with_mipmap) return out;
    auto mipmap = r.boolean(t, "mipmap", field);
    if (!mipmap.ok()) return mipmap.error();
    out.mipmap = mipmap.value();
    auto mip_filter = r.choice(t, "mip_filter", field, kFilters);
    if (!mip_filter.ok()) return mip_filter.error();
    if (mip_filter.value()) out.mip_filter = static_cast<Filter>(*mip_filter.value());
    return out;
}

Result<PassEntry> parse_pass(const TomlReader& r, const toml::table& t, size_t index, const TemplateLibrary* library) {
    const std::string prefix = "pass[" + std::to_string(index) + "]";
    if (auto s = r.only_keys(t, {"alias", "preset", "stages", "scale_type", "scale_type_x", "scale_type_y", "scale", "format",
                                 "input", "filter", "wrap", "mipmap", "mip_filter", "textures", "frame_count_mod", "supersample"},
                             prefix);
        !s.ok())
        return s.error();
    PassEntry pass;
    pass.line = r.line_of(t);
    auto alias = r.string(t, "alias", prefix, true);
    if (!alias.ok()) return alias.error();
    if (!detail::is_identifier(alias.value()))
        return r.error(t.get("alias"), prefix + ".alias", detail::not_identifier(alias.value()));
    pass.alias = alias.value();
    const std::string field = "pass." + pass.alias;
    auto preset = r.string(t, "preset", field, false);
    if (!preset.ok()) return preset.error();
    pass.preset = preset.value();
    if (const toml::node* stages = t.get("stages")) {
        auto entries = parse_stage_entries(r, *stages, field + ".stages", library);
        if (!entries.ok()) return entries.error();
        pass.stages = std::move(entries.value());
    }
    if (auto s = parse_scale(r, t, field, pass); !s.ok()) return s.error();
    auto format = r.choice(t, "format", field, kFormats);
    if (!format.ok()) return format.error();
    if (format.value()) pass.format = static_cast<PixelFormat>(*format.value());
    if (t.get("input")) {
        auto input = r.string(t, "input", field, true);
        if (!input.ok()) return input.error();
        pass.input = input.value();
    }
    auto main_sampling = parse_sampling(r, t, field, true);
    if (!main_sampling.ok()) return main_sampling.error();
    pass.filter = main_sampling.value().filter;
    pass.wrap = main_sampling.value().wrap;
    pass.mipmap = main_sampling.value().mipmap;
    pass.mip_filter = main_sampling.value().mip_filter;
    if (const toml::node* textures = t.get("textures")) {
        const toml::table* tt = textures->as_table();
        if (!tt) return r.error(textures, field + ".textures", "must be a table of name = \"source\"");
        for (const auto& [name, node] : *tt) {
            const std::string key(name.str()), tfield = field + ".textures." + key;
            pass.texture_lines[key] = r.line_of(node);
            if (node.is_string()) {
                pass.textures[key] = std::string(node.as_string()->get());
                continue;
            }
            // { from = "source", filter = ..., wrap = ..., mipmap = ... }: how this texture is sampled.
            const toml::table* entry = node.as_table();
            if (!entry) return r.error(&node, tfield, "must be a string naming a source, or { from = \"source\", filter, wrap, mipmap, mip_filter }");
            if (auto k = r.only_keys(*entry, {"from", "filter", "wrap", "mipmap", "mip_filter"}, tfield); !k.ok()) return k.error();
            auto from = r.string(*entry, "from", tfield, true);
            if (!from.ok()) return from.error();
            pass.textures[key] = from.value();
            auto sampling = parse_sampling(r, *entry, tfield, true);
            if (!sampling.ok()) return sampling.error();
            pass.texture_sampling[key] = sampling.value();
        }
    }
    auto mod = r.integer(t, "frame_count_mod", field);
    if (!mod.ok()) return mod.error();
    if (mod.value()) {
        if (*mod.value() < 0 || *mod.value() > (1 << 30))  // 0: as is, as RetroArch reads it
            return r.error(t.get("frame_count_mod"), field + ".frame_count_mod", "must be 0..2^30 (0: as is)");
        pass.frame_count_mod = static_cast<int>(*mod.value());
    }
    auto supersample = parse_supersample(r, t, field);
    if (!supersample.ok()) return supersample.error();
    pass.supersample = supersample.value();
    return pass;
}

Result<LutSpec> parse_lut(const TomlReader& r, const std::string& name, const toml::node& node) {
    const std::string field = "lut." + name;
    const toml::table* t = node.as_table();
    if (!t) return r.error(&node, field, "must be a table");
    if (!detail::is_identifier(name)) return r.error(&node, field, detail::not_identifier(name));
    LutSpec lut;
    lut.name = name;
    lut.where = {r.path(), r.line_of(node)};
    auto generator = r.string(*t, "generator", field, false);
    if (!generator.ok()) return generator.error();
    auto file = r.string(*t, "file", field, false);
    if (!file.ok()) return file.error();
    if (generator.value().empty() == file.value().empty())
        return r.error(&node, field, "needs exactly one of generator = \"...\" or file = \"...\"");
    lut.generator = generator.value();
    lut.file = file.value();
    auto sampling = parse_sampling(r, *t, field, false);
    if (!sampling.ok()) return sampling.error();
    lut.filter = sampling.value().filter.value_or(lut.filter);
    lut.wrap = sampling.value().wrap.value_or(lut.wrap);
    const LutGenerator* gen = lut.generator.empty() ? nullptr : find_lut_generator(lut.generator);
    if (!lut.generator.empty() && !gen) {
        std::vector<std::string> names;
        for (const auto& g : lut_generators()) names.emplace_back(g.name);
        return r.error(t->get("generator"), field + ".generator",
                       "unknown generator '" + lut.generator + "' (generators: " + join_list(names) + ")");
    }
    for (const auto& [key, value] : *t) {
        const std::string k(key.str());
        if (k == "generator" || k == "file" || k == "filter" || k == "wrap") continue;
        const LutParam* param = nullptr;
        if (gen)
            for (const LutParam& p : gen->params)
                if (p.name == k) param = &p;
        if (!param) {
            std::vector<std::string> names = {"generator", "file", "filter", "wrap"};
            if (gen)
                for (const LutParam& p : gen->params) names.push_back(p.name);
            return r.error(&value, field + "." + k, "unknown key (expected one of: " + join_list(names) + ")");
        }
        auto v = r.number(*t, k, field);
        if (!v.ok()) return v.error();
        if (*v.value() < param->min || *v.value() > param->max)
            return r.error(&value, field + "." + k, fmt::format("{} is outside [{}, {}]", *v.value(), param->min, param->max));
        lut.params[k] = *v.value();
    }
    if (gen)
        for (const LutParam& p : gen->params) lut.params.emplace(p.name, p.default_value);
    return lut;
}

// [source], [display] and [time].
Status parse_scene_tables(const TomlReader& r, const toml::table& root, PresetFile& file) {
    if (const toml::node* node = root.get("source")) {
        const toml::table* t = node->as_table();
        if (!t) return r.error(node, "source", "must be a table");
        if (auto s = r.only_keys(*t, {"size", "pixel_aspect", "fit"}, "source"); !s.ok()) return s.error();
        auto size = r.int_pair(*t, "size", "source", 1, kMaxSceneDimension);
        if (!size.ok()) return size.error();
        if (size.value()) std::tie(file.source_width, file.source_height) = *size.value();
        if (const std::string over = source_budget_error(file.source_width.value_or(1), file.source_height.value_or(1)); !over.empty())
            return r.error(t->get("size"), "source.size", over);
        auto par = r.int_pair(*t, "pixel_aspect", "source", 1, 1000);
        if (!par.ok()) return par.error();
        if (par.value()) std::tie(file.pixel_aspect_x, file.pixel_aspect_y) = *par.value();
        auto fit = r.choice(*t, "fit", "source", {"stretch", "width", "height", "contain"});
        if (!fit.ok()) return fit.error();
        if (fit.value()) file.source_fit = static_cast<SourceFit>(*fit.value());
    }
    if (const toml::node* node = root.get("display")) {
        const toml::table* t = node->as_table();
        if (!t) return r.error(node, "display", "must be a table");
        if (auto s = r.only_keys(*t, {"fit", "aspect"}, "display"); !s.ok()) return s.error();
        auto fit = r.choice(*t, "fit", "display", {"stretch", "aspect", "integer"});
        if (!fit.ok()) return fit.error();
        if (fit.value()) file.fit = static_cast<DisplayFit>(*fit.value());
        auto aspect = r.int_pair(*t, "aspect", "display", 1, 1000);
        if (!aspect.ok()) return aspect.error();
        if (aspect.value()) std::tie(file.screen_aspect_x, file.screen_aspect_y) = *aspect.value();
    }
    if (const toml::node* node = root.get("time")) {
        const toml::table* t = node->as_table();
        if (!t) return r.error(node, "time", "must be a table");
        if (auto s = r.only_keys(*t, {"fps"}, "time"); !s.ok()) return s.error();
        auto fps = r.number(*t, "fps", "time");
        if (!fps.ok()) return fps.error();
        if (fps.value()) {
            if (!(*fps.value() > 0.0 && *fps.value() <= 1000.0)) return r.error(t->get("fps"), "time.fps", "must be above 0 and at most 1000");
            file.fps = *fps.value();
        }
    }
    return Ok{};
}

}  // namespace

// [<prefix>.<alias>] tables: per pass, its stages' changes and a new scale factor.
Result<std::map<std::string, PassOverride>> parse_pass_overrides(const TomlReader& r, const toml::node& node, const std::string& prefix,
                                                                 const TemplateLibrary* library) {
    const toml::table* t = node.as_table();
    if (!t) return r.error(&node, prefix, "must be a table of [" + prefix + ".<alias>] sections");
    std::map<std::string, PassOverride> out;
    for (const auto& [alias, pass_node] : *t) {
        const std::string field = prefix + "." + std::string(alias.str());
        const toml::table* pt = pass_node.as_table();
        if (!pt) return r.error(&pass_node, field, "must be a table");
        if (auto s = r.only_keys(*pt, {"stages", "scale", "supersample"}, field); !s.ok()) return s.error();
        PassOverride o;
        o.line = r.line_of(pass_node);
        if (const toml::node* stages = pt->get("stages")) {
            auto entries = parse_stage_entries(r, *stages, field + ".stages", library);
            if (!entries.ok()) return entries.error();
            o.stages = std::move(entries.value());
        }
        if (const toml::node* scale = pt->get("scale")) {
            const std::optional<double> f = scale->value<double>();
            if (!scale->is_number() || !f || !(*f > 0.0 && *f <= 16.0))
                return r.error(scale, field + ".scale", "must be a number above 0 and at most 16 (the pass's factor on both axes)");
            o.scale = *f;
            o.scale_line = r.line_of(*scale);
        }
        auto supersample = parse_supersample(r, *pt, field);
        if (!supersample.ok()) return supersample.error();
        o.supersample = supersample.value();
        out[std::string(alias.str())] = std::move(o);
    }
    return out;
}

// [tiers.<name>] tables: a one-line doc and the passes they change, in file order.
Result<std::vector<TierEntry>> parse_tiers(const TomlReader& r, const toml::node& node, const TemplateLibrary* library) {
    const toml::table* t = node.as_table();
    if (!t) return r.error(&node, "tiers", "must be a table of [tiers.<name>] sections");
    std::vector<TierEntry> out;
    for (const auto& [key, tier_node] : *t) {
        TierEntry tier;
        tier.name = std::string(key.str());
        const std::string field = "tiers." + tier.name;
        tier.line = r.line_of(tier_node);
        // A tier's name joins the point and filtered tiers' ("<name>+filtered") in reports and CLI.
        if (!is_preset_name(tier.name) || tier.name == "point" || tier.name == "filtered")
            return r.error(&tier_node, field, "'" + tier.name + "' must be 1 to 64 lower-case letters, digits, '-' or '_', starting with a letter or digit, and not 'point' or 'filtered'");
        const toml::table* tt = tier_node.as_table();
        if (!tt) return r.error(&tier_node, field, "must be a table");
        if (auto s = r.only_keys(*tt, {"doc", "passes"}, field); !s.ok()) return s.error();
        auto doc = r.string(*tt, "doc", field, true);
        if (!doc.ok()) return doc.error();
        tier.doc = doc.value();
        if (tier.doc.empty() || tier.doc.find('\n') != std::string::npos)
            return r.error(tt->get("doc"), field + ".doc", "must be one non-empty line");
        const toml::node* passes = tt->get("passes");
        if (!passes) return r.error(&tier_node, field + ".passes", "a tier changes at least one pass ([" + field + ".passes.<alias>])");
        auto parsed = parse_pass_overrides(r, *passes, field + ".passes", library);
        if (!parsed.ok()) return parsed.error();
        tier.passes = std::move(parsed.value());
        if (tier.passes.empty()) return r.error(passes, field + ".passes", "a tier changes at least one pass");
        out.push_back(std::move(tier));
    }
    std::sort(out.begin(), out.end(), [](const TierEntry& a, const TierEntry& b) { return a.line < b.line; });
    return out;
}

Result<PresetFile> parse_preset_file(const std::string& text, const std::string& path,
                                     const TemplateLibrary* library) {
    TomlReader r(path);
    auto parsed = r.parse(text);
    if (!parsed.ok()) return parsed.error();
    const toml::table& root = parsed.value();
    if (auto s = r.only_keys(root, {"name", "doc", "base", "filter", "stages", "pass", "passes", "tiers", "source", "display", "time", "lut", "format", "glitch"}, "");
        !s.ok())
        return s.error();

    PresetFile file;
    file.where = {path, 1};
    for (const auto& [key, node] : root) file.key_lines[std::string(key.str())] = r.line_of(node);
    auto name = r.string(root, "name", "", true);
    if (!name.ok()) return name.error();
    file.name = name.value();
    if (!is_preset_name(file.name))
        return r.error(root.get("name"), "name",
                       "'" + file.name + "' must be 1 to 64 lower-case letters, digits, '-' or '_', starting with a letter or digit (it becomes a file name)");
    auto doc = r.string(root, "doc", "", true);
    if (!doc.ok()) return doc.error();
    file.doc = doc.value();
    if (file.doc.empty() || file.doc.find('\n') != std::string::npos)
        return r.error(root.get("doc"), "doc", "must be one non-empty line");
    auto base = r.string(root, "base", "", false);
    if (!base.ok()) return base.error();
    file.base = base.value();
    auto filter = r.choice(root, "filter", "", kFilters);
    if (!filter.ok()) return filter.error();
    if (filter.value()) file.filter = static_cast<Filter>(*filter.value());

    auto format = preset_format(r, root);
    if (!format.ok()) return format.error();
    file.format = format.value();
    if (file.format == 1) {
        if (auto s = migrate_glitch_preset(r, root, library, file); !s.ok()) return s.error();
        return file;
    }
    if (root.get("glitch"))
        return r.error(root.get("glitch"), "glitch", "[glitch] is the format-1 (Glitch) layout; this file says format = " +
                                                         std::to_string(file.format));

    if (const toml::node* stages = root.get("stages")) {
        auto entries = parse_stage_entries(r, *stages, "stages", library);
        if (!entries.ok()) return entries.error();
        file.stages = std::move(entries.value());
    }
    if (const toml::node* passes = root.get("pass")) {
        const toml::array* a = passes->as_array();
        if (!a || !a->is_array_of_tables() || a->empty()) return r.error(passes, "pass", "must be [[pass]] tables");
        if (root.get("stages"))
            return r.error(root.get("stages"), "stages", "a preset with [[pass]] sets its stages in each pass ([pass.stages.<name>])");
        size_t index = 0;
        for (const toml::node& node : *a) {
            auto pass = parse_pass(r, *node.as_table(), index++, library);
            if (!pass.ok()) return pass.error();
            for (const PassEntry& other : file.passes)
                if (other.alias == pass.value().alias)
                    return r.error(node.as_table()->get("alias"), "pass." + other.alias + ".alias",
                                   "alias '" + other.alias + "' is already used at line " + std::to_string(other.line));
            file.passes.push_back(std::move(pass.value()));
        }
    }
    if (const toml::node* overrides = root.get("passes")) {
        if (root.get("pass"))
            return r.error(overrides, "passes", "[passes.<alias>] changes a base preset's passes; this file defines its own [[pass]]");
        auto parsed = parse_pass_overrides(r, *overrides, "passes", library);
        if (!parsed.ok()) return parsed.error();
        file.pass_overrides = std::move(parsed.value());
    }
    if (const toml::node* tiers = root.get("tiers")) {
        auto parsed = parse_tiers(r, *tiers, library);
        if (!parsed.ok()) return parsed.error();
        file.tiers = std::move(parsed.value());
    }
    if (auto s = parse_scene_tables(r, root, file); !s.ok()) return s.error();
    if (const toml::node* luts = root.get("lut")) {
        const toml::table* t = luts->as_table();
        if (!t) return r.error(luts, "lut", "must be a table of [lut.<name>] sections");
        for (const auto& [name, node] : *t) {
            auto lut = parse_lut(r, std::string(name.str()), node);
            if (!lut.ok()) return lut.error();
            file.luts.push_back(std::move(lut.value()));
        }
    }
    return file;
}

}  // namespace crtforge
