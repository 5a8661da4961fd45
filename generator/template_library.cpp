// Loads the whole templates/ directory and cross-checks it (unique param names, pass order).
#include "crtforge/template_library.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "crtforge/files.hpp"
#include "crtforge/lut_file.hpp"
#include "crtforge/paths.hpp"
#include "generator/template_lint.hpp"
#include "generator/toml_reader.hpp"

namespace crtforge {


namespace {

// Names the generated code itself declares; a param may not shadow them.
const std::set<std::string>& reserved_names() {
    static const std::set<std::string> names = {
        "main", "source", "fragColor", "vTexCoord", "crt", "CrtParams", "CrtFrag", "color", "frag",
        "inside", "sampleUv", "outputSize", "sourceSize", "time", "frameCount", "viewportSize", "hostTime", "crt_warp", "crt_source_uv", "PI", "TAU"};
    return names;
}

}  // namespace

std::string TemplateLibrary::default_dir() {
    if (const char* env = std::getenv("CRTFORGE_TEMPLATES"); env && *env) return env;
    return data_path("templates");
}

const StageSpec* TemplateLibrary::find_stage(const std::string& name) const {
    for (const auto& s : stages_)
        if (s.name == name) return &s;
    return nullptr;
}

const Preset* TemplateLibrary::find_preset(const std::string& name) const {
    for (const auto& p : presets_)
        if (p.name == name) return &p;
    return nullptr;
}

std::vector<std::string> TemplateLibrary::preset_names() const {
    std::vector<std::string> names;
    for (const auto& p : presets_) names.push_back(p.name);
    return names;
}

Result<const Preset*> TemplateLibrary::lookup_preset(const std::string& name) const {
    if (const Preset* p = find_preset(name)) return p;
    if (auto broken = broken_.find(name); broken != broken_.end()) return broken->second;
    return make_error("unknown preset '" + name + "' (presets: " + join_list(preset_names()) + ")", {}, 0, "--preset");
}

const ParamSpec* TemplateLibrary::find_param(const std::string& name, const StageSpec** owner) const {
    for (const auto& s : stages_) {
        if (const ParamSpec* p = s.find_param(name)) {
            if (owner) *owner = &s;
            return p;
        }
    }
    return nullptr;
}

namespace {

// Paths in diagnostics and #line directives: relative to the working directory when the templates
// sit below it (short, readable), absolute otherwise.
std::string display_dir(const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path p(dir);
    if (!p.is_absolute()) return dir;
    fs::path rel = fs::relative(p, fs::current_path(ec), ec);
    if (ec || rel.empty() || *rel.begin() == "..") return dir;
    return rel.string();
}

// A template file must lie in its template folder: a link out of it (to /etc/passwd, say) would
// make any file on the machine part of a stage or preset, and its text part of an error message.
Status inside_folder(const std::string& path, const std::string& folder) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path file = fs::weakly_canonical(path, ec);
    const fs::path root = fs::weakly_canonical(folder, ec);
    if (ec) return make_error("cannot resolve: " + ec.message(), path);
    const fs::path rel = file.lexically_relative(root);
    if (rel.empty() || *rel.begin() == "..")
        return make_error("leads out of the template folder " + folder + " (to " + file.string() + ")", path);
    return Ok{};
}

}  // namespace

namespace {

// The files of one kind across the layers, by file stem: a later layer's file replaces an earlier
// one of the same name. Sorted by stem, like one folder's listing. A layer may lack the folder.
Result<std::vector<std::string>> layered_files(const std::vector<std::string>& layers, const std::string& sub, const std::string& ext) {
    std::map<std::string, std::string> by_stem;
    for (const std::string& layer : layers) {
        std::error_code ec;
        if (!std::filesystem::is_directory(layer + "/" + sub, ec)) continue;
        auto files = list_files(layer + "/" + sub, ext);
        if (!files.ok()) return files.error();
        for (const std::string& f : files.value()) {
            if (auto inside = inside_folder(f, layer); !inside.ok()) return inside.error();
            by_stem[file_stem(f)] = f;
        }
    }
    std::vector<std::string> out;
    for (const auto& [stem, path] : by_stem) out.push_back(path);
    return out;
}

}  // namespace

