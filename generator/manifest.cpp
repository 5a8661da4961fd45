#include "generator/manifest.hpp"

#include "crtforge/assembler.hpp"
#include "crtforge/luts.hpp"

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

json time_reduce_by(const Variant& variant) {
    const VariantParam* speed = variant.angular_speed();
    if (!speed) return nullptr;
    return speed->uniform ? json(speed->spec->name) : value_to_json(speed->value);
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
            member["doc"] = builtin_doc(builtin);
            // How hosts reduce the seconds (shader_time()): fmod(seconds * |S|, 2 pi) / |S| in double
            // precision, S the named uniform's value or the baked number.
            if (builtin == Builtin::Time && compiled.variant.angular_speed()) {
                member["doc"] = "seconds since start, reduced by the host in double precision: fmod(seconds * |S|, 2*pi) / |S|, "
                                "S = reduceBy (a uniform's name or a number)";
                member["reduceBy"] = time_reduce_by(compiled.variant);
            }
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

json scale_json(const PassScale& s) { return json{{"type", scale_type_name(s.type)}, {"factor", s.factor}}; }

json pass_manifest(const CompiledVariant& compiled) {
    const Variant& v = compiled.variant;
    const Pass& pass = *v.pass;
    json out;
    out["alias"] = pass.alias;
    out["scale"] = json{{"x", scale_json(pass.scale_x)}, {"y", scale_json(pass.scale_y)}};
    out["format"] = pixel_format_name(pass.format);
    out["frameCountMod"] = pass.frame_count_mod;
    // The pass's main input, read or not: its size is the pass's sourceSize and the base of a
    // source scale (a RetroArch pass may read only Original or a LUT and still scale by it).
    if (const PassInput* main = pass.find_input(kSourceTextureName)) out["input"] = main->from.str();
    json stages = json::array();
    for (const ResolvedStage& rs : pass.stages) stages.push_back(json{{"stage", rs.stage->name}, {"form", rs.form->name}});
    out["stages"] = std::move(stages);
    json baked = json::object();
    for (const VariantParam* p : v.baked()) baked[p->spec->name] = value_to_json(p->value);
    out["baked"] = std::move(baked);
    out["uniformBlock"] = uniform_block(compiled);
    // Every texture the shader declares, with what feeds it and how it is sampled.
    json textures = json::array();
    for (const ReflectedTexture& t : compiled.reflection.textures) {
        json texture{{"name", t.name}, {"set", t.set}, {"binding", t.binding}};
        if (const PassInput* input = pass.find_input(t.name)) {
            texture["from"] = input->from.str();
            texture["filter"] = filter_name(input->filter);
            texture["wrap"] = wrap_name(input->wrap);
            texture["mipmap"] = input->mipmap;
            if (input->mipmap) texture["mipFilter"] = filter_name(input->mip_filter);
        }
        textures.push_back(std::move(texture));
    }
    out["textures"] = std::move(textures);
    return out;
}

}  // namespace

json preset_manifest(const Preset& preset, const std::vector<CompiledVariant>& passes) {
    json out;
    out["doc"] = preset.doc;
    out["lineage"] = preset.lineage;
    if (!passes.empty()) {
        out["precision"] = precision_name(passes.front().variant.options.precision);
        out["uniforms"] = passes.front().variant.options.uniforms.str();
    }
    const SceneSettings& s = preset.scene;
    json source{{"pixelAspect", {s.pixel_aspect_x, s.pixel_aspect_y}}, {"fit", source_fit_name(s.source_fit)}};
    source["size"] = s.source_width ? json::array({s.source_width, s.source_height}) : json(nullptr);
    json display{{"fit", display_fit_name(s.fit)}};
    display["aspect"] = s.screen_aspect_x ? json::array({s.screen_aspect_x, s.screen_aspect_y}) : json(nullptr);
    out["scene"] = json{{"source", std::move(source)}, {"display", std::move(display)}, {"fps", s.fps},
                        {"historyFrames", preset.history_depth()}, {"feedback", preset.has_feedback()}};
    json luts = json::object();
    for (const LutSpec& lut : preset.luts) {
        json entry{{"file", lut_export_path(preset, lut)}, {"filter", filter_name(lut.filter)}, {"wrap", wrap_name(lut.wrap)}};
        if (const LutGenerator* g = find_lut_generator(lut.generator)) {
            entry["generator"] = lut.generator;
            entry["layout"] = g->layout;
            json params = json::object();
            for (const auto& [name, value] : lut.params) params[name] = value;
            entry["params"] = std::move(params);
        }
        luts[lut.name] = std::move(entry);
    }
    out["luts"] = std::move(luts);
    out["vertexInput"] = "none: draw 3 vertices; the vertex shader derives a full-screen triangle from the vertex index";
    json list = json::array();
    for (const CompiledVariant& c : passes) list.push_back(pass_manifest(c));
    out["passes"] = std::move(list);
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
