// Preset files -> a resolved Preset: inheritance, then the scene — its passes with their stages,
// sizes, formats and inputs — checked as a graph: every input names something that exists, no pass
// reads this frame's output of itself or of a later pass (only feedback may go backwards), and
// passes nothing reads are dropped. Errors name the preset file, line and field.
#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "crtforge/lut_file.hpp"
#include "crtforge/template_library.hpp"

namespace crtforge {

const char* filter_name(Filter filter) { return filter == Filter::Linear ? "linear" : "nearest"; }

const char* wrap_name(Wrap wrap) {
    switch (wrap) {
        case Wrap::ClampToEdge: return "clamp_to_edge";
        case Wrap::ClampToBorder: return "clamp_to_border";
        case Wrap::Repeat: return "repeat";
        case Wrap::MirroredRepeat: return "mirrored_repeat";
    }
    return "?";
}

const char* pixel_format_name(PixelFormat format) {
    switch (format) {
        case PixelFormat::Rgba8: return "rgba8";
        case PixelFormat::Rgba8Srgb: return "rgba8_srgb";
        case PixelFormat::Rgba16F: return "rgba16f";
        case PixelFormat::Rgba32F: return "rgba32f";
        case PixelFormat::Rgb10A2: return "rgb10a2";
        case PixelFormat::R16F: return "r16f";
        case PixelFormat::Rg16F: return "rg16f";
    }
    return "?";
}

const char* scale_type_name(PassScale::Type type) {
    switch (type) {
        case PassScale::Type::Source: return "source";
        case PassScale::Type::Viewport: return "viewport";
        case PassScale::Type::Absolute: return "absolute";
    }
    return "?";
}

const char* source_fit_name(SourceFit fit) {
    switch (fit) {
        case SourceFit::Stretch: return "stretch";
        case SourceFit::Width: return "width";
        case SourceFit::Height: return "height";
        case SourceFit::Contain: return "contain";
    }
    return "?";
}

const char* display_fit_name(DisplayFit fit) {
    switch (fit) {
        case DisplayFit::Stretch: return "stretch";
        case DisplayFit::Aspect: return "aspect";
        case DisplayFit::Integer: return "integer";
    }
    return "?";
}

std::string TextureSource::str() const {
    switch (kind) {
        case Kind::Original: return frames_back ? "original@" + std::to_string(frames_back) : "original";
        case Kind::Pass: return name;
        case Kind::Feedback: return name + "@previous";
        case Kind::Lut: return "lut:" + name;
    }
    return "?";
}

const ResolvedStage* Pass::find_stage(const std::string& stage_name) const {
    for (const auto& s : stages)
        if (s.stage->name == stage_name) return &s;
    return nullptr;
}

const PassInput* Pass::find_input(const std::string& binding) const {
    for (const auto& i : inputs)
        if (i.binding == binding) return &i;
    return nullptr;
}

std::vector<std::string> Pass::texture_names() const {
    std::vector<std::string> names;
    for (const ResolvedStage& rs : stages)
        for (const std::string& t : rs.form->textures)
            if (std::find(names.begin(), names.end(), t) == names.end()) names.push_back(t);
    return names;
}

const ResolvedStage* Preset::find_stage(const std::string& stage_name) const {
    for (const Pass& p : passes)
        if (const ResolvedStage* s = p.find_stage(stage_name)) return s;
    return nullptr;
}

const Pass* Preset::find_pass(const std::string& alias) const {
    for (const Pass& p : passes)
        if (p.alias == alias) return &p;
    return nullptr;
}

const LutSpec* Preset::find_lut(const std::string& lut_name) const {
    for (const LutSpec& l : luts)
        if (l.name == lut_name) return &l;
    return nullptr;
}

int Preset::history_depth() const {
    int depth = 0;
    for (const Pass& p : passes)
        for (const PassInput& i : p.inputs)
            if (i.from.kind == TextureSource::Kind::Original) depth = std::max(depth, i.from.frames_back);
    return depth;
}

bool Preset::has_feedback() const {
    for (const Pass& p : passes)
        for (const PassInput& i : p.inputs)
            if (i.from.kind == TextureSource::Kind::Feedback) return true;
    return false;
}

namespace {

// How far back a pass may read the original: RetroArch offers OriginalHistory0..15.
// How deep `base` chains and `preset =` references may nest.
constexpr size_t kMaxInheritanceDepth = 32;

using StageValues = std::map<std::string, std::map<std::string, Value>>;  // enabled stage -> values set

void apply_entries(StageValues& enabled, const std::vector<PresetStageEntry>& entries) {
    for (const auto& entry : entries) {
        if (!entry.enabled) {
            enabled.erase(entry.stage);
            continue;
        }
        auto& values = enabled[entry.stage];
        for (const auto& [k, v] : entry.values) values[k] = v;
    }
}

// The enabled stages in pass order, each with its form and every value it reads. A value the
// `leaf` entries set that the chosen form never reads is almost always a mistake: an error there.
Result<std::vector<ResolvedStage>> resolve_stages(const std::vector<StageSpec>& specs, const StageValues& enabled,
                                                  const std::vector<PresetStageEntry>& leaf, const std::string& file,
                                                  const std::string& field_prefix) {
    std::vector<ResolvedStage> out;
    for (const StageSpec& spec : specs) {
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
        for (const auto& entry : leaf) {
            if (entry.stage != spec.name) continue;
            for (const auto& [k, v] : entry.values)
                if (!rs.values.count(k))
                    return make_error(fmt::format("is not read by form '{}' of stage '{}' (it reads: {})", rs.form->name,
                                                  spec.name, join_list(reads)),
                                      file, entry.value_lines.at(k), field_prefix + spec.name + "." + k);
        }
        out.push_back(std::move(rs));
    }
    // A program is the whole pass: nothing runs before or after it in the same shader.
    for (const ResolvedStage& rs : out)
        if (rs.stage->program && out.size() > 1) {
            std::string others;
            for (const ResolvedStage& o : out)
                if (&o != &rs) others += (others.empty() ? "" : ", ") + o.stage->name;
            return make_error("program stage '" + rs.stage->name + "' runs alone in its pass; turn off " + others, file, 0,
                              field_prefix + rs.stage->name);
        }
    return out;
}

// A LUT bound where a form reads a fixed layout (FormSpec::texture_sizes) must have that size:
// a picture of another size would be sampled as if it had the layout, silently wrong.
Status lut_fits_forms(const Pass& pass, const std::string& binding, const LutSpec& lut) {
    for (const ResolvedStage& rs : pass.stages) {
        if (!rs.form) continue;
        auto wanted = rs.form->texture_sizes.find(binding);
        if (wanted == rs.form->texture_sizes.end()) continue;
        std::optional<std::pair<int, int>> size;
        if (lut.bytes) {
            size = lut_picture_size(*lut.bytes);
        } else if (const LutGenerator* generator = lut.generator.empty() ? nullptr : find_lut_generator(lut.generator)) {
            const LutImage image = generator->generate(lut.params);
            size = std::make_pair(image.width, image.height);
        }
        if (size && *size != wanted->second)
            return make_error(fmt::format("is {}x{}, but form '{}' of stage '{}' reads '{}' as a {}x{} table", size->first, size->second,
                                          rs.form->name, rs.stage->name, binding, wanted->second.first, wanted->second.second),
                              lut.where.file, lut.where.line, "lut." + lut.name);
    }
    return Ok{};
}

// "original", "original@N", "<alias>", "<alias>@previous", "lut:<name>".
Result<TextureSource> parse_source(const std::string& text, const std::string& file, int line, const std::string& field) {
    TextureSource src;
    auto bad = [&](const std::string& why) {
        return make_error("'" + text + "' " + why +
                              " (sources: original, original@N, <pass alias>, <pass alias>@previous, lut:<name>)",
                          file, line, field);
    };
    if (text.rfind("lut:", 0) == 0) {
        src.kind = TextureSource::Kind::Lut;
        src.name = text.substr(4);
        if (src.name.empty()) return bad("names no LUT");
        return src;
    }
    const size_t at = text.find('@');
    const std::string head = text.substr(0, at), tail = at == std::string::npos ? "" : text.substr(at + 1);
    if (head.empty()) return bad("is not a source");
    if (head == "original") {
        src.kind = TextureSource::Kind::Original;
        if (at == std::string::npos) return src;
        if (tail.empty() || tail.size() > 2 || !std::all_of(tail.begin(), tail.end(), ::isdigit)) return bad("has a bad history depth");
        src.frames_back = std::stoi(tail);
        if (src.frames_back < 1 || src.frames_back > kMaxHistory)
            return bad("reads history deeper than " + std::to_string(kMaxHistory) + " frames, or 0 (write original)");
        return src;
    }
    src.name = head;
    if (at == std::string::npos) {
        src.kind = TextureSource::Kind::Pass;
        return src;
    }
    if (tail != "previous") return bad("has an unknown suffix '@" + tail + "'");
    src.kind = TextureSource::Kind::Feedback;
    return src;
}

// Every texture the pass's enabled forms read is bound by the pass; else an error at `line` naming
// the stage that reads the unbound one.
Status textures_bound(const Pass& pass, const std::string& file, int line, const std::string& field) {
    for (const std::string& t : pass.texture_names())
        if (!pass.find_input(t)) {
            std::string stage;
            for (const ResolvedStage& rs : pass.stages)
                if (std::find(rs.form->textures.begin(), rs.form->textures.end(), t) != rs.form->textures.end()) stage = rs.stage->name;
            return make_error("stage '" + stage + "' reads texture '" + t + "': bind it with [pass.textures] " + t + " = \"...\"", file,
                              line, field);
        }
    return Ok{};
}

// A supersampled pass averages its stages' math; a pass without stages is a copy, with nothing to average.
Status supersample_has_stages(const Pass& pass, const std::string& file, int line, const std::string& field) {
    if (pass.supersample > 1 && pass.stages.empty())
        return make_error("pass '" + pass.alias + "' has no stages: supersample averages a pass's stages, and a copy has none", file, line, field);
    return Ok{};
}

// A pass's scale factor replaced on both axes, its scale type kept; an absolute size (pixels) is
// not a factor to change.
Status rescale(Pass& pass, double factor, const std::string& file, int line, const std::string& field) {
    if (pass.scale_x.type == PassScale::Type::Absolute || pass.scale_y.type == PassScale::Type::Absolute)
        return make_error("pass '" + pass.alias + "' has an absolute size in pixels; scale changes a source or viewport factor", file, line, field);
    pass.scale_x.factor = factor;
    pass.scale_y.factor = factor;
    return Ok{};
}

// `preset` with `tier`'s changes (declared in `file`): each named pass rescaled and its stages
// changed as a derived preset's [passes.<alias>] would change them. An `inherited` tier (a base
// preset's, checked against the base's passes when the base loaded) skips the passes this preset
// dropped (a derived preset that turns a stage off may leave a pass nothing reads).
Result<DeclaredTier> apply_tier(const std::vector<StageSpec>& specs, const Preset& preset, const TierEntry& tier, const std::string& file,
                                bool inherited) {
    Preset out = preset;
    out.tiers.clear();
    DeclaredTier declared{tier.name, tier.doc, {file, tier.line}, nullptr, {}};
    for (const auto& [alias, o] : tier.passes) {
        const std::string field = "tiers." + tier.name + ".passes." + alias;
        auto pass = std::find_if(out.passes.begin(), out.passes.end(), [&](const Pass& p) { return p.alias == alias; });
        if (pass == out.passes.end() && inherited) continue;
        if (pass == out.passes.end()) return make_error("there is no pass '" + alias + "' in preset '" + preset.name + "'", file, o.line, field);
        if (o.scale) {
            declared.changes.push_back(fmt::format("pass {}: scale {} -> {}", alias, value_to_string(Value{pass->scale_x.factor}),
                                                   value_to_string(Value{*o.scale})));
            if (auto s = rescale(*pass, *o.scale, file, o.scale_line, field + ".scale"); !s.ok()) return s.error();
        }
        if (o.supersample) {
            declared.changes.push_back(fmt::format("pass {}: supersample {} -> {}", alias, pass->supersample, *o.supersample));
            pass->supersample = *o.supersample;
        }
        if (o.stages.empty()) continue;
        StageValues enabled;
        for (const ResolvedStage& rs : pass->stages) enabled[rs.stage->name] = rs.values;
        apply_entries(enabled, o.stages);
        auto stages = resolve_stages(specs, enabled, o.stages, file, field + ".stages.");
        if (!stages.ok()) return stages.error();
        for (const ResolvedStage& now : stages.value()) {
            const ResolvedStage* was = pass->find_stage(now.stage->name);
            if (!was) {
                declared.changes.push_back(fmt::format("pass {}: {} on", alias, now.stage->name));
                continue;
            }
            for (const auto& [param, value] : now.values)
                if (!was->values.count(param) || !(was->values.at(param) == value))
                    declared.changes.push_back(fmt::format("pass {}: {}.{} {} -> {}", alias, now.stage->name, param,
                                                           was->values.count(param) ? value_to_string(was->values.at(param)) : "-",
                                                           value_to_string(value)));
        }
        for (const ResolvedStage& was : pass->stages)
            if (std::none_of(stages.value().begin(), stages.value().end(), [&](const ResolvedStage& rs) { return rs.stage == was.stage; }))
                declared.changes.push_back(fmt::format("pass {}: {} off", alias, was.stage->name));
        pass->stages = std::move(stages.value());
        if (auto s = textures_bound(*pass, file, o.line, field + ".stages"); !s.ok()) return s.error();
    }
    for (const auto& [alias, o] : tier.passes)
        for (const Pass& pass : out.passes)
            if (pass.alias == alias)
                if (auto s = supersample_has_stages(pass, file, o.line, "tiers." + tier.name + ".passes." + alias + ".supersample"); !s.ok())
                    return s.error();
    declared.preset = std::make_shared<const Preset>(std::move(out));
    return declared;
}

// Every [tiers.<name>] of the chain applied to `preset`: a base's tiers first, a derived file's
// tier of the same name replacing the base's. An inherited tier that changes nothing left in the
// preset (its passes were all dropped) goes with them.
Status add_declared_tiers(const std::vector<StageSpec>& specs, Preset& preset, const std::vector<const PresetFile*>& chain) {
    std::vector<std::pair<const TierEntry*, const PresetFile*>> tiers;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it)
        for (const TierEntry& t : (*it)->tiers) {
            auto same = std::find_if(tiers.begin(), tiers.end(), [&](const auto& e) { return e.first->name == t.name; });
            if (same != tiers.end()) *same = {&t, *it};
            else tiers.emplace_back(&t, *it);
        }
    for (const auto& [tier, file] : tiers) {
        const bool inherited = file != chain.front();
        auto declared = apply_tier(specs, preset, *tier, file->where.file, inherited);
        if (!declared.ok()) return declared.error();
        if (inherited && declared.value().changes.empty()) continue;
        preset.tiers.push_back(std::move(declared.value()));
    }
    return Ok{};
}

}  // namespace