Result<std::shared_ptr<TemplateLibrary>> TemplateLibrary::load(const std::string& dir_arg) {
    const std::string dir = display_dir(dir_arg);
    auto lib = std::make_shared<TemplateLibrary>();
    lib->dir_ = dir;

    // A folder with its own prelude.glsl is a whole template set; one without is an overlay: its
    // stages/ and presets/ go on top of the shipped templates, replacing files of the same name.
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) return make_error("is not a template folder", dir, 0, "--templates");
    std::vector<std::string> layers{dir};
    if (!std::filesystem::exists(dir + "/prelude.glsl", ec)) {
        const std::string shipped = display_dir(default_dir());
        if (std::filesystem::equivalent(shipped, dir, ec))
            return make_error("the shipped templates lack prelude.glsl", dir);
        if (!std::filesystem::is_directory(dir + "/stages", ec) && !std::filesystem::is_directory(dir + "/presets", ec))
            return make_error("has neither prelude.glsl (a whole template set) nor stages/ or presets/ (an overlay on the shipped "
                              "templates)",
                              dir, 0, "--templates");
        layers.insert(layers.begin(), shipped);
        lib->overlay_ = true;
    }

    lib->prelude_path_ = layers.front() + "/prelude.glsl";
    auto prelude = read_text_file(lib->prelude_path_, detail::kMaxTomlBytes);
    if (!prelude.ok()) return prelude.error();
    lib->prelude_ = prelude.value();
    lib->vertex_path_ = layers.front() + "/fullscreen.vert";
    auto vertex = read_text_file(lib->vertex_path_, detail::kMaxTomlBytes);
    if (!vertex.ok()) return vertex.error();
    lib->vertex_ = vertex.value();

    auto spec_files = layered_files(layers, "stages", ".toml");
    if (!spec_files.ok()) return spec_files.error();
    if (spec_files.value().empty()) return make_error("no stage specs (*.toml) found", dir + "/stages");
    std::map<std::string, std::string> param_owner;  // param -> "file:line" of first declaration
    for (const auto& path : spec_files.value()) {
        auto text = read_text_file(path, detail::kMaxTomlBytes);
        if (!text.ok()) return text.error();
        auto spec = parse_stage_spec(text.value(), path);
        if (!spec.ok()) return spec.error();
        StageSpec& s = spec.value();
        if (s.name != file_stem(path))
            return make_error("stage name '" + s.name + "' must match the file name '" + file_stem(path) + "'", path, 1, "name");
        for (const auto& other : lib->stages_)
            if (!s.program && !other.program && other.order == s.order)
                return make_error("order " + std::to_string(s.order) + " is already used by stage '" + other.name +
                                  "' (the pass order must be unambiguous)", path, 1, "order");
        for (const auto& p : s.params) {
            if (reserved_names().count(p.name))
                return make_error("'" + p.name + "' is reserved by the generated code", path, p.where.line, "param." + p.name);
            if (s.program) continue;  // a program's params are its own: it never shares a shader
            auto [it, fresh] = param_owner.emplace(p.name, p.where.file + ":" + std::to_string(p.where.line));
            if (!fresh)
                return make_error("param names are global (they become uniform names); already declared at " + it->second,
                                  path, p.where.line, "param." + p.name);
        }
        if (s.program) {  // its forms carry their own files
            lib->stages_.push_back(std::move(s));
            continue;
        }
        s.glsl_path = std::filesystem::path(path).parent_path().string() + "/" + s.name + ".glsl";
        if (auto inside = inside_folder(s.glsl_path, std::filesystem::path(path).parent_path().parent_path().string()); !inside.ok())
            return inside.error();
        auto glsl = read_text_file(s.glsl_path, detail::kMaxTomlBytes);
        if (!glsl.ok()) return glsl.error();
        s.glsl_source = glsl.value();
        if (auto lint = detail::lint_stage_source(s); !lint.ok()) return lint.error();
        for (const auto& f : s.forms)
            for (const auto& fn : f.functions)
                if (!fn.empty() && s.glsl_source.find(fn) == std::string::npos)
                    return make_error("function '" + fn + "' is not defined in " + s.glsl_path, path, f.where.line, "form." + f.name);
        lib->stages_.push_back(std::move(s));
    }
    std::sort(lib->stages_.begin(), lib->stages_.end(),
              [](const StageSpec& a, const StageSpec& b) { return a.order != b.order ? a.order < b.order : a.name < b.name; });

    auto preset_files = layered_files(layers, "presets", ".toml");
    if (!preset_files.ok()) return preset_files.error();
    if (auto s = lib->add_preset_files(preset_files.value(), false); !s.ok()) return s.error();
    return lib;
}

