// A RetroArch preset as a crtforge overlay: the program stage, the pass programs, the scene, the
// LUT images. docs/retroarch.md is the mapping this writes.
#include "crtforge/slang_import.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <filesystem>
#include <map>
#include <set>

#include <fmt/format.h>

#include "crtforge/cache.hpp"
#include "crtforge/files.hpp"
#include "crtforge/inert_text.hpp"
#include "crtforge/lut_file.hpp"
#include "generator/reserved_words.hpp"
#include "generator/retroarch/slang_program.hpp"
#include "generator/retroarch/slangp_file.hpp"
#include "generator/toml_reader.hpp"

namespace crtforge {

namespace fs = std::filesystem;
using retroarch::SlangParameter;
using retroarch::SlangpPass;
using retroarch::SlangSource;

namespace {

// A TOML basic string.
std::string toml_string(const std::string& text) {
    std::string out = "\"";
    for (unsigned char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        if (c < 0x20 || c == 0x7f) out += fmt::format("\\u{:04X}", c);
        else out += static_cast<char>(c);
    }
    return out + "\"";
}

// A TOML array of strings.
std::string toml_strings(const std::vector<std::string>& items) {
    std::vector<std::string> quoted;
    for (const std::string& item : items) quoted.push_back(toml_string(item));
    return "[" + join_list(quoted) + "]";
}

// A TOML float that reads back as the same double.
std::string toml_float(double v) {
    std::string text = fmt::format("{}", v);
    if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
    return text;
}

// One line of plain text for a doc (inert_comment: no control characters, line separators or
// backslashes), `fallback` when nothing is left.
std::string doc_line(const std::string& text, const std::string& fallback) {
    std::string line = inert_comment(text);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    while (!line.empty() && line.front() == ' ') line.erase(line.begin());
    return line.empty() ? fallback : line;
}

std::string identifier_from(const std::string& text) {
    std::string out;
    // GLSL reserves names with "__": runs of '_' become one.
    for (char c : text) {
        const char k = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
        if (k != '_' || out.empty() || out.back() != '_') out += k;
    }
    while (out.size() > 1 && out.back() == '_') out.pop_back();
    if (out.empty() || std::isdigit(static_cast<unsigned char>(out.front()))) out = "_" + out;
    return out;
}

// `name` cut to `longest` characters where it is longer: its start, then `joiner` and 8 hex digits
// of the whole's Cache::key, so two long names that share a start stay apart.
std::string shortened(std::string name, size_t longest, char joiner) {
    if (name.size() <= longest) return name;
    const std::string hash = Cache::key({name}).substr(0, 8);
    name.resize(longest - 9);
    while (!name.empty() && (name.back() == '_' || name.back() == '-')) name.pop_back();
    return name + joiner + hash;
}

// "ra_" + the preset's name as an identifier, short enough that its pass selector (<stage>_pass)
// is still a name crtforge takes (64 characters).
std::string stage_name_for(const std::string& preset_name) {
    std::string id = identifier_from(preset_name);
    id.erase(0, id.find_first_not_of('_'));  // "ra_" + a name that starts with a digit: no "__"
    return shortened("ra_" + id, detail::kMaxIdentifierLength - std::char_traits<char>::length("_pass"), '_');
}

std::string relative_to(const std::string& path, const std::string& base) {
    std::error_code ec;
    const fs::path rel = fs::relative(path, base, ec);
    return ec || rel.empty() ? path : rel.generic_string();
}

const char* wrap_of(const std::optional<std::string>& mode) { return mode ? mode->c_str() : "clamp_to_border"; }

// RetroArch's framebuffer formats onto crtforge's: exact where crtforge has the format, else the
// nearest with a warning.
std::pair<const char*, bool> pixel_format(const SlangpPass& pass, const std::string& pragma) {
    if (pass.float_framebuffer.value_or(false)) return {"rgba16f", true};
    if (pass.srgb_framebuffer.value_or(false)) return {"rgba8_srgb", true};
    if (pragma.empty() || pragma == "R8G8B8A8_UNORM") return {"rgba8", true};
    if (pragma == "R8G8B8A8_SRGB") return {"rgba8_srgb", true};
    if (pragma == "R16G16B16A16_SFLOAT") return {"rgba16f", true};
    if (pragma == "R32G32B32A32_SFLOAT") return {"rgba32f", true};
    if (pragma == "A2B10G10R10_UNORM_PACK32") return {"rgb10a2", true};
    if (pragma == "R16_SFLOAT") return {"r16f", true};
    if (pragma == "R16G16_SFLOAT") return {"rg16f", true};
    if (pragma.find("FLOAT") != std::string::npos) return {"rgba32f", false};
    return {"rgba8", false};
}

struct PassPlan {
    std::string alias;        // crtforge's
    const SlangSource* source = nullptr;
    retroarch::TranslatedProgram program;
};

class Importer {
public:
    Importer(const retroarch::SlangpPreset& preset, const SlangImportOptions& options) : preset_(preset), options_(options) {}

