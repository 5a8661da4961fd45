// Quality tiers of a preset: the same scene with each stage in its point-sampled form or in its
// filtered form (FormSpec::quality_of), so speed can be weighed against aliasing (crtforge bench,
// crtforge generate --max-error).
#pragma once

#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/preset.hpp"

namespace crtforge {

enum class QualityTier { Point, Filtered };
const char* quality_tier_name(QualityTier tier);  // "point", "filtered"

struct PresetTier {
    QualityTier tier = QualityTier::Point;
    Preset preset;                     // the preset with its stages in the tier's forms
    std::vector<std::string> changes;  // e.g. "pass main: mask shadow -> shadow_filtered" (empty: as written)
    // "point", "filtered", or "filtered:<stage>" for a tier that filters that stage alone; a
    // declared tier's name, or "<name>+filtered" for it with every stage filtered.
    std::string name = "point";
    std::string declared;  // the [tiers.<name>] it starts from ("": the preset as written)
};

// The tiers a preset offers, by the work they do: first each tier the preset declares
// ([tiers.<name>]: a cheaper scene), point-sampled and, where the preset has filtered forms, as
// "<name>+filtered"; then "point" (every stage with a filtered form back to its point-sampled one);
// when two or more stages have filtered forms, "filtered:<stage>" for each of them alone, in pass
// order (the others point-sampled); then "filtered" (all of them); last each declared tier that
// supersamples a pass more than the preset does (more work), as the first ones. One entry when
// the preset declares no tier and no stage of it has a filtered form.
std::vector<PresetTier> preset_tiers(const Preset& preset);

// The point tier of preset_tiers()'s list (the preset as written, every stage point-sampled): the
// picture every tier is measured against. `tiers` is not empty.
const PresetTier& point_tier(const std::vector<PresetTier>& tiers);

// The tier of that name (as preset_tiers() names them); an unknown name is an error listing them,
// on field --tier.
Result<PresetTier> find_tier(const Preset& preset, const std::string& name);

}  // namespace crtforge
