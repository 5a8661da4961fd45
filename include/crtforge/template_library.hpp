// The template library: every stage spec, the shared GLSL (prelude, full-screen vertex shader) and
// every preset, loaded and validated from one templates/ directory.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/preset.hpp"
#include "crtforge/spec.hpp"

namespace crtforge {

class TemplateLibrary {
public:
    // Loads <dir>/stages/*.toml (+ .glsl), <dir>/prelude.glsl, <dir>/fullscreen.vert and
    // <dir>/presets/*.toml. An invalid stage or shared file fails the whole load with its first
    // diagnostic; an invalid preset file is one broken preset (broken_presets()), and so is every
    // preset derived from it, while the others load.
    // A folder without prelude.glsl is an overlay: its stages/ and presets/ (either may be absent)
    // go on top of the shipped templates (default_dir()), a file replacing the shipped one of the
    // same name: a studio keeps only its own stages and presets.
    static Result<std::shared_ptr<TemplateLibrary>> load(const std::string& dir);

    // The directory compiled into the binary (the source tree's templates/), overridable with
    // the CRTFORGE_TEMPLATES environment variable.
    static std::string default_dir();

    const std::vector<StageSpec>& stages() const { return stages_; }
    const std::vector<Preset>& presets() const { return presets_; }  // sorted by name
    const StageSpec* find_stage(const std::string& name) const;
    const Preset* find_preset(const std::string& name) const;
    // The same, or the preset's own load error when it is broken, or an error (field --preset)
    // that lists the presets there are.
    Result<const Preset*> lookup_preset(const std::string& name) const;
    // The presets that did not load, by name (a file's stem), each with its first diagnostic.
    // Commands over every preset refuse to run while one is broken; commands naming others run.
    const std::map<std::string, Diagnostic>& broken_presets() const { return broken_; }
    std::vector<std::string> preset_names() const;
    const ParamSpec* find_param(const std::string& name, const StageSpec** owner = nullptr) const;

    const std::string& prelude_source() const { return prelude_; }
    const std::string& prelude_path() const { return prelude_path_; }
    const std::string& vertex_source() const { return vertex_; }
    const std::string& vertex_path() const { return vertex_path_; }
    const std::string& dir() const { return dir_; }
    bool overlay() const { return overlay_; }  // dir() went on top of the shipped templates
    // What loading noticed but did not refuse, one line each ("file:line: warning: field 'x': ..."):
    // keys of legacy (format-1, Glitch) presets migrated to the current params.
    const std::vector<std::string>& warnings() const { return warnings_; }

    // Resolves a preset file (inheritance, defaults, validation) against this library. Public so
    // tools and tests can resolve presets that are not in the library's presets/ folder.
    Result<Preset> resolve(const std::vector<PresetFile>& files, const std::string& name) const;

    // Adds the presets of <dir>/*.toml (if the folder exists) as test presets (Preset::test_only):
    // configurations only validation renders, such as the stage-isolation presets of
    // golden/stages/. `export`, `list` and `bench` of "all presets" leave them out. Call it before
    // the library is used: it re-sorts presets(), so earlier Preset pointers dangle.
    Status add_test_presets(const std::string& dir);
    // Adds every declared tier of the shipped presets ([tiers.<name>]) as a test preset named
    // "<preset>-tier-<name>" (Preset::tier_of names its preset), so validation renders the tiers
    // a preset's author offers like any preset. Same caveat as add_test_presets.
    Status add_tier_presets();

private:
    Status add_presets(const std::string& dir, bool test_only);
    // Appends presets and keeps presets() sorted by name.
    void adopt(std::vector<Preset> added);
    // Test presets (shipped with the golden plan) must all load; the library's own may break one
    // by one (broken_).
    Status add_preset_files(const std::vector<std::string>& paths, bool test_only);
    // One preset file read, parsed and its LUT files checked (inside `template_root`).
    Result<PresetFile> load_preset_file(const std::string& path, const std::string& template_root) const;
    // resolve(), tracking the presets being resolved (`preset = "..."` references nest).
    Result<Preset> resolve_preset(const std::vector<PresetFile>& files, const std::string& name,
                                  std::set<std::string>& visiting) const;

    std::string dir_;
    std::vector<StageSpec> stages_;  // sorted by order
    std::vector<Preset> presets_;
    std::map<std::string, Diagnostic> broken_;
    std::string prelude_, prelude_path_, vertex_, vertex_path_;
    std::vector<std::string> warnings_;
    bool overlay_ = false;
};

// Parsers for one file's text; `path` is used in diagnostics only.
Result<StageSpec> parse_stage_spec(const std::string& text, const std::string& path);
Result<PresetFile> parse_preset_file(const std::string& text, const std::string& path,
                                     const TemplateLibrary* library_for_types);

}  // namespace crtforge
