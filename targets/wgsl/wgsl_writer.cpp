#include "targets/wgsl/wgsl_writer.hpp"
#include "crtforge/inert_text.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/assembler.hpp"
#include "targets/wgsl/wgsl_emitter.hpp"

namespace crtforge::wgsl {

namespace {

using json = nlohmann::ordered_json;

EmitOptions emit_options(const Variant& variant) {
    EmitOptions options;
    options.block_instance_names[kUniformBlockName] = kUniformInstanceName;
    options.header_comment = fmt::format(
        "crtforge preset '{}': WGSL for WebGPU, generated from SPIR-V by crtforge's WGSL emitter.\n"
        "{}\n"
        "Draw 3 vertices with no vertex buffers: {} makes a full-screen triangle, {} shades it.\n"
        "Bindings (group 0) and the uniform buffer's byte layout are in manifest.json under targets.wgsl.",
        variant.file_stem(), inert_comment(variant.preset->doc), kVertexEntry, kFragmentEntry);
    // WebGPU has no border colour: the hosts sample these clamp-to-edge and the shader fades.
    options.emulate_border = variant.clamp_to_border_inputs();
    if (variant.options.precision == Precision::Medium)
        options.header_comment += "\nMedium precision: WGSL has no relaxed precision, so this is the full-precision f32 shader.";
    return options;
}

// A nearest-filtered texture can be any float texture, rgba32float included, so its layout entry
// asks for unfilterable-float with a non-filtering sampler (valid without float32-filterable) —
// unless its mip levels blend (mipmap with mip_filter linear), which WebGPU counts as filtering.
json manifest_extra(const WgslModule& module, const Variant& variant) {
    auto nearest = [&](const std::string& texture) {
        const PassInput* input = variant.pass->find_input(texture);
        const bool blends_levels = input && input->mipmap && input->mip_filter == Filter::Linear;
        return variant.texture_filter(texture) == Filter::Nearest && !blends_levels;
    };
    json layout = json::array();
    json uniform_buffer = nullptr;
    for (const WgslBinding& b : module.bindings) {
        json entry;
        entry["binding"] = b.binding;
        entry["name"] = b.name;
        entry["visibility"] = b.stages;
        if (b.kind == "uniform-buffer") {
            entry["buffer"] = json{{"type", "uniform"}, {"minBindingSize", b.size}};
            json members = json::array();
            for (const WgslMember& m : b.members)
                members.push_back(json{{"name", m.name}, {"type", m.wgsl_type}, {"offset", m.offset}, {"size", m.size}});
            uniform_buffer = json{{"struct", b.wgsl_type}, {"binding", b.binding}, {"size", b.size},
                                  {"note", "little-endian f32/i32/u32; bytes between members are padding"},
                                  {"members", std::move(members)}};
        } else if (b.kind == "texture") {
            const std::string sample_type = nearest(b.name) && b.sample_type == "float" ? "unfilterable-float" : b.sample_type;
            entry["texture"] = json{{"sampleType", sample_type}, {"viewDimension", "2d"}, {"multisampled", false}};
            if (!b.paired_with.empty()) entry["pairedSampler"] = b.paired_with;
        } else {
            entry["sampler"] = json{{"type", nearest(b.paired_with) ? "non-filtering" : "filtering"}};
            // The host samples clamp-to-edge: the shader fades to the border (EmitOptions::emulate_border).
            if (b.border_in_shader) entry["sampler"]["borderInShader"] = true;
            if (!b.paired_with.empty()) entry["pairedTexture"] = b.paired_with;
        }
        layout.push_back(std::move(entry));
    }
    json out;
    out["entryPoints"] = json{{"vertex", kVertexEntry}, {"fragment", kFragmentEntry}};
    out["bindGroupLayout"] = json{{"group", 0}, {"entries", std::move(layout)}};
    out["uniformBuffer"] = std::move(uniform_buffer);
    out["primitive"] = "triangle-list, 3 vertices, no vertex buffers";
    return out;
}

// Re-runs the emitter on a debug-line build of the same source to name the template line of an
// instruction it cannot translate.
Diagnostic locate(const Diagnostic& error, const TargetInput& input, const EmitOptions& options) {
    if (!error.file.empty() || !input.fragment_source) return error;
    CompileOptions compile;
    compile.debug_lines = true;
    compile.source_name = "<fragment shader>";
    auto debug = compile_to_spirv(*input.fragment_source, compile);
    if (!debug.ok()) return error;
    auto again = emit_wgsl({{input.vertex, kVertexEntry}, {&debug.value(), kFragmentEntry}}, options);
    if (again.ok() || again.error().file.empty()) return error;
    return again.error();
}

}  // namespace

Result<TargetOutput> generate(const TargetInput& input) {
    const EmitOptions options = emit_options(*input.variant);
    auto module = emit_wgsl({{input.vertex, kVertexEntry}, {input.fragment, kFragmentEntry}}, options);
    if (!module.ok()) return locate(module.error(), input, options);
    TargetOutput out;
    out.files.push_back({ShaderStage::Fragment, ".wgsl", module.value().text, "shader", ""});
    for (const WgslBinding& b : module.value().bindings)
        out.bindings.push_back({b.name, fmt::format("@group({}) @binding({}) {}", b.group, b.binding, b.wgsl_type)});
    out.manifest_json = manifest_extra(module.value(), *input.variant).dump();
    return out;
}

std::vector<TargetInfo> records() {
    return {{TargetId::Wgsl, "wgsl", "WGSL for WebGPU: one module, vs_main + fs_main (crtforge's own emitter)",
             {"shader"}, "dawn", [](const TargetInput& in) { return generate(in); }, "wgsl/crtforge-emitter/v3"}};
}

}  // namespace crtforge::wgsl
