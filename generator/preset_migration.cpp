#include "generator/preset_migration.hpp"

#include <algorithm>
#include <cctype>

namespace crtforge::detail {

namespace {

// Glitch's own effects, which the document leaves with Glitch ("Glitch keeps: ...").
constexpr const char* kGlitchKeeps[] = {"analog", "digital", "vhs", "datamosh", "row", "column", "diagonal",
                                        "block", "temporal", "jitter"};

bool glitch_keeps(const std::string& key) {
    std::string lower = key;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const char* prefix : kGlitchKeeps)
        if (lower.rfind(prefix, 0) == 0) return true;
    return false;
}

std::string warning(const TomlReader& r, const toml::node* node, const std::string& field, const std::string& message) {
    return make_error(message, r.path(), node ? r.line_of(*node) : 0, field).warning();
}

// A stage entry set from the legacy keys; values are checked against the stage's spec (range,
// type) and keep the legacy key's line, so an out-of-range value is reported where it is written.
struct EntryBuilder {
    const TomlReader& r;
    const TemplateLibrary* library;
    PresetStageEntry entry;

    Status set(const std::string& param, const toml::node& node, const std::string& legacy_field) {
        const StageSpec* stage = library ? library->find_stage(entry.stage) : nullptr;
        const ParamSpec* spec = stage ? stage->find_param(param) : nullptr;
        if (!spec) return r.error(&node, legacy_field, "migrates to " + entry.stage + "." + param + ", which these templates do not have");
        auto v = r.param_value(node, *spec, legacy_field);
        if (!v.ok()) return v.error();
        entry.values[param] = v.value();
        entry.value_lines[param] = r.line_of(node);
        return Ok{};
    }
    void set_value(const std::string& param, Value value, int line) {
        entry.values[param] = std::move(value);
        entry.value_lines[param] = line;
    }
};

}  // namespace

Result<int> preset_format(const TomlReader& r, const toml::table& root) {
    auto format = r.integer(root, "format", "");
    if (!format.ok()) return format.error();
    if (format.value()) {
        const int64_t v = *format.value();
        if (v < 1 || v > kPresetFormat)
            return r.error(root.get("format"), "format",
                           "format " + std::to_string(v) + " is not one this crtforge reads (1 = Glitch's [glitch] table, " +
                               std::to_string(kPresetFormat) + " = current)");
        return static_cast<int>(v);
    }
    return root.get("glitch") ? 1 : kPresetFormat;
}

Status migrate_glitch_preset(const TomlReader& r, const toml::table& root, const TemplateLibrary* library, PresetFile& file) {
    for (const char* key : {"stages", "pass", "passes", "source", "display", "time", "lut"})
        if (root.get(key))
            return r.error(root.get(key), key, "a format-1 (Glitch) preset has only name, doc, base and [glitch]; "
                                                "write format = 2 to use the current layout");
    const toml::node* node = root.get("glitch");
    const toml::table* glitch = node ? node->as_table() : nullptr;
    if (!glitch) return r.error(node ? node : &root, "glitch", "a format-1 (Glitch) preset needs a [glitch] table");

    auto crt = r.boolean(*glitch, "crtEnabled", "glitch");
    if (!crt.ok()) return crt.error();
    auto vignette = r.boolean(*glitch, "vignetteEnabled", "glitch");
    if (!vignette.ok()) return vignette.error();
    auto overlay = r.string(*glitch, "overlayMode", "glitch", false);
    if (!overlay.ok()) return overlay.error();
    const bool scanlines = overlay.value() == "scanlines";

    const int line = r.line_of(*node);
    EntryBuilder curvature{r, library, {}}, vignettes{r, library, {}}, scan{r, library, {}};
    curvature.entry = {"curvature", crt.value().value_or(false), line, {}, {}};
    vignettes.entry = {"vignette", vignette.value().value_or(false), line, {}, {}};
    scan.entry = {"scanlines", scanlines, line, {}, {}};
    if (curvature.entry.enabled) curvature.set_value("curvatureForm", std::string("crt_effect"), line);
    if (vignettes.entry.enabled) vignettes.set_value("vignetteForm", std::string("crt_effect"), line);
    if (scan.entry.enabled) scan.set_value("scanlineForm", std::string("crt_effect"), line);

    // Each key in file order: migrated (with a warning), left with Glitch (a warning), or a typo (an error).
    std::vector<std::pair<std::string, const toml::node*>> keys;
    for (const auto& [key, value] : *glitch) keys.emplace_back(std::string(key.str()), &value);
    std::sort(keys.begin(), keys.end(), [&](const auto& a, const auto& b) { return r.line_of(*a.second) < r.line_of(*b.second); });
    for (const auto& [key, value] : keys) {
        const std::string field = "glitch." + key;
        std::string to;
        if (key == "crtEnabled") {
            to = "stages.curvature " + std::string(curvature.entry.enabled ? "on (crt_effect form)" : "off");
        } else if (key == "curvature") {
            if (!curvature.entry.enabled) {
                file.warnings.push_back(warning(r, value, field, "Glitch key ignored: crtEnabled is not true, so there is no barrel"));
                continue;
            }
            if (auto s = curvature.set("curvature", *value, field); !s.ok()) return s.error();
            to = "stages.curvature.curvature";
        } else if (key == "vignetteEnabled") {
            to = "stages.vignette " + std::string(vignettes.entry.enabled ? "on (crt_effect form, the document's exponent)" : "off");
        } else if (key == "overlayMode") {
            if (!scanlines) {
                file.warnings.push_back(warning(r, value, field, "overlay mode '" + overlay.value() +
                                                                     "' stays with Glitch (only its scanlines are CRT): ignored"));
                continue;
            }
            to = "stages.scanlines on (crt_effect form)";
        } else if (key == "overlayIntensity" || key == "overlaySpacing") {
            if (!scanlines) {
                file.warnings.push_back(warning(r, value, field, "Glitch key ignored: overlayMode is not \"scanlines\""));
                continue;
            }
            const std::string param = key == "overlayIntensity" ? "scanlineIntensity" : "scanlineSpacing";
            if (auto s = scan.set(param, *value, field); !s.ok()) return s.error();
            to = "stages.scanlines." + param;
        } else if (glitch_keeps(key)) {
            file.warnings.push_back(warning(r, value, field, "a Glitch effect that stays with Glitch (crtforge has no Glitch): ignored"));
            continue;
        } else {
            return r.error(value, field, "not a Glitch key (migrated: crtEnabled, curvature, vignetteEnabled, overlayMode, "
                                         "overlayIntensity, overlaySpacing)");
        }
        file.warnings.push_back(warning(r, value, field, "Glitch (format 1) key migrated to " + to + "; write format = 2 presets to silence this"));
    }

    if (file.base.empty()) file.base = "crt-shadow-mask";  // the CRT effect's own defaults
    for (EntryBuilder* b : {&curvature, &scan})
        file.stages.push_back(std::move(b->entry));
    // Glitch had no phosphor mask: the migrated look has none either.
    file.stages.push_back({"mask", false, line, {}, {}});
    file.stages.push_back(std::move(vignettes.entry));
    return Ok{};
}

}  // namespace crtforge::detail