    Result<ImportedPreset> run(const std::string& path) {
        out_.name = options_.name.empty() ? imported_preset_name(path) : options_.name;
        out_.stage = stage_name_for(out_.name);
        out_.passes = preset_.passes.size();
        out_.inputs = preset_.files;
        for (const Diagnostic& w : preset_.warnings) out_.warnings.push_back(w.warning());
        if (auto s = check_scales(); !s.ok()) return s.error();
        if (auto s = load_sources(); !s.ok()) return s.error();
        if (auto s = collect_params(); !s.ok()) return s.error();
        name_passes();
        for (size_t i = 0; i < passes_.size(); ++i) {
            const std::map<std::string, std::string> textures = textures_before(i);
            const retroarch::ProgramContext context{textures, param_names_, options_.fps, i + 1 == passes_.size()};
            auto program = retroarch::translate_program(*passes_[i].source, context);
            if (!program.ok()) return program.error();
            passes_[i].program = std::move(program.value());
        }
        if (auto s = write_luts(); !s.ok()) return s.error();
        write_stage();
        write_preset();
        return std::move(out_);
    }

private:
    // A corpus path as generated files show it: relative to --root (or the working folder).
    std::string shown_path(const std::string& path) const { return relative_to(path, options_.root.empty() ? "." : options_.root); }

    Status load_sources() {
        for (const SlangpPass& pass : preset_.passes) {
            if (!sources_.count(pass.shader)) {
                auto source = retroarch::load_slang_source(pass.shader, options_.root);
                if (!source.ok()) return source.error();
                for (const std::string& f : source.value().files) out_.inputs.push_back(f);
                sources_.emplace(pass.shader, std::move(source.value()));
            }
            passes_.push_back({"", &sources_.at(pass.shader), {}});
        }
        return Ok{};
    }

    // One namespace for the whole preset: an id declared by several passes is one value, and must
    // be declared alike.
    Status collect_params() {
        std::set<std::string> used_names;
        for (const PassPlan& pass : passes_)
            for (const SlangParameter& p : pass.source->parameters) {
                auto [it, fresh] = params_.emplace(p.id, p);
                if (!fresh) {
                    const SlangParameter& first = it->second;
                    if (static_cast<float>(first.initial) != static_cast<float>(p.initial) ||
                        static_cast<float>(first.minimum) != static_cast<float>(p.minimum) ||
                        static_cast<float>(first.maximum) != static_cast<float>(p.maximum))
                        return make_error(fmt::format("parameter '{}' is declared again with other values (first at {}:{})", p.id,
                                                      first.where.file, first.where.line),
                                          p.where.file, p.where.line, "pragma parameter");
                    continue;
                }
                // A name no target reserves and crtforge's own code does not use.
                std::string name = detail::is_identifier(p.id) ? p.id : identifier_from(p.id);
                if (!detail::reserving_language(name).empty() || name.rfind("crtStage_", 0) == 0 || name == out_.stage + "_pass" ||
                    reserved_by_program(name))
                    name = "ra_" + name;
                while (used_names.count(name)) name += "_";
                used_names.insert(name);
                param_names_[p.id] = name;
            }
        for (const auto& [id, at] : preset_.empty_values)
            if (params_.count(id))
                return make_error(fmt::format("the shader parameter '{}' is given an empty value (give a number, or leave the line out)", id),
                                  at.file, at.line, id);
        for (const auto& [id, value] : preset_.parameters) {
            if (!params_.count(id)) continue;
            if (!std::isfinite(value) || std::fabs(value) > std::numeric_limits<float>::max()) {
                const SourceLocation& at = preset_.parameter_lines.at(id);
                return make_error(fmt::format("the shader parameter '{}' is set to {}, not a finite number within float range "
                                              "(RetroArch reads it as a float)", id, value), at.file, at.line, id);
            }
            values_[id] = value;
        }
        return Ok{};
    }