Result<Preset> TemplateLibrary::resolve(const std::vector<PresetFile>& files, const std::string& name) const {
    std::set<std::string> visiting;
    return resolve_preset(files, name, visiting);
}

Result<Preset> TemplateLibrary::resolve_preset(const std::vector<PresetFile>& files, const std::string& name,
                                               std::set<std::string>& visiting) const {
    auto find_file = [&](const std::string& n) -> const PresetFile* {
        for (const auto& f : files)
            if (f.name == n) return &f;
        return nullptr;
    };
    const PresetFile* leaf = find_file(name);
    if (!leaf) return make_error("unknown preset '" + name + "'");
    if (visiting.size() >= kMaxInheritanceDepth)
        return make_error("presets nest more than " + std::to_string(kMaxInheritanceDepth) + " deep", leaf->where.file, 1, "base");
    visiting.insert(name);

    // Walk to the root of the inheritance chain, refusing cycles.
    std::vector<const PresetFile*> chain{leaf};
    std::set<std::string> seen{leaf->name};
    while (!chain.back()->base.empty()) {
        const PresetFile* child = chain.back();
        const int line = child->key_lines.count("base") ? child->key_lines.at("base") : 1;
        const PresetFile* base = find_file(child->base);
        if (!base) {
            if (auto broken = broken_.find(child->base); broken != broken_.end())
                return make_error("base preset '" + child->base + "' does not load (" + broken->second.str() + ")", child->where.file, line, "base");
            return make_error("base preset '" + child->base + "' does not exist", child->where.file, line, "base");
        }
        if (!seen.insert(base->name).second)
            return make_error("inheritance cycle through '" + base->name + "'", child->where.file, line, "base");
        if (chain.size() >= kMaxInheritanceDepth)
            return make_error("inheritance deeper than " + std::to_string(kMaxInheritanceDepth) + " presets", child->where.file, line,
                              "base");
        chain.push_back(base);
    }

    Preset preset;
    preset.name = leaf->name;
    preset.doc = leaf->doc;
    preset.where = leaf->where;
    for (const auto* f : chain) preset.lineage.push_back(f->name);

    // Settings apply from the root down: more derived files override, key by key.
    SceneSettings& scene = preset.scene;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        const PresetFile& f = **it;
        if (f.filter) preset.filter = *f.filter;
        if (f.source_width) std::tie(scene.source_width, scene.source_height) = std::make_pair(*f.source_width, *f.source_height);
        if (f.pixel_aspect_x) std::tie(scene.pixel_aspect_x, scene.pixel_aspect_y) = std::make_pair(*f.pixel_aspect_x, *f.pixel_aspect_y);
        if (f.screen_aspect_x)
            std::tie(scene.screen_aspect_x, scene.screen_aspect_y) = std::make_pair(*f.screen_aspect_x, *f.screen_aspect_y);
        if (f.source_fit) scene.source_fit = *f.source_fit;
        if (f.fit) scene.fit = *f.fit;
        if (f.fps) scene.fps = *f.fps;
        for (const LutSpec& lut : f.luts) {
            auto existing = std::find_if(preset.luts.begin(), preset.luts.end(), [&](const LutSpec& l) { return l.name == lut.name; });
            if (existing != preset.luts.end()) *existing = lut;
            else preset.luts.push_back(lut);
        }
    }

    // The pass list comes from the most derived file that defines one; files derived from that one
    // may change its passes' stages by alias.
    auto definer = std::find_if(chain.begin(), chain.end(), [](const PresetFile* f) { return !f->passes.empty(); });
    if (definer == chain.end()) {
        for (const PresetFile* f : chain)
            if (!f->pass_overrides.empty())
                return make_error("[passes." + f->pass_overrides.begin()->first + "] changes passes, but no base defines [[pass]]",
                                  f->where.file, f->pass_overrides.begin()->second.line, "passes");
        StageValues enabled;
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) apply_entries(enabled, (*it)->stages);
        auto stages = resolve_stages(stages_, enabled, leaf->stages, leaf->where.file, "stages.");
        if (!stages.ok()) return stages.error();
        Pass pass;
        pass.alias = "main";
        pass.stages = std::move(stages.value());
        pass.where = leaf->where;
        pass.inputs.push_back({"source", {}, preset.filter, Wrap::ClampToEdge, false, 0});
        for (const std::string& t : pass.texture_names()) {
            // Blame the entry that enabled the stage reading it, in whichever file of the chain.
            std::string file = leaf->where.file, field = "stages";
            int line = 1;
            for (const ResolvedStage& rs : pass.stages) {
                if (std::find(rs.form->textures.begin(), rs.form->textures.end(), t) == rs.form->textures.end()) continue;
                for (const PresetFile* f : chain)
                    for (const PresetStageEntry& e : f->stages)
                        if (e.stage == rs.stage->name && line == 1) {
                            file = f->where.file;
                            line = e.line;
                            field = "stages." + e.stage;
                        }
            }
            return make_error("stage of preset '" + name + "' reads texture '" + t + "': only a [[pass]] can bind it ([pass.textures] " +
                                  t + " = \"...\")",
                              file, line, field);
        }
        preset.passes.push_back(std::move(pass));
        if (preset.scene.source_fit != SourceFit::Stretch && !preset.scene.source_width)
            return make_error("a source fit other than stretch needs the source's size ([source] size = [w, h])",
                              leaf->where.file, leaf->key_lines.count("source") ? leaf->key_lines.at("source") : 1, "source.fit");
        if (auto s = add_declared_tiers(stages_, preset, chain); !s.ok()) return s.error();
        visiting.erase(name);
        return preset;
    }

    for (auto it = chain.begin(); it != definer; ++it)
        if (!(*it)->stages.empty())
            return make_error("a preset whose base has [[pass]] sets stages per pass ([passes.<alias>.stages.<name>])",
                              (*it)->where.file, (*it)->stages.front().line, "stages");
    const PresetFile& def = **definer;
    const std::string& file = def.where.file;
    for (auto it = chain.begin(); it != definer; ++it)
        for (const auto& [alias, o] : (*it)->pass_overrides)
            if (std::none_of(def.passes.begin(), def.passes.end(), [&](const PassEntry& p) { return p.alias == alias; }))
                return make_error("there is no pass '" + alias + "' in base preset '" + def.name + "'", (*it)->where.file, o.line,
                                  "passes." + alias);

    const size_t count = def.passes.size();
    for (size_t index = 0; index < count; ++index) {
        const PassEntry& entry = def.passes[index];
        const std::string field = "pass." + entry.alias;
        Pass pass;
        pass.alias = entry.alias;
        pass.where = {file, entry.line};
        StageValues enabled;
        Filter filter = index == 0 ? preset.filter : Filter::Linear;
        if (!entry.preset.empty()) {
            if (visiting.count(entry.preset))
                return make_error("preset '" + entry.preset + "' refers back to itself", file, entry.line, field + ".preset");
            auto from = resolve_preset(files, entry.preset, visiting);
            if (!from.ok()) {
                if (auto broken = broken_.find(entry.preset); broken != broken_.end())
                    return make_error("preset '" + entry.preset + "' does not load (" + broken->second.str() + ")", file, entry.line,
                                      field + ".preset");
                if (!find_file(entry.preset))
                    return make_error("preset '" + entry.preset + "' does not exist", file, entry.line, field + ".preset");
                return from.error();
            }
            if (!from.value().single_pass())
                return make_error("preset '" + entry.preset + "' has several passes; a pass can start from a single-pass preset",
                                  file, entry.line, field + ".preset");
            for (const ResolvedStage& rs : from.value().passes.front().stages) enabled[rs.stage->name] = rs.values;
            filter = from.value().filter;
        }
        apply_entries(enabled, entry.stages);
        std::vector<PresetStageEntry> leaf_entries = entry.stages;
        // Overrides from the files derived from the definer, root-most first.
        const PassOverride* scaled = nullptr;  // the most derived one that sets a scale, and its file
        std::optional<int> supersample = entry.supersample;  // the most derived one set
        std::string scaled_file;
        for (auto it = definer; it != chain.begin();) {
            --it;
            auto o = (*it)->pass_overrides.find(entry.alias);
            if (o == (*it)->pass_overrides.end()) continue;
            apply_entries(enabled, o->second.stages);
            if (*it == leaf) leaf_entries = o->second.stages;
            if (o->second.scale) {
                scaled = &o->second;
                scaled_file = (*it)->where.file;
            }
            if (o->second.supersample) supersample = *o->second.supersample;
        }
        const std::string& values_file = leaf == &def ? file : leaf->where.file;
        const std::string values_field = leaf == &def ? field + ".stages." : "passes." + entry.alias + ".stages.";
        auto stages = resolve_stages(stages_, enabled, leaf == &def || leaf->pass_overrides.count(entry.alias) ? leaf_entries
                                                                                                              : std::vector<PresetStageEntry>{},
                                     values_file, values_field);
        if (!stages.ok()) return stages.error();
        pass.stages = std::move(stages.value());

        const bool last = index + 1 == count;
        const PassScale fallback{last ? PassScale::Type::Viewport : PassScale::Type::Source, 1.0};
        pass.scale_x = entry.scale_x.value_or(fallback);
        pass.scale_y = entry.scale_y.value_or(fallback);
        if (scaled)
            if (auto s = rescale(pass, *scaled->scale, scaled_file, scaled->scale_line, "passes." + entry.alias + ".scale"); !s.ok())
                return s.error();
        pass.format = entry.format.value_or(PixelFormat::Rgba8);
        pass.frame_count_mod = entry.frame_count_mod.value_or(0);
        pass.supersample = supersample.value_or(1);
        if (auto s = supersample_has_stages(pass, file, entry.line, field + ".supersample"); !s.ok()) return s.error();

        // The main input: the previous pass's output, or the original for the first pass.
        const std::string main = entry.input.value_or(index == 0 ? "original" : def.passes[index - 1].alias);
        auto main_source = parse_source(main, file, entry.line, field + ".input");
        if (!main_source.ok()) return main_source.error();
        pass.inputs.push_back({"source", main_source.value(), entry.filter.value_or(filter), entry.wrap.value_or(Wrap::ClampToEdge),
                               entry.mipmap.value_or(false), entry.line});
        pass.inputs.back().mip_filter = entry.mip_filter.value_or(pass.inputs.back().filter);
        // The textures the enabled forms read, each bound by the pass.
        const std::vector<std::string> reads = pass.texture_names();
        for (const auto& [binding, text] : entry.textures) {
            const int line = entry.texture_lines.at(binding);
            const bool known = std::any_of(stages_.begin(), stages_.end(), [&](const StageSpec& s) {
                return std::any_of(s.forms.begin(), s.forms.end(), [&](const FormSpec& f) {
                    return std::find(f.textures.begin(), f.textures.end(), binding) != f.textures.end();
                });
            });
            if (!known) return make_error("no stage reads a texture '" + binding + "'", file, line, field + ".textures." + binding);
            if (std::find(reads.begin(), reads.end(), binding) == reads.end()) continue;  // its stage is off
            auto src = parse_source(text, file, line, field + ".textures." + binding);
            if (!src.ok()) return src.error();
            // LUTs are sampled as their own section says; anything else like the main input.
            PassInput input{binding, src.value(), Filter::Linear, Wrap::ClampToEdge, false, line};
            if (const LutSpec* lut = src.value().kind == TextureSource::Kind::Lut ? preset.find_lut(src.value().name) : nullptr) {
                input.filter = lut->filter;
                input.wrap = lut->wrap;
            }
            if (auto how = entry.texture_sampling.find(binding); how != entry.texture_sampling.end()) {
                input.filter = how->second.filter.value_or(input.filter);
                input.wrap = how->second.wrap.value_or(input.wrap);
                input.mipmap = how->second.mipmap.value_or(input.mipmap);
            }
            const auto how = entry.texture_sampling.find(binding);
            input.mip_filter = how != entry.texture_sampling.end() && how->second.mip_filter ? *how->second.mip_filter : input.filter;
            pass.inputs.push_back(std::move(input));
        }
        if (auto s = textures_bound(pass, file, entry.line, field + ".textures"); !s.ok()) return s.error();
        preset.passes.push_back(std::move(pass));
    }

    // The pass graph: what each input names must exist; this frame's outputs only flow forward.
    for (size_t index = 0; index < preset.passes.size(); ++index) {
        const Pass& pass = preset.passes[index];
        for (const PassInput& input : pass.inputs) {
            const std::string field = "pass." + pass.alias + (input.binding == "source" ? ".input" : ".textures." + input.binding);
            const int line = input.line ? input.line : pass.where.line;
            const TextureSource& src = input.from;
            if (src.kind == TextureSource::Kind::Lut && !preset.find_lut(src.name))
                return make_error("there is no [lut." + src.name + "]", file, line, field);
            if (src.kind == TextureSource::Kind::Lut)
                if (auto sized = lut_fits_forms(pass, input.binding, *preset.find_lut(src.name)); !sized.ok()) return sized.error();
            if (src.kind != TextureSource::Kind::Pass && src.kind != TextureSource::Kind::Feedback) continue;
            auto target = std::find_if(preset.passes.begin(), preset.passes.end(), [&](const Pass& p) { return p.alias == src.name; });
            if (target == preset.passes.end()) return make_error("there is no pass '" + src.name + "'", file, line, field);
            const size_t target_index = static_cast<size_t>(target - preset.passes.begin());
            if (src.kind == TextureSource::Kind::Pass && target_index >= index)
                return make_error(fmt::format("pass '{}' reads this frame's output of {}, which {}: a cycle; read the "
                                              "previous frame's with '{}@previous'",
                                              pass.alias, target_index == index ? "itself" : "pass '" + src.name + "'",
                                              target_index == index ? "it is still drawing" : "runs after it", src.name),
                                  file, line, field);
        }
    }
    // What the scene does not use does not exist: only passes the last one depends on (this frame
    // or, through feedback, the next) are kept.
    std::set<std::string> live{preset.passes.back().alias};
    for (bool grew = true; grew;) {
        grew = false;
        for (const Pass& pass : preset.passes) {
            if (!live.count(pass.alias)) continue;
            for (const PassInput& input : pass.inputs)
                if ((input.from.kind == TextureSource::Kind::Pass || input.from.kind == TextureSource::Kind::Feedback) &&
                    live.insert(input.from.name).second)
                    grew = true;
        }
    }
    preset.passes.erase(std::remove_if(preset.passes.begin(), preset.passes.end(), [&](const Pass& p) { return !live.count(p.alias); }),
                        preset.passes.end());
    preset.filter = preset.passes.front().inputs.front().filter;
    if (preset.scene.source_fit != SourceFit::Stretch && !preset.scene.source_width)
        return make_error("a source fit other than stretch needs the source's size ([source] size = [w, h])", leaf->where.file,
                          leaf->key_lines.count("source") ? leaf->key_lines.at("source") : 1, "source.fit");
    if (auto s = add_declared_tiers(stages_, preset, chain); !s.ok()) return s.error();
    visiting.erase(name);
    return preset;
}

}  // namespace crtforge
