// Quality tiers: a preset's stages swapped between their point-sampled and filtered forms.
#include "crtforge/quality_tiers.hpp"

#include <algorithm>

namespace crtforge {

const char* quality_tier_name(QualityTier tier) { return tier == QualityTier::Point ? "point" : "filtered"; }

namespace {

// The form of `stage` that stands for `form` in `tier`: its filtered tier, or the point form a
// filtered one refines; `form` itself when the stage has no such counterpart.
const FormSpec* form_in_tier(const StageSpec& stage, const FormSpec& form, QualityTier tier) {
    if (tier == QualityTier::Point) return form.quality_of.empty() ? &form : stage.find_form(form.quality_of);
    if (!form.quality_of.empty()) return &form;
    for (const FormSpec& f : stage.forms)
        if (f.quality_of == form.name) return &f;
    return &form;
}

// The preset with each stage in its `tier` form; `only`: the stage filtered alone (the others
// point-sampled), empty for every stage.
PresetTier with_tier(const Preset& preset, QualityTier tier, const std::string& only = {}) {
    PresetTier out{tier, preset, {}, only.empty() ? quality_tier_name(tier) : std::string("filtered:") + only, ""};
    for (Pass& pass : out.preset.passes) {
        for (ResolvedStage& rs : pass.stages) {
            if (!rs.stage || !rs.form) continue;
            const QualityTier here = only.empty() || rs.stage->name == only ? tier : QualityTier::Point;
            const FormSpec* to = form_in_tier(*rs.stage, *rs.form, here);
            if (!to || to == rs.form) continue;
            out.changes.push_back("pass " + pass.alias + ": " + rs.stage->name + " " + rs.form->name + " -> " + to->name);
            rs.form = to;
            if (!rs.stage->selector.empty()) rs.values[rs.stage->selector] = Value{to->name};
        }
    }
    return out;
}

// The stages of the preset that have a filtered counterpart (or are a filtered form), in pass order.
std::vector<std::string> filterable_stages(const Preset& preset) {
    std::vector<std::string> names;
    for (const Pass& pass : preset.passes)
        for (const ResolvedStage& rs : pass.stages) {
            if (!rs.stage || !rs.form) continue;
            const bool has = form_in_tier(*rs.stage, *rs.form, QualityTier::Filtered) != form_in_tier(*rs.stage, *rs.form, QualityTier::Point);
            if (has && std::find(names.begin(), names.end(), rs.stage->name) == names.end()) names.push_back(rs.stage->name);
        }
    return names;
}

// Whether `tier` averages more samples in some pass than `preset` does.
bool supersamples_more(const Preset& preset, const Preset& tier) {
    for (const Pass& t : tier.passes)
        if (const auto p = std::find_if(preset.passes.begin(), preset.passes.end(), [&](const Pass& p) { return p.alias == t.alias; });
            p != preset.passes.end() && t.supersample > p->supersample)
            return true;
    return false;
}

}  // namespace

std::vector<PresetTier> preset_tiers(const Preset& preset) {
    PresetTier point = with_tier(preset, QualityTier::Point);
    PresetTier filtered = with_tier(preset, QualityTier::Filtered);
    const bool filterable = !point.changes.empty() || !filtered.changes.empty();
    if (!filterable && preset.tiers.empty()) return {std::move(point)};
    // By the work they do: the declared tiers that make a cheaper scene, point-sampled, filtered,
    // then the declared tiers that do more (a pass supersampled).
    std::vector<PresetTier> tiers, more;
    for (const DeclaredTier& declared : preset.tiers)
        for (const QualityTier q : {QualityTier::Point, QualityTier::Filtered}) {
            if (q == QualityTier::Filtered && !filterable) continue;
            // Point: the declared scene as written (its own forms stand); filtered: every stage filtered.
            PresetTier t = q == QualityTier::Point ? PresetTier{q, *declared.preset, {}, declared.name, ""} : with_tier(*declared.preset, q);
            t.name = q == QualityTier::Point ? declared.name : declared.name + "+filtered";
            t.changes.insert(t.changes.begin(), declared.changes.begin(), declared.changes.end());
            t.declared = declared.name;
            (supersamples_more(preset, *declared.preset) ? more : tiers).push_back(std::move(t));
        }
    tiers.push_back(std::move(point));
    if (filterable) {
        const std::vector<std::string> stages = filterable_stages(preset);
        if (stages.size() > 1)
            for (const std::string& stage : stages) tiers.push_back(with_tier(preset, QualityTier::Filtered, stage));
        tiers.push_back(std::move(filtered));
    }
    for (PresetTier& t : more) tiers.push_back(std::move(t));
    return tiers;
}

const PresetTier& point_tier(const std::vector<PresetTier>& tiers) {
    auto point = std::find_if(tiers.begin(), tiers.end(), [](const PresetTier& t) { return t.name == "point"; });
    return point != tiers.end() ? *point : tiers.front();
}

Result<PresetTier> find_tier(const Preset& preset, const std::string& name) {
    std::vector<PresetTier> tiers = preset_tiers(preset);
    std::string names;
    for (PresetTier& t : tiers) {
        if (t.name == name) return std::move(t);
        names += (names.empty() ? "" : ", ") + t.name;
    }
    return make_error("preset '" + preset.name + "' has no tier '" + name + "' (its tiers: " + names + ")", {}, 0, "--tier");
}

}  // namespace crtforge