    static bool reserved_by_program(const std::string& name) {
        static const std::set<std::string> words = {"source", "sourceSize", "outputSize", "viewportSize", "frameCount", "time",
                                                    "CrtParams", "fragColor", "vTexCoord", "crtCorner", "MVP"};
        return words.count(name) != 0;
    }

    // crtforge aliases (identifiers, unique, not `original`), and the textures each name reaches.
    void name_passes() {
        std::set<std::string> taken{"original", "source"};
        for (size_t i = 0; i < passes_.size(); ++i) {
            const SlangpPass& pass = preset_.passes[i];
            std::string alias = !pass.alias.empty() ? pass.alias : passes_[i].source->name;
            std::string ours = alias.empty() ? "pass" + std::to_string(i) : identifier_from(alias);
            while (taken.count(ours)) ours.append(1, '_').append(std::to_string(i));
            taken.insert(ours);
            passes_[i].alias = ours;
            pass_index_[ours] = i;
            textures_["PassOutput" + std::to_string(i)] = ours;
            textures_["PassFeedback" + std::to_string(i)] = ours + "@previous";
            if (!alias.empty()) {
                textures_.emplace(alias, ours);
                textures_.emplace(alias + "Feedback", ours + "@previous");
            }
        }
        textures_["Original"] = "original";
        textures_["OriginalHistory0"] = "original";
        for (int n = 1; n <= kMaxHistory; ++n) textures_["OriginalHistory" + std::to_string(n)] = "original@" + std::to_string(n);
        for (const auto& lut : preset_.textures) {
            textures_[lut.name] = "lut:" + lut.name;
            luts_[lut.name] = &lut;
        }
    }

    // The textures pass i reaches: a pass at or after it (this frame's output does not exist yet)
    // is its previous frame's output. RetroArch refuses to sample one ("non-causal"), but reads
    // its size, and accepts a declaration nothing uses.
    std::map<std::string, std::string> textures_before(size_t i) const {
        std::map<std::string, std::string> out = textures_;
        for (auto& [name, from] : out)
            if (auto at = pass_index_.find(from); at != pass_index_.end() && at->second >= i) from += "@previous";
        return out;
    }

    Status write_luts() {
        for (const auto& lut : preset_.textures) {
            if (!detail::is_identifier(lut.name))
                return make_error("LUT name '" + lut.name + "' is not an identifier", lut.where.file, lut.where.line, "textures");
            auto bytes = read_text_file(lut.path, kMaxLutFileBytes);
            if (!bytes.ok()) return make_error(bytes.error().message, lut.where.file, lut.where.line, lut.name);
            if (std::string e = lut_picture_error(bytes.value()); !e.empty())
                return make_error("texture '" + lut.path + "' " + e, lut.where.file, lut.where.line, lut.name);
            out_.inputs.push_back(lut.path);
            const std::string file = out_.name + "/" + lut.name + fs::path(lut.path).extension().string();
            out_.files.push_back({"presets/" + file, std::move(bytes.value())});
            lut_files_[lut.name] = file;
        }
        return Ok{};
    }

