// compile_variant -> emit_target -> run_export: the in-memory export pipeline, with the
// content-hash cache in front of the two expensive steps (glslang+spirv-opt and SPIRV-Cross).
#include "crtforge/exporter.hpp"

#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "crtforge/assembler.hpp"
#include "generator/file_io.hpp"
#include "generator/manifest.hpp"

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

Result<SpirvBinary> compile_cached(const std::string& source, ShaderStage stage,
                                   const std::string& name, const Cache& cache) {
    const std::string key = Cache::key({"spirv", compiler_versions(), shader_stage_name(stage), source});
    if (auto hit = cache.get("spirv", key); hit && hit->size() % 4 == 0 && !hit->empty()) {
        SpirvBinary words = from_bytes(*hit);
        if (words[0] == 0x07230203u) return words;
    }
    CompileOptions options;
    options.stage = stage;
    options.source_name = name;
    auto spirv = compile_to_spirv(source, options);
    if (!spirv.ok()) return spirv;
    cache.put("spirv", key, to_bytes(spirv.value()));
    return spirv;
}

std::string serialize(const TargetOutput& out) {
    json j;
    j["files"] = json::array();
    for (const auto& f : out.files)
        j["files"].push_back(json{{"stage", shader_stage_name(f.stage)}, {"suffix", f.suffix}, {"data", f.data}});
    j["bindings"] = out.bindings;
    return j.dump();
}

std::optional<TargetOutput> deserialize(const std::string& text) {
    json j = json::parse(text, nullptr, false);
    if (j.is_discarded()) return std::nullopt;
    try {
        TargetOutput out;
        for (const auto& f : j.at("files"))
            out.files.push_back({f.at("stage") == "vert" ? ShaderStage::Vertex : ShaderStage::Fragment,
                                 f.at("suffix").get<std::string>(), f.at("data").get<std::string>()});
        out.bindings = j.at("bindings").get<std::vector<std::pair<std::string, std::string>>>();
        return out;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

}  // namespace

Result<CompiledVariant> compile_variant(const TemplateLibrary& library, const Preset& preset,
                                        const VariantOptions& options, const Cache& cache) {
    auto variant = make_variant(library, preset, options);
    if (!variant.ok()) return variant.error();
    CompiledVariant out;
    out.variant = std::move(variant.value());
    AssembledShader src = assemble(library, out.variant);
    out.fragment_glsl = src.fragment;
    auto frag = compile_cached(src.fragment, ShaderStage::Fragment, "<preset " + preset.name + ">", cache);
    if (!frag.ok()) return frag.error();
    out.fragment = std::move(frag.value());
    auto vert = compile_cached(src.vertex, ShaderStage::Vertex, library.vertex_path(), cache);
    if (!vert.ok()) return vert.error();
    out.vertex = std::move(vert.value());
    auto reflection = reflect(out.fragment);
    if (!reflection.ok()) return reflection.error();
    out.reflection = std::move(reflection.value());
    return out;
}

Result<TargetOutput> emit_target(const CompiledVariant& compiled, TargetId target, const Cache& cache) {
    TargetInput input{&compiled.variant, &compiled.fragment, &compiled.vertex};
    if (target == TargetId::Spirv) return generate_target(target, input);  // nothing to cache
    const std::string key = Cache::key({"target", target_fingerprint(target),
                                        precision_name(compiled.variant.options.precision),
                                        compiled.variant.has_uniform_block() ? "ubo" : "no-ubo",
                                        to_bytes(compiled.fragment), to_bytes(compiled.vertex)});
    const std::string kind = target_info(target).name;
    if (auto hit = cache.get(kind, key))
        if (auto out = deserialize(*hit)) return *out;
    auto out = generate_target(target, input);
    if (!out.ok()) return out;
    cache.put(kind, key, serialize(out.value()));
    return out;
}

std::string export_path(const std::string& preset, TargetId target, const std::string& suffix) {
    return std::string(target_info(target).name) + "/" + preset + suffix;
}

Result<ExportResult> run_export(const TemplateLibrary& library, const ExportRequest& request, const Cache& cache) {
    std::vector<const Preset*> presets;
    if (request.presets.empty()) {
        for (const auto& p : library.presets()) presets.push_back(&p);
    } else {
        for (const auto& name : request.presets) {
            const Preset* p = library.find_preset(name);
            if (!p) {
                std::string list;
                for (const auto& q : library.presets()) list += (list.empty() ? "" : ", ") + q.name;
                return make_error("unknown preset '" + name + "' (presets: " + list + ")", {}, 0, "--preset");
            }
            presets.push_back(p);
        }
    }
    std::vector<TargetId> targets = request.targets;
    if (targets.empty())
        for (const auto& t : all_targets()) targets.push_back(t.id);

    ExportResult result;
    json manifest;
    manifest["generator"] = std::string("crtforge ") + CRTFORGE_VERSION;
    manifest["manifestVersion"] = 1;
    manifest["options"] = json{{"uniforms", request.options.uniforms.str()},
                               {"precision", precision_name(request.options.precision)}};
    json target_names = json::array();
    for (TargetId t : targets) target_names.push_back(target_info(t).name);
    manifest["targets"] = std::move(target_names);
    manifest["presets"] = json::object();

    for (const Preset* preset : presets) {
        auto compiled = compile_variant(library, *preset, request.options, cache);
        if (!compiled.ok()) return compiled.error();
        json entry = detail::preset_manifest(compiled.value());
        json files = json::object();
        for (TargetId target : targets) {
            auto out = emit_target(compiled.value(), target, cache);
            if (!out.ok()) {
                Diagnostic d = out.error();
                d.message = "preset " + preset->name + ", target " + target_info(target).name + ": " + d.message;
                return d;
            }
            detail::ManifestTargetEntry te{target, {}, out.value().bindings};
            for (const OutputFile& f : out.value().files) {
                const std::string path = export_path(preset->name, target, f.suffix);
                te.files[f.stage == ShaderStage::Vertex ? "vertex" : "fragment"] = path;
                result.files[path] = f.data;
            }
            files[target_info(target).name] = detail::target_manifest(te);
        }
        entry["targets"] = std::move(files);
        manifest["presets"][preset->name] = std::move(entry);
        ++result.variants;
    }
    result.files["manifest.json"] = manifest.dump(2) + "\n";
    return result;
}

Status write_files(const std::string& dir, const std::map<std::string, std::string>& files) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) return make_error("cannot create output directory: " + ec.message(), dir, 0, "--out");
    if (!std::filesystem::is_directory(dir, ec)) return make_error("is not a directory", dir, 0, "--out");
    for (const auto& [path, data] : files)
        if (auto s = detail::write_file_atomic(dir + "/" + path, data); !s.ok()) return s;
    return Ok{};
}

}  // namespace crtforge
