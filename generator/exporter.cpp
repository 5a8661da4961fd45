// compile_variant -> emit_target -> run_export: the in-memory export pipeline, with the
// content-hash cache in front of the two expensive steps (glslang+spirv-opt and SPIRV-Cross).
#include "crtforge/exporter.hpp"
#include "crtforge/parallel.hpp"
#include "crtforge/bounded_memo.hpp"
#include "crtforge/version.hpp"

#include <algorithm>
#include <cstring>
#include <atomic>
#include <filesystem>
#include <mutex>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/assembler.hpp"
#include "crtforge/luts.hpp"
#include "crtforge/files.hpp"
#include "crtforge/lut_file.hpp"
#include "generator/manifest.hpp"
#include "generator/spirv_source_key.hpp"
#include "generator/spirv_spec_values.hpp"
#include "generator/web_package.hpp"

namespace crtforge {

using json = nlohmann::ordered_json;

namespace {

std::string to_bytes(const SpirvBinary& words) {
    return std::string(reinterpret_cast<const char*>(words.data()), words.size() * sizeof(uint32_t));
}

SpirvBinary from_bytes(const std::string& bytes) {
    SpirvBinary words(bytes.size() / sizeof(uint32_t));
    std::memcpy(words.data(), bytes.data(), words.size() * sizeof(uint32_t));
    return words;
}

// Modules compiled earlier in this process (the full-screen vertex shader is shared by every
// variant): a memo in front of the on-disk cache.
BoundedMemo<SpirvBinary>& compile_memo() {
    static BoundedMemo<SpirvBinary> memo(256u << 20, [](const SpirvBinary& m) { return m.size() * sizeof(uint32_t); });
    return memo;
}

// Whether the float specialization constants `module` holds are the values the key took out of its
// source: only then may the module stand for every source of that key (glslang reads a literal as
// a double, as source_key() does, and a constant the module no longer holds reads nothing).
bool holds_key_values(const SpirvBinary& module, const SourceKey& key) {
    const auto held = spec_constant_values(module);
    for (const auto& [id, value] : key.float_values) {
        auto it = held.find(id);
        if (it != held.end() && (it->second.opcode != value.opcode || it->second.words != value.words)) return false;
    }
    return true;
}

Result<SpirvBinary> compile_cached(const std::string& source, ShaderStage stage, const std::string& name,
                                   bool optimize, bool local_names, const Cache& cache) {
    const SourceKey source_key = crtforge::source_key(source);
    const std::string key = Cache::key({"spirv", Cache::build_id(), compiler_versions(), shader_stage_name(stage),
                                        optimize ? "optimized" : "glslang", local_names ? "names" : "", source_key.text});
    // A kept module holds the values of the source that made it: this source's go in.
    auto with_values = [&](SpirvBinary words) {
        if (!source_key.float_values.empty()) write_spec_constant_values(words, source_key.float_values);
        return words;
    };
    if (auto known = compile_memo().find(key)) return with_values(std::move(*known));
    const auto claim = compile_memo().claim(key);  // a worker compiling this very source: wait for it
    if (auto known = compile_memo().find(key)) return with_values(std::move(*known));
    auto remember = [&](const SpirvBinary& words) { compile_memo().put(key, words); };
    if (auto hit = cache.get("spirv", key); hit && hit->size() % 4 == 0 && !hit->empty()) {
        // A cached module reaches SPIRV-Cross and the drivers: it must be valid SPIR-V, whatever
        // happened to the file (the checksum catches damage; this catches the rest).
        SpirvBinary words = from_bytes(*hit);
        if (words[0] == 0x07230203u && validate_spirv(words).ok()) {
            remember(words);
            return with_values(std::move(words));
        }
    }
    CompileOptions options;
    options.stage = stage;
    options.source_name = name;
    options.optimize = optimize;
    options.local_names = local_names;
    auto spirv = compile_to_spirv(source, options);
    if (!spirv.ok()) return spirv;
    if (holds_key_values(spirv.value(), source_key)) {
        cache.put("spirv", key, to_bytes(spirv.value()));
        remember(spirv.value());
    }
    return spirv;
}

// Cache encoding of a TargetOutput: length-prefixed fields (cheap to read back, unlike JSON).
void put_field(std::string& out, std::string_view field) {
    out += std::to_string(field.size());
    out += ':';
    out += field;
}

bool get_field(std::string_view& in, std::string& field) {
    const size_t colon = in.find(':');
    if (colon == std::string_view::npos || colon == 0 || colon > 12) return false;
    size_t size = 0;
    for (char c : in.substr(0, colon)) {
        if (c < '0' || c > '9') return false;
        size = size * 10 + static_cast<size_t>(c - '0');
    }
    if (in.size() < colon + 1 + size) return false;
    field.assign(in.substr(colon + 1, size));
    in.remove_prefix(colon + 1 + size);
    return true;
}

// A count of one or two digits.
bool parse_count(const std::string& field, int& n) {
    if (field.empty() || field.size() > 2) return false;
    n = 0;
    for (char c : field) {
        if (c < '0' || c > '9') return false;
        n = n * 10 + (c - '0');
    }
    return true;
}

std::string serialize(const TargetOutput& out) {
    std::string blob;
    put_field(blob, std::to_string(out.files.size()));
    for (const auto& f : out.files) {
        put_field(blob, shader_stage_name(f.stage));
        put_field(blob, f.suffix);
        put_field(blob, f.data);
        put_field(blob, f.role);
        put_field(blob, f.path);
    }
    put_field(blob, std::to_string(out.bindings.size()));
    for (const auto& [name, how] : out.bindings) {
        put_field(blob, name);
        put_field(blob, how);
    }
    put_field(blob, out.manifest_json);
    return blob;
}

std::optional<TargetOutput> deserialize(std::string_view in) {
    TargetOutput out;
    std::string field, stage, suffix, data, role, path, name, how;
    int n = 0;
    if (!get_field(in, field) || !parse_count(field, n)) return std::nullopt;
    for (; n > 0; --n) {
        if (!get_field(in, stage) || !get_field(in, suffix) || !get_field(in, data) || !get_field(in, role) ||
            !get_field(in, path))
            return std::nullopt;
        out.files.push_back({stage == "vert" ? ShaderStage::Vertex : ShaderStage::Fragment, suffix, data, role, path});
    }
    if (!get_field(in, field) || !parse_count(field, n)) return std::nullopt;
    for (; n > 0; --n) {
        if (!get_field(in, name) || !get_field(in, how)) return std::nullopt;
        out.bindings.emplace_back(name, how);
    }
    if (!get_field(in, out.manifest_json)) return std::nullopt;
    if (!in.empty()) return std::nullopt;
    return out;
}

// Exact text of a value: value_to_string rounds colours to 8 bits.
std::string exact_value(const Value& value) {
    if (auto c = std::get_if<Color>(&value)) return fmt::format("{} {} {}", (*c)[0], (*c)[1], (*c)[2]);
    return value_to_string(value);
}

std::string optional_number(const std::optional<double>& x) { return x ? fmt::format("{}", *x) : std::string("-"); }

// Everything besides the SPIR-V that a target may print or decide by: Godot files carry the
// preset's name and doc and every param's range, step, unit, doc and default (hint_range, inspector
// text), and two presets can share one SPIR-V module. Every field of ParamSpec is here, so an edit
// to any of them is a new key; text fields are length-prefixed so no two fingerprints collide.
std::string variant_fingerprint(const Variant& v) {
    auto text = [](const std::string& s) { return fmt::format("{}:{}", s.size(), s); };
    std::string out = text(v.file_stem()) + text(v.preset->doc) +
                      fmt::format("pass {} of {};alpha {};", v.pass_index, v.preset->passes.size(), v.writes_alpha());
    // The format: Godot's shaders reduce their output to a format its viewports lack.
    out += fmt::format("frame_mod {};supersample {};format {};", v.pass->frame_count_mod, v.pass->supersample,
                       pixel_format_name(v.pass->format));
    for (const PassInput& input : v.pass->inputs)
        out += text(input.binding) + text(input.from.str()) + filter_name(input.filter) + ":" + wrap_name(input.wrap) +
               (input.mipmap ? std::string(":mip ") + filter_name(input.mip_filter) + ";" : std::string(";"));
    for (const std::string& t : v.textures) out += "texture " + text(t);
    for (Builtin b : v.builtins) out += fmt::format("builtin {};", static_cast<int>(b));
    for (const VariantParam& p : v.params) {
        const ParamSpec& spec = *p.spec;
        out += text(spec.name) + (p.uniform ? "u:" : "c:") + text(exact_value(p.value));
        out += fmt::format("type {};min {};max {};step {};role {};runtime {};", static_cast<int>(spec.type),
                           optional_number(spec.min), optional_number(spec.max), optional_number(spec.step),
                           static_cast<int>(spec.role), spec.runtime);
        out += text(exact_value(spec.default_value)) + text(spec.unit) + text(spec.doc);
        for (const std::string& e : spec.enum_values) out += text(e);
        out += "\n";
    }
    return out;
}

}  // namespace

Result<CompiledVariant> compile_variant(const TemplateLibrary& library, const Preset& preset,
                                        const VariantOptions& options, const Cache& cache, size_t pass_index) {
    auto variant = make_variant(library, preset, options, pass_index);
    if (!variant.ok()) return variant.error();
    CompiledVariant out;
    out.variant = std::move(variant.value());
    auto compile_stages = [&](BakedParams baked) -> Status {
        AssembledShader src = assemble(library, out.variant, baked);
        out.fragment_glsl = src.fragment;
        auto frag = compile_cached(src.fragment, ShaderStage::Fragment, "<preset " + out.variant.file_stem() + ">",
                                   options.optimize, options.local_names, cache);
        if (!frag.ok()) return frag.error();
        out.fragment = std::move(frag.value());
        auto vert = compile_cached(src.vertex, ShaderStage::Vertex, library.vertex_path(), options.optimize, options.local_names, cache);
        if (!vert.ok()) return vert.error();
        out.vertex = std::move(vert.value());
        return Ok{};
    };
    // A program's baked params are variables it never writes, folded by spirv-opt in 32 bits as a
    // GPU computes RetroArch's run-time params: as `const`s, glslang would fold their constant
    // expressions in double precision (crt-maximus-royale's H_blur: 0.001 / 10.0 folded to
    // 9.99999975e-05, not the 32-bit 1.00000005e-04, and its float loop ran once more). A program
    // that needs them constant (an array size) gets constants, and an error then is its own
    // (assembler.hpp, BakedParams). With specialize_baked they are specialization constants
    // first, where the program allows them.
    const bool program_baked = out.variant.program_form() && !out.variant.baked().empty();
    const bool specialized = options.specialize_baked && program_baked && compile_stages(BakedParams::Specialized).ok();
    if (!specialized) {
        const BakedParams first = program_baked ? BakedParams::Variables : BakedParams::Constants;
        if (auto s = compile_stages(first); !s.ok()) {
            if (!program_baked) return s.error();
            if (auto again = compile_stages(BakedParams::Constants); !again.ok()) return again.error();
        }
    }
    auto reflection = reflect(out.fragment);
    if (!reflection.ok()) return reflection.error();
    out.reflection = std::move(reflection.value());
    // A program's vertex shader may read the block or a texture the fragment shader does not: the
    // host binds what either stage declares (the assembler gives both stages the same block).
    auto vertex_reflection = reflect(out.vertex);
    if (!vertex_reflection.ok()) return vertex_reflection.error();
    for (ReflectedBlock& block : vertex_reflection.value().uniform_blocks)
        if (std::none_of(out.reflection.uniform_blocks.begin(), out.reflection.uniform_blocks.end(),
                         [&](const ReflectedBlock& b) { return b.binding == block.binding; }))
            out.reflection.uniform_blocks.push_back(std::move(block));
    for (ReflectedTexture& texture : vertex_reflection.value().textures)
        if (std::none_of(out.reflection.textures.begin(), out.reflection.textures.end(),
                         [&](const ReflectedTexture& t) { return t.binding == texture.binding; }))
            out.reflection.textures.push_back(std::move(texture));
    return out;
}

Result<std::vector<CompiledVariant>> compile_scene(const TemplateLibrary& library, const Preset& preset,
                                                   const VariantOptions& options, const Cache& cache) {
    std::vector<CompiledVariant> passes;
    for (size_t i = 0; i < preset.passes.size(); ++i) {
        auto compiled = compile_variant(library, preset, options, cache, i);
        if (!compiled.ok()) return compiled.error();
        passes.push_back(std::move(compiled.value()));
    }
    return passes;
}

Result<TargetOutput> emit_target(const CompiledVariant& compiled, TargetId target, const Cache& cache) {
    TargetInput input{&compiled.variant, &compiled.fragment, &compiled.vertex, &compiled.fragment_glsl};
    if (target == TargetId::Spirv) return generate_target(target, input);  // nothing to cache
    const std::string key = Cache::key({"target", Cache::build_id(), target_info(target).fingerprint,
                                        precision_name(compiled.variant.options.precision),
                                        compiled.variant.has_uniform_block() ? "ubo" : "no-ubo",
                                        to_bytes(compiled.fragment), to_bytes(compiled.vertex),
                                        variant_fingerprint(compiled.variant)});
    const std::string kind = target_info(target).name;
    if (auto hit = cache.get(kind, key))
        if (auto out = deserialize(*hit)) return *out;
    auto out = generate_target(target, input);
    if (!out.ok()) return out;
    cache.put(kind, key, serialize(out.value()));
    return out;
}

Result<std::vector<TargetOutput>> emit_scene(const std::vector<CompiledVariant>& passes, TargetId target, const Cache& cache) {
    std::vector<TargetOutput> outputs;
    for (const CompiledVariant& pass : passes) {
        auto out = emit_target(pass, target, cache);
        if (!out.ok()) return out.error();
        outputs.push_back(std::move(out.value()));
    }
    return outputs;
}

std::string export_path(const std::string& stem, TargetId target, const std::string& suffix) {
    return std::string(target_info(target).name) + "/" + stem + suffix;
}

std::string lut_file_path(const LutSpec& lut) {
    const std::filesystem::path file(lut.file);
    if (file.is_absolute()) return lut.file;
    return (std::filesystem::path(lut.where.file).parent_path() / file).string();
}

std::string lut_export_path(const Preset& preset, const LutSpec& lut) {
    // Generated LUTs are PNG; a file LUT is too wherever a decoder can make it one (lut_files).
    const bool png = !lut.generator.empty() || lut_picture_decoder();
    const std::string ext = png ? ".png" : std::filesystem::path(lut.file).extension().string();
    return "luts/" + preset.name + "." + lut.name + ext;
}

Result<std::map<std::string, std::string>> lut_files(const Preset& preset) {
    std::map<std::string, std::string> files;
    for (const LutSpec& lut : preset.luts) {
        if (!lut.generator.empty()) {
            auto image = generate_lut(lut.generator, lut.params);
            if (!image.ok()) {
                Diagnostic d = image.error();
                d.file = lut.where.file;
                d.line = lut.where.line;
                d.field = "lut." + lut.name;
                return d;
            }
            files[lut.name] = encode_png(image.value());
            continue;
        }
        // Read and checked at load (crtforge/lut_file.hpp); a LUT resolved outside a library is
        // read and checked here.
        std::string bytes;
        if (lut.bytes) {
            bytes = *lut.bytes;
        } else {
            auto data = read_text_file(lut_file_path(lut), kMaxLutFileBytes);
            if (!data.ok()) return make_error("cannot read the LUT file: " + data.error().message, lut.where.file, lut.where.line,
                                              "lut." + lut.name + ".file");
            if (std::string e = lut_picture_error(data.value()); !e.empty())
                return make_error("the LUT file '" + lut.file + "' " + e, lut.where.file, lut.where.line, "lut." + lut.name + ".file");
            bytes = std::move(data.value());
        }
        // A JPEG (any picture but a PNG) ships as the PNG of its decoded texels, where a decoder is
        // registered (lut_export_path names it .png then).
        const bool png = bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
        if (LutPictureDecoder decode = lut_picture_decoder(); decode && !png) {
            auto picture = decode(lut_file_path(lut));
            if (!picture.ok())
                return make_error("cannot decode the LUT file '" + lut.file + "': " + picture.error().message, lut.where.file,
                                  lut.where.line, "lut." + lut.name + ".file");
            bytes = encode_png(picture.value());
        }
        files[lut.name] = std::move(bytes);
    }
    return files;
}

Result<std::vector<OutputFile>> generate_target_scene(TargetId target, const Preset& preset,
                                                      const std::vector<CompiledVariant>& passes,
                                                      const std::vector<TargetOutput>& outputs,
                                                      const std::map<std::string, std::string>& luts) {
    const TargetInfo& info = target_info(target);
    if (!info.generate_scene) return std::vector<OutputFile>{};
    SceneTargetInput in;
    in.preset = &preset;
    for (const CompiledVariant& pass : passes) in.passes.push_back(&pass.variant);
    for (const TargetOutput& out : outputs) in.outputs.push_back(&out);
    in.lut_files = luts;
    auto files = info.generate_scene(in);
    if (!files.ok()) {
        Diagnostic d = files.error();
        d.message = std::string("target ") + info.name + " scene: " + d.message;
        return d;
    }
    return files;
}

namespace {

// manifest.json's fields above "presets" (which starts empty).
json manifest_head(const VariantOptions& options, const std::vector<TargetId>& targets) {
    json manifest;
    manifest["generator"] = std::string("crtforge ") + CRTFORGE_VERSION;
    manifest["manifestVersion"] = 2;
    manifest["options"] = json{{"uniforms", options.uniforms.str()}, {"precision", precision_name(options.precision)}};
    json target_names = json::array();
    for (TargetId t : targets) target_names.push_back(target_info(t).name);
    manifest["targets"] = std::move(target_names);
    manifest["presets"] = json::object();
    return manifest;
}

// Puts one pass's emitted files for `target` at their export paths; returns the pass's manifest
// entry for the target (which names those paths).
json place_target_files(const CompiledVariant& variant, TargetId target, const TargetOutput& out,
                        std::map<std::string, std::string>& files) {
    detail::ManifestTargetEntry te{target, {}, out.bindings, out.manifest_json};
    for (const OutputFile& f : out.files) {
        const std::string path = f.path.empty() ? export_path(variant.variant.file_stem(), target, f.suffix)
                                                : std::string(target_info(target).name) + "/" + f.path;
        te.files[f.manifest_role()] = path;
        files[path] = f.data;
    }
    return detail::target_manifest(te);
}

void place_lut_files(const Preset& preset, const std::map<std::string, std::string>& luts,
                     std::map<std::string, std::string>& files) {
    for (const LutSpec& lut : preset.luts) files[lut_export_path(preset, lut)] = luts.at(lut.name);
}

}  // namespace

Result<std::map<std::string, std::string>> preset_web_package(const Preset& preset, const std::vector<CompiledVariant>& passes,
                                                              const std::vector<TargetOutput>& wgsl) {
    if (passes.empty() || wgsl.size() != passes.size())
        return make_error("preset " + preset.name + ": the npm package needs every pass's WGSL");
    auto luts = lut_files(preset);
    if (!luts.ok()) return luts.error();
    std::map<std::string, std::string> files;
    place_lut_files(preset, luts.value(), files);
    json entry = detail::preset_manifest(preset, passes);
    for (size_t i = 0; i < passes.size(); ++i)
        entry["passes"][i]["targets"] = json{{target_info(TargetId::Wgsl).name, place_target_files(passes[i], TargetId::Wgsl, wgsl[i], files)}};
    json manifest = manifest_head(passes.front().variant.options, {TargetId::Wgsl});
    manifest["presets"][preset.name] = std::move(entry);
    if (auto package = detail::add_web_package(manifest, files); !package.ok()) return package.error();
    std::map<std::string, std::string> package;
    const std::string dir = detail::kWebPackageDir;
    for (auto& [path, data] : files)
        if (path.compare(0, dir.size(), dir) == 0) package[path.substr(dir.size())] = std::move(data);
    return package;
}

Result<ExportResult> run_export(const TemplateLibrary& library, const ExportRequest& request, const Cache& cache) {
    std::vector<const Preset*> presets;
    if (request.presets.empty()) {
        for (const auto& p : library.presets())
            if (!p.test_only) presets.push_back(&p);
    } else {
        for (const auto& name : request.presets) {
            auto p = library.lookup_preset(name);
            if (!p.ok()) return p.error();
            presets.push_back(p.value());
        }
    }
    std::vector<TargetId> targets = request.targets;
    if (targets.empty())
        for (const auto& t : all_targets()) targets.push_back(t.id);

    ExportResult result;
    json manifest = manifest_head(request.options, targets);

    // Every pass of every preset is compiled and emitted for the targets on a worker thread
    // (glslang, SPIRV-Tools and SPIRV-Cross objects are per-thread), so one many-pass preset uses
    // every core; each preset's LUTs, manifest entry and scene files follow once its passes are
    // in. Results are gathered in order, so output stays deterministic.
    struct PassOutput {
        std::optional<Diagnostic> compile_error, emit_error;
        std::optional<CompiledVariant> compiled;
        std::vector<TargetOutput> outputs;  // per target, in `targets` order
    };
    std::vector<std::pair<size_t, size_t>> pass_items;  // (preset, pass)
    std::vector<std::vector<PassOutput>> pass_outputs(presets.size());
    for (size_t i = 0; i < presets.size(); ++i) {
        pass_outputs[i].resize(presets[i]->passes.size());
        for (size_t pass = 0; pass < presets[i]->passes.size(); ++pass) pass_items.emplace_back(i, pass);
    }
    parallel_for(pass_items.size(), hardware_threads(), [&](size_t item) {
        const auto [i, pass] = pass_items[item];
        PassOutput& po = pass_outputs[i][pass];
        auto compiled = compile_variant(library, *presets[i], request.options, cache, pass);
        if (!compiled.ok()) {
            po.compile_error = compiled.error();
            return;
        }
        po.compiled = std::move(compiled.value());
        for (TargetId target : targets) {
            auto out = emit_target(*po.compiled, target, cache);
            if (!out.ok()) {
                Diagnostic d = out.error();
                d.message = "preset " + presets[i]->name + (presets[i]->single_pass() ? "" : ", pass " + po.compiled->variant.pass->alias) +
                            ", target " + target_info(target).name + ": " + d.message;
                po.emit_error = d;
                return;
            }
            po.outputs.push_back(std::move(out.value()));
        }
    });

    struct PresetOutput {
        std::optional<Diagnostic> error;
        json entry;
        std::map<std::string, std::string> files;
    };
    std::vector<PresetOutput> outputs(presets.size());
    parallel_for(presets.size(), hardware_threads(), [&](size_t i) {
        const Preset* preset = presets[i];
        PresetOutput& po = outputs[i];
        // The first failing pass in order: a compile error before any emitter's, as a scene
        // compiles whole before it is emitted.
        for (const PassOutput& pass : pass_outputs[i])
            if (pass.compile_error) {
                po.error = pass.compile_error;
                return;
            }
        for (const PassOutput& pass : pass_outputs[i])
            if (pass.emit_error) {
                po.error = pass.emit_error;
                return;
            }
        std::vector<CompiledVariant> compiled;
        for (PassOutput& pass : pass_outputs[i]) compiled.push_back(std::move(*pass.compiled));
        auto luts = lut_files(*preset);
        if (!luts.ok()) {
            po.error = luts.error();
            return;
        }
        place_lut_files(*preset, luts.value(), po.files);
        po.entry = detail::preset_manifest(*preset, compiled);
        std::map<TargetId, std::vector<TargetOutput>> per_target;
        for (size_t pass = 0; pass < compiled.size(); ++pass) {
            json files = json::object();
            for (size_t t = 0; t < targets.size(); ++t) {
                TargetOutput& out = pass_outputs[i][pass].outputs[t];
                files[target_info(targets[t]).name] = place_target_files(compiled[pass], targets[t], out, po.files);
                per_target[targets[t]].push_back(std::move(out));
            }
            po.entry["passes"][pass]["targets"] = std::move(files);
        }
        // Whole-scene files (Godot's .tscn), after every pass of every target.
        for (TargetId target : targets) {
            auto scene = generate_target_scene(target, *preset, compiled, per_target[target], luts.value());
            if (!scene.ok()) {
                Diagnostic d = scene.error();
                d.message = "preset " + preset->name + ", " + d.message;
                po.error = d;
                return;
            }
            if (scene.value().empty()) continue;
            json roles = json::object();
            for (const OutputFile& f : scene.value()) {
                const std::string path = std::string(target_info(target).name) + "/" + f.path;
                roles[f.manifest_role()] = path;
                po.files[path] = f.data;
            }
            po.entry["scene"]["targets"][target_info(target).name] = std::move(roles);
        }
    });

    for (size_t i = 0; i < presets.size(); ++i) {
        if (outputs[i].error) return *outputs[i].error;  // the first failing preset, in order
        manifest["presets"][presets[i]->name] = std::move(outputs[i].entry);
        result.files.merge(outputs[i].files);
        ++result.variants;
    }
    if (auto package = detail::add_web_package(manifest, result.files); !package.ok()) return package.error();
    result.files["manifest.json"] = manifest.dump(2) + "\n";
    return result;
}

Status write_files(const std::string& dir, const std::map<std::string, std::string>& files) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) return make_error("cannot create output directory: " + ec.message(), dir, 0, "--out");
    if (!std::filesystem::is_directory(dir, ec)) return make_error("is not a directory", dir, 0, "--out");
    for (const auto& [path, data] : files) {
        // Unchanged files are left alone: re-exports are cheap and keep file times stable.
        if (auto existing = read_text_file(dir + "/" + path); existing.ok() && existing.value() == data) continue;
        if (auto s = write_file_atomic(dir + "/" + path, data); !s.ok()) return s;
    }
    return Ok{};
}

}  // namespace crtforge
