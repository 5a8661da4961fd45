// Presets: which stages are on, which form each uses, and param values. A preset may inherit from
// another (base = "classic") and override; templates/presets/<name>.toml.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "crtforge/spec.hpp"

namespace crtforge {

enum class Filter { Linear, Nearest };
const char* filter_name(Filter filter);

// A preset's own settings for one stage, as written in its file (before inheritance).
struct PresetStageEntry {
    std::string stage;
    bool enabled = true;
    int line = 0;
    std::map<std::string, Value> values;     // param name -> value (already type-checked)
    std::map<std::string, int> value_lines;  // param name -> line in the preset file
};

struct PresetFile {
    std::string name;
    std::string doc;
    std::string base;                      // empty: no inheritance
    std::optional<Filter> filter;          // source texture filter; inherited when unset
    std::vector<PresetStageEntry> stages;  // in file order
    SourceLocation where;
};

// A preset after inheritance: the enabled stages (in pass order) and every value they use.
struct ResolvedStage {
    const StageSpec* stage = nullptr;
    const FormSpec* form = nullptr;
    std::map<std::string, Value> values;   // every param the form reads, defaults filled in
};

struct Preset {
    std::string name;
    std::string doc;
    Filter filter = Filter::Linear;
    std::vector<ResolvedStage> stages;     // sorted by StageSpec::order
    std::vector<std::string> lineage;      // this preset, then its bases
    SourceLocation where;

    const ResolvedStage* find_stage(const std::string& name) const;
};

}  // namespace crtforge