    void write_stage() {
        std::string t;
        t += "# Imported by crtforge from RetroArch's " + toml_string(shown_path(preset_.path)) +
             ": a program stage, one form per pass.\n";
        t += "name = " + toml_string(out_.stage) + "\n";
        t += "doc = " + toml_string("The passes of RetroArch's " + fs::path(preset_.path).filename().string()) + "\n";
        t += "kind = \"program\"\n";
        const bool several = passes_.size() > 1;
        if (several) t += "selector = " + toml_string(out_.stage + "_pass") + "\n";
        // Params in first-declaration order across the passes, those some pass reads.
        std::set<std::string> read, written;
        for (const PassPlan& pass : passes_) read.insert(pass.program.params.begin(), pass.program.params.end());
        for (const PassPlan& pass : passes_)
            for (const SlangParameter& p : pass.source->parameters) {
                if (!read.count(p.id) || !written.insert(p.id).second) continue;
                // RetroArch clamps neither the default nor a preset's value to the declared range:
                // the range widens to hold both.
                double lo = std::min(p.minimum, p.initial), hi = std::max(p.maximum, p.initial);
                if (auto v = values_.find(p.id); v != values_.end()) {
                    if (v->second < p.minimum || v->second > p.maximum)
                        out_.warnings.push_back(make_error(fmt::format("the preset sets '{}' to {}, outside its declared range [{}, {}]: the "
                                                                       "range is widened (RetroArch does not clamp it)",
                                                                       p.id, toml_float(v->second), toml_float(p.minimum), toml_float(p.maximum)),
                                                           preset_.parameter_lines.at(p.id).file,
                                                           preset_.parameter_lines.at(p.id).line, p.id).warning());
                    lo = std::min(lo, v->second);
                    hi = std::max(hi, v->second);
                }
                if (!(lo < hi)) hi = lo + 1.0;
                t += "\n[[param]]\n";
                t += "name = " + toml_string(param_names_.at(p.id)) + "\n";
                t += "type = \"float\"\n";
                t += "range = [" + toml_float(lo) + ", " + toml_float(hi) + "]\n";
                if (p.step > 0 && std::isfinite(p.step)) t += "step = " + toml_float(p.step) + "\n";
                t += "default = " + toml_float(p.initial) + "\n";
                t += "doc = " + toml_string(doc_line(p.description, p.id) + (param_names_.at(p.id) != p.id ? " (RetroArch: " + p.id + ")" : "")) + "\n";
                t += "runtime = true\n";
            }
        if (several) {
            std::vector<std::string> forms;
            for (size_t i = 0; i < passes_.size(); ++i) forms.push_back("pass" + std::to_string(i));
            t += "\n[[param]]\nname = " + toml_string(out_.stage + "_pass") + "\ntype = \"enum\"\nvalues = " + toml_strings(forms) +
                 "\ndefault = \"pass0\"\ndoc = \"Which pass's program this pass runs\"\n";
        }
        for (size_t i = 0; i < passes_.size(); ++i) {
            const PassPlan& pass = passes_[i];
            const std::string form = "pass" + std::to_string(i);
            t += "\n[[form]]\nname = " + toml_string(form) + "\n";
            t += "doc = " + toml_string(doc_line(shown_path(pass.source->path), form)) + "\n";
            std::vector<std::string> params, builtins;
            for (const std::string& id : pass.program.params) params.push_back(param_names_.at(id));
            for (Builtin b : pass.program.builtins) builtins.push_back(builtin_name(b));
            t += "params = " + toml_strings(params) + "\nbuiltins = " + toml_strings(builtins) + "\ntextures = " +
                 toml_strings(pass.program.textures) + "\n";
            t += "vertex = " + toml_string(out_.stage + "/" + form + ".vert") + "\n";
            t += "fragment = " + toml_string(out_.stage + "/" + form + ".frag") + "\n";
            out_.files.push_back({"stages/" + out_.stage + "/" + form + ".vert", pass.program.vertex});
            out_.files.push_back({"stages/" + out_.stage + "/" + form + ".frag", pass.program.fragment});
        }
        out_.files.push_back({"stages/" + out_.stage + ".toml", t});
    }

