// Quality tiers of a preset: the same scene with each stage in its point-sampled form or in its
// filtered form (FormSpec::quality_of), so speed can be weighed against aliasing (crtforge bench,
// crtforge generate --max-error).
#pragma once

#include <string>
#include <vector>

#include "crtforge/preset.hpp"

namespace crtforge {

enum class QualityTier { Point, Filtered };
const char* quality_tier_name(QualityTier tier);  // "point", "filtered"

struct PresetTier {
    QualityTier tier = QualityTier::Point;
    Preset preset;                     // the preset with every stage that has the tier in it
    std::vector<std::string> changes;  // e.g. "pass main: mask shadow -> shadow_filtered" (empty: as written)
};

// The tiers a preset offers, cheapest first: "point" (every stage with a filtered form back to its
// point-sampled one) then "filtered" (every stage with a filtered form in it). One entry when no
// stage of the preset has a filtered form.
std::vector<PresetTier> preset_tiers(const Preset& preset);

}  // namespace crtforge
