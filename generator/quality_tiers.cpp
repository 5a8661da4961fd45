// Quality tiers: a preset's stages swapped between their point-sampled and filtered forms.
#include "crtforge/quality_tiers.hpp"

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

PresetTier with_tier(const Preset& preset, QualityTier tier) {
    PresetTier out{tier, preset, {}};
    for (Pass& pass : out.preset.passes) {
        for (ResolvedStage& rs : pass.stages) {
            if (!rs.stage || !rs.form) continue;
            const FormSpec* to = form_in_tier(*rs.stage, *rs.form, tier);
            if (!to || to == rs.form) continue;
            out.changes.push_back("pass " + pass.alias + ": " + rs.stage->name + " " + rs.form->name + " -> " + to->name);
            rs.form = to;
            if (!rs.stage->selector.empty()) rs.values[rs.stage->selector] = Value{to->name};
        }
    }
    return out;
}

}  // namespace

std::vector<PresetTier> preset_tiers(const Preset& preset) {
    PresetTier point = with_tier(preset, QualityTier::Point);
    PresetTier filtered = with_tier(preset, QualityTier::Filtered);
    if (point.changes.empty() && filtered.changes.empty()) return {std::move(point)};
    return {std::move(point), std::move(filtered)};
}

}  // namespace crtforge