    // How a texture is sampled, as `key = value` pairs: RetroArch's filter (unset: --smooth), wrap
    // (unset: clamp_to_border), mipmaps and, where it is not the filter, how their levels blend.
    std::vector<std::string> sampling(std::optional<bool> linear, const std::optional<std::string>& wrap,
                                      std::optional<bool> mipmap, bool blend_levels = false) const {
        const bool lin = linear.value_or(options_.unset_filter == Filter::Linear);
        std::vector<std::string> keys{fmt::format("filter = \"{}\"", lin ? "linear" : "nearest"),
                                      fmt::format("wrap = \"{}\"", wrap_of(wrap))};
        if (mipmap.value_or(false)) {
            keys.push_back("mipmap = true");
            if (blend_levels != lin) keys.push_back(fmt::format("mip_filter = \"{}\"", blend_levels ? "linear" : "nearest"));
        }
        return keys;
    }
    // Whether RetroArch blends mip levels in what pass k samples through its own settings: only
    // when its filter is not nearest (unset counts as linear here) and its own output has a chain
    // (mipmap_input of pass k + 1): its pass_info.mip_filter. Pass k's main input and this frame's
    // readers of pass k - 1 use it; readers of pass k's feedback use pass k's.
    bool blends_levels(size_t k) const {
        if (k >= preset_.passes.size()) return false;
        const bool next_mipmapped = k + 1 < preset_.passes.size() && preset_.passes[k + 1].mipmap_input.value_or(false);
        return preset_.passes[k].filter_linear.value_or(true) && next_mipmapped;
    }
    // How this frame's readers sample pass k's output: as the pass after it declares (filter_linear,
    // wrap_mode, mipmap_input of pass k + 1 describe the texture pass k produces); pass 0's filter
    // and wrap govern the original, which has no mip chain in RetroArch whatever mipmap_input0 says.
    std::vector<std::string> sampling_of_output(size_t producer) const {
        if (producer + 1 >= preset_.passes.size()) return sampling(std::nullopt, std::nullopt, std::nullopt);
        const SlangpPass& p = preset_.passes[producer + 1];
        return sampling(p.filter_linear, p.wrap_mode, p.mipmap_input, blends_levels(producer + 1));
    }
    // How readers of pass k's feedback sample it: RetroArch's update_feedback_info gives the copy
    // pass k's own filter, wrap and level blending; its chain is the output's (mipmap_input of k + 1).
    std::vector<std::string> sampling_of_feedback(size_t producer) const {
        const SlangpPass& p = preset_.passes[producer];
        const std::optional<bool> chain =
            producer + 1 < preset_.passes.size() ? preset_.passes[producer + 1].mipmap_input : std::nullopt;
        return sampling(p.filter_linear, p.wrap_mode, chain, blends_levels(producer));
    }

    // A pass's scale as RetroArch reads it: scale_typeN sets both axes and hides _x/_y, scaleN hides
    // scale_xN/_yN; no scale type at all: none (RetroArch: source x1, the last pass the viewport).
    struct Scale {
        std::string type_x, type_y;
        double x = 1.0, y = 1.0;
    };
    static std::optional<Scale> scale_of(const SlangpPass& p) {
        const std::optional<std::string> x = p.scale_type ? p.scale_type : p.scale_type_x;
        const std::optional<std::string> y = p.scale_type ? p.scale_type : p.scale_type_y;
        if (!x && !y) return std::nullopt;
        Scale scale{x.value_or("source"), y.value_or("source"), p.scale ? *p.scale : p.scale_x.value_or(1.0),
                    p.scale ? *p.scale : p.scale_y.value_or(1.0)};
        if (scale.type_x == "absolute") scale.x = std::round(scale.x);
        if (scale.type_y == "absolute") scale.y = std::round(scale.y);
        return scale;
    }

    // Each pass's scale as crtforge's preset loader takes it, refused here at the .slangp's own line
    // (the preset written would name only itself): above 0 and at most kMaxSceneDimension, an
    // absolute size once rounded as RetroArch rounds it.
    Status check_scales() const {
        for (size_t i = 0; i < preset_.passes.size(); ++i) {
            const SlangpPass& p = preset_.passes[i];
            const std::optional<Scale> scale = scale_of(p);
            if (!scale) continue;
            for (const auto& [value, type, axis] : {std::tuple{scale->x, scale->type_x, "scale_x"}, std::tuple{scale->y, scale->type_y, "scale_y"}}) {
                if (value > 0.0 && value <= kMaxSceneDimension) continue;
                const std::string key = p.scale ? "scale" : axis;
                const auto at = p.key_lines.find(key);
                const SourceLocation where = at != p.key_lines.end() ? at->second : p.where;
                return make_error(fmt::format("{} {} scale of {} is not one crtforge renders: above 0 and at most {}{}", type,
                                              std::string(axis).substr(6), toml_float(value), kMaxSceneDimension,
                                              type == "absolute" ? " pixels, once rounded" : ""),
                                  where.file, where.line, key + std::to_string(i));
            }
        }
        return Ok{};
    }

