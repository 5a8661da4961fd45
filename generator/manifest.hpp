// manifest.json: for each preset and target, the files, the uniform layout (from SPIR-V
// reflection) and the baked values — enough for a host to bind and fill everything.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "crtforge/exporter.hpp"

namespace crtforge::detail {

struct ManifestTargetEntry {
    TargetId target;
    std::map<std::string, std::string> files;  // "vertex"/"fragment" -> relative path
    std::vector<std::pair<std::string, std::string>> bindings;
    std::string extra_json;  // TargetOutput::manifest_json
};

nlohmann::ordered_json value_to_json(const Value& value);

// The speed a pass's time is reduced by (shader_time()), as hosts read it: the uniform's name
// when the speed is a uniform, the baked number otherwise; null when the pass has none.
nlohmann::ordered_json time_reduce_by(const Variant& variant);

// The preset-level part: scene, LUTs, and per pass its stages, baked values, uniform block and
// textures (the caller adds each pass's "targets").
nlohmann::ordered_json preset_manifest(const Preset& preset, const std::vector<CompiledVariant>& passes);

nlohmann::ordered_json target_manifest(const ManifestTargetEntry& entry);

}  // namespace crtforge::detail
