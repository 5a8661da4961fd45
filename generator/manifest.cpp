#include "generator/manifest.hpp"

#include "crtforge/assembler.hpp"

namespace crtforge::detail {

using json = nlohmann::ordered_json;

json value_to_json(const Value& value) {
    if (auto d = std::get_if<double>(&value)) return *d;
    if (auto i = std::get_if<int64_t>(&value)) return *i;
    if (auto b = std::get_if<bool>(&value)) return *b;
    if (auto s = std::get_if<std::string>(&value)) return *s;
    const Color& c = std::get<Color>(value);
    return json::array({c[0], c[1], c[2]});
}

namespace {

const VariantParam* find_param(const Variant& v, const std::string& name) {
    for (const auto& p : v.params)
        if (p.spec->name == name) return &p;
    return nullptr;
}

json uniform_block(const CompiledVariant& compiled) {
    const auto& blocks = compiled.reflection.uniform_blocks;
    if (blocks.empty()) return nullptr;
    const ReflectedBlock& block = blocks.front();
    json members = json::array();
    for (const ReflectedMember& m : block.members) {
        json member;
        member["name"] = m.name;
        member["type"] = m.type;
        member["offset"] = m.offset;
        member["size"] = m.size;
        Builtin builtin{};
        if (parse_builtin(m.name, builtin)) {
            member["builtin"] = true;
            member["doc"] = builtin == Builtin::OutputSize ? "output size in pixels (width, height)"
                          : builtin == Builtin::SourceSize ? "source texture size in texels (width, height)"
                                                           : "seconds since start; keep it continuous";
        } else if (const VariantParam* p = find_param(compiled.variant, m.name)) {
            member["stage"] = p->stage->name;
            if (p->spec->min) member["range"] = json::array({*p->spec->min, *p->spec->max});
            if (p->spec->step) member["step"] = *p->spec->step;
            member["default"] = value_to_json(p->value);
            member["unit"] = p->spec->unit;
            member["doc"] = p->spec->doc;
        }
        members.push_back(std::move(member));
    }
    json out;
    out["name"] = block.name;
    out["instance"] = kUniformInstanceName;
    out["layout"] = "std140";
    out["set"] = block.set;
    out["binding"] = block.binding;
    out["size"] = block.size;
    // D3D constant buffers and many engines want whole 16-byte registers.
    out["allocationSize"] = (block.size + 15u) / 16u * 16u;
    out["members"] = std::move(members);
    return out;
}

}  // namespace

json preset_manifest(const CompiledVariant& compiled) {
    const Variant& v = compiled.variant;
    const Preset& preset = *v.preset;
    json out;
    out["doc"] = preset.doc;
    out["lineage"] = preset.lineage;
    out["precision"] = precision_name(v.options.precision);
    out["uniforms"] = v.options.uniforms.str();
    json stages = json::array();
    for (const ResolvedStage& rs : preset.stages)
        stages.push_back(json{{"stage", rs.stage->name}, {"form", rs.form->name}});
    out["stages"] = std::move(stages);
    json baked = json::object();
    for (const VariantParam* p : v.baked()) baked[p->spec->name] = value_to_json(p->value);
    out["baked"] = std::move(baked);
    out["uniformBlock"] = uniform_block(compiled);
    json textures = json::array();
    for (const ReflectedTexture& t : compiled.reflection.textures)
        textures.push_back(json{{"name", t.name}, {"set", t.set}, {"binding", t.binding},
                                {"filter", filter_name(preset.filter)}, {"addressMode", "clamp-to-edge"}});
    out["textures"] = std::move(textures);
    out["vertexInput"] = "none: draw 3 vertices; the vertex shader derives a full-screen triangle from the vertex index";
    return out;
}

json target_manifest(const ManifestTargetEntry& entry) {
    json out;
    for (const auto& [stage, path] : entry.files) out[stage] = path;
    json bindings = json::object();
    for (const auto& [name, how] : entry.bindings) bindings[name] = how;
    out["bindings"] = std::move(bindings);
    if (!entry.extra_json.empty()) {
        const json extra = json::parse(entry.extra_json);
        for (auto& [key, value] : extra.items()) out[key] = value;
    }
    return out;
}

}  // namespace crtforge::detail