    static std::string scale_lines(const SlangpPass& p) {
        const std::optional<Scale> scale = scale_of(p);
        if (!scale) return "";  // crtforge's defaults are RetroArch's
        return fmt::format("scale_type_x = {}\nscale_type_y = {}\nscale = [{}, {}]\n", toml_string(scale->type_x),
                           toml_string(scale->type_y), toml_float(scale->x), toml_float(scale->y));
    }

    // Whether RetroArch draws the last pass into a framebuffer of its own size and then copies it
    // to the viewport: an explicit scale other than the viewport x1.
    bool last_pass_copied() const {
        const std::optional<Scale> scale = scale_of(preset_.passes.back());
        return scale && (scale->type_x != "viewport" || scale->type_y != "viewport" || scale->x != 1.0 || scale->y != 1.0);
    }

    void write_preset() {
        std::string t;
        t += "# Imported by crtforge from RetroArch's " +
             toml_string(shown_path(preset_.path)) + ".\n";
        t += "name = " + toml_string(out_.name) + "\n";
        t += "doc = " + toml_string("RetroArch's " + fs::path(preset_.path).filename().string() + ", imported") + "\n";
        if (options_.source_width > 0) t += fmt::format("\n[source]\nsize = [{}, {}]\n", options_.source_width, options_.source_height);
        t += fmt::format("\n[display]\nfit = {}\n", toml_string(display_fit_name(options_.fit)));
        t += "\n[time]\nfps = " + toml_float(options_.fps) + "\n";
        for (const auto& lut : preset_.textures) {
            t += "\n[lut." + lut.name + "]\n";
            t += "file = " + toml_string(lut_files_.at(lut.name)) + "\n";
            t += join_list(sampling(lut.linear, lut.wrap_mode, std::nullopt), "\n") + "\n";  // mipmaps: on the readers
        }
        for (size_t i = 0; i < passes_.size(); ++i) {
            const SlangpPass& p = preset_.passes[i];
            const PassPlan& plan = passes_[i];
            t += "\n[[pass]]\nalias = " + toml_string(plan.alias) + "\n";
            t += scale_lines(p);
            auto [format, exact] = pixel_format(p, plan.source->format);
            if (!exact)
                out_.warnings.push_back(make_error(fmt::format("pass {}: framebuffer format {} is stored as {} (crtforge has no {} yet)", i,
                                                               plan.source->format, format, plan.source->format),
                                                   p.where.file, p.where.line, "shader" + std::to_string(i))
                                            .warning());
            if (std::string(format) != "rgba8") t += fmt::format("format = \"{}\"\n", format);
            // RetroArch gives the original no mip chain: mipmap_input0 is never read.
            const std::optional<bool> main_mipmap = i == 0 ? std::nullopt : p.mipmap_input;
            t += join_list(sampling(p.filter_linear, p.wrap_mode, main_mipmap, blends_levels(i)), "\n") + "\n";
            if (p.frame_count_mod && *p.frame_count_mod > 0) t += fmt::format("frame_count_mod = {}\n", *p.frame_count_mod);
            if (!plan.program.textures.empty()) {
                t += "[pass.textures]\n";
                const std::map<std::string, std::string> reachable = textures_before(i);
                for (const std::string& name : plan.program.textures) {
                    const std::string& from = reachable.at(name);
                    std::vector<std::string> how;
                    if (from.rfind("original", 0) == 0) {
                        const SlangpPass& first = preset_.passes.front();
                        how = sampling(first.filter_linear, first.wrap_mode, std::nullopt);  // no chain: above
                    } else if (auto lut = luts_.find(name); lut != luts_.end()) {
                        if (lut->second->mipmap.value_or(false)) how = {"mipmap = true"};  // filter, wrap: its [lut] section's
                    } else {
                        const size_t producer = pass_index_.at(from.substr(0, from.find('@')));
                        const bool feedback = from.find('@') != std::string::npos;
                        how = feedback ? sampling_of_feedback(producer) : sampling_of_output(producer);
                    }
                    t += name + " = { from = " + toml_string(from) + (how.empty() ? "" : ", " + join_list(how)) + " }\n";
                }
            }
            t += "[pass.stages." + out_.stage + "]\n";
            if (passes_.size() > 1) t += out_.stage + "_pass = " + toml_string("pass" + std::to_string(i)) + "\n";
            for (const std::string& id : plan.program.params)
                if (auto v = values_.find(id); v != values_.end()) t += param_names_.at(id) + " = " + toml_float(v->second) + "\n";
        }
        if (last_pass_copied()) {
            // RetroArch draws the last pass at its own scale, then copies that picture to the viewport.
            t += "\n# RetroArch's copy of the last pass's framebuffer onto the viewport.\n";
            t += "[[pass]]\nalias = \"retroarch_viewport\"\n";
            t += fmt::format("filter = \"{}\"\n", options_.unset_filter == Filter::Linear ? "linear" : "nearest");
            t += "wrap = \"clamp_to_border\"\n";
        }
        out_.files.push_back({"presets/" + out_.name + ".toml", t});
    }