Status TemplateLibrary::add_presets(const std::string& dir, bool test_only) {
    auto preset_files = list_files(dir, ".toml");
    if (!preset_files.ok()) return preset_files.error();
    return add_preset_files(preset_files.value(), test_only);
}

namespace {

// The folder a preset's LUT files must lie in: the template folder above its presets/ folder (or
// the folder that holds it, for presets added from elsewhere).
std::string template_root_of(const std::string& preset_path) {
    const std::filesystem::path folder = std::filesystem::path(preset_path).parent_path();
    return (folder.filename() == "presets" ? folder.parent_path() : folder).string();
}

}  // namespace

Result<PresetFile> TemplateLibrary::load_preset_file(const std::string& path, const std::string& template_root) const {
    auto text = read_text_file(path, detail::kMaxTomlBytes);
    if (!text.ok()) return text.error();
    auto file = parse_preset_file(text.value(), path, this);
    if (!file.ok()) return file.error();
    if (file.value().name != file_stem(path))
        return make_error("preset name '" + file.value().name + "' must match the file name '" + file_stem(path) + "'", path, 1, "name");
    for (LutSpec& lut : file.value().luts) {
        if (lut.file.empty()) continue;
        auto bytes = read_lut_file(lut, template_root);
        if (!bytes.ok()) return bytes.error();
        lut.bytes = std::make_shared<const std::string>(std::move(bytes.value()));
    }
    return file;
}

Status TemplateLibrary::add_preset_files(const std::vector<std::string>& paths, bool test_only) {
    std::vector<PresetFile> files;
    auto refuse = [&](const std::string& name, Diagnostic error) -> Status {
        if (test_only) return error;
        broken_.emplace(name, std::move(error));
        return Ok{};
    };
    for (const auto& path : paths) {
        auto file = load_preset_file(path, template_root_of(path));
        if (!file.ok()) {
            if (auto s = refuse(file_stem(path), file.error()); !s.ok()) return s;
            continue;
        }
        if (find_preset(file.value().name) || broken_.count(file.value().name)) {
            auto s = refuse(file.value().name, make_error("preset '" + file.value().name + "' already exists in the library", path, 1, "name"));
            if (!s.ok()) return s;
            continue;
        }
        for (const std::string& w : file.value().warnings) warnings_.push_back(w);
        files.push_back(std::move(file.value()));
    }
    std::vector<Preset> added;
    for (const auto& f : files) {
        auto preset = resolve(files, f.name);
        if (!preset.ok()) {
            if (auto s = refuse(f.name, preset.error()); !s.ok()) return s;
            continue;
        }
        preset.value().test_only = test_only;
        added.push_back(std::move(preset.value()));
    }
    adopt(std::move(added));
    return Ok{};
}

void TemplateLibrary::adopt(std::vector<Preset> added) {
    for (Preset& p : added) presets_.push_back(std::move(p));
    std::sort(presets_.begin(), presets_.end(), [](const Preset& a, const Preset& b) { return a.name < b.name; });
}

Status TemplateLibrary::add_tier_presets() {
    std::vector<Preset> added;
    for (const Preset& p : presets_) {
        if (p.test_only) continue;
        for (const DeclaredTier& tier : p.tiers) {
            if (!tier.preset) continue;
            Preset t = *tier.preset;
            t.name = p.name + "-tier-" + tier.name;
            t.doc = "Declared tier '" + tier.name + "' of " + p.name + ": " + tier.doc;
            t.test_only = true;
            t.tier_of = p.name;
            if (find_preset(t.name)) return make_error("preset '" + t.name + "' clashes with the name of " + p.name + "'s tier '" + tier.name + "'", tier.where.file, tier.where.line);
            added.push_back(std::move(t));
        }
    }
    adopt(std::move(added));
    return Ok{};
}

Status TemplateLibrary::add_test_presets(const std::string& dir) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) return Ok{};
    return add_presets(dir, true);
}

}  // namespace crtforge