    const retroarch::SlangpPreset& preset_;
    const SlangImportOptions& options_;
    ImportedPreset out_;
    std::map<std::string, SlangSource> sources_;
    std::vector<PassPlan> passes_;
    std::map<std::string, SlangParameter> params_;
    std::map<std::string, std::string> param_names_;
    std::map<std::string, double> values_;
    std::map<std::string, std::string> textures_;   // RetroArch sampler name -> crtforge source
    std::map<std::string, std::string> lut_files_;  // LUT -> file relative to the preset file
    std::map<std::string, size_t> pass_index_;       // crtforge alias -> pass
    std::map<std::string, const retroarch::SlangpTexture*> luts_;
};

}  // namespace

std::string imported_preset_name(const std::string& slangp_path) {
    std::string out;
    for (char c : fs::path(slangp_path).stem().string()) {
        const unsigned char u = static_cast<unsigned char>(c);
        out += std::isalnum(u) ? static_cast<char>(std::tolower(u)) : c == '_' ? '_' : '-';
    }
    while (!out.empty() && !std::isalnum(static_cast<unsigned char>(out.front()))) out.erase(out.begin());
    return out.empty() ? "imported" : shortened(out, 64, '-');
}

Result<ImportedPreset> import_slangp(const std::string& slangp_path, const SlangImportOptions& options) {
    auto preset = retroarch::load_slangp(slangp_path, options.root);
    if (!preset.ok()) return preset.error();
    if (preset.value().passes.empty()) return make_error("has no passes", slangp_path, 0, "shaders");
    return Importer(preset.value(), options).run(slangp_path);
}

Status write_imported_preset(const ImportedPreset& preset, const std::string& dir) {
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) return make_error("exists and is not a folder", dir, 0, "--out");
    const fs::path staging = fs::path(dir) / (".crtforge-import-" + preset.name + "-" + std::to_string(::getpid()));
    fs::remove_all(staging, ec);
    // Every file staged first (where a full disk shows), then each moved into place.
    for (const ImportedFile& f : preset.files)
        if (auto s = write_file_atomic((staging / f.path).string(), f.data); !s.ok()) {
            fs::remove_all(staging, ec);
            return s;
        }
    for (const ImportedFile& f : preset.files) {
        const fs::path to = fs::path(dir) / f.path;
        fs::create_directories(to.parent_path(), ec);
        fs::rename(staging / f.path, to, ec);
        if (ec) {
            fs::remove_all(staging, ec);
            return make_error("cannot move the imported file into place: " + ec.message(), to.string(), 0, "--out");
        }
    }
    fs::remove_all(staging, ec);
    return Ok{};
}

}  // namespace crtforge
