// Splits a preset's params into baked constants and runtime uniforms.
#include "crtforge/variant.hpp"

#include <algorithm>
#include <set>
#include <sstream>

namespace crtforge {

const char* precision_name(Precision precision) {
    return precision == Precision::High ? "high" : "medium";
}

Result<UniformSelection> UniformSelection::parse(const std::string& text) {
    UniformSelection sel;
    if (text.empty() || text == "default") return sel;
    if (text == "all") { sel.mode = Mode::All; return sel; }
    if (text == "none") { sel.mode = Mode::None; return sel; }
    sel.mode = Mode::Names;
    std::stringstream ss(text);
    std::string name;
    while (std::getline(ss, name, ',')) {
        if (name.empty()) return make_error("empty name in the list '" + text + "'", {}, 0, "--uniforms");
        sel.names.push_back(name);
    }
    return sel;
}

std::string UniformSelection::str() const {
    switch (mode) {
        case Mode::Default: return "default";
        case Mode::All: return "all";
        case Mode::None: return "none";
        case Mode::Names: {
            std::string out;
            for (const auto& n : names) out += (out.empty() ? "" : ",") + n;
            return out;
        }
    }
    return "default";
}

std::string Variant::file_stem() const {
    return preset->single_pass() ? preset->name : preset->name + "." + pass->alias;
}

Filter Variant::texture_filter(const std::string& name) const {
    const PassInput* input = pass->find_input(name);
    return input ? input->filter : preset->filter;
}

bool Variant::has_uniform_block() const { return !builtins.empty() || !uniforms().empty(); }

std::vector<const VariantParam*> Variant::uniforms() const {
    std::vector<const VariantParam*> out;
    for (const auto& p : params)
        if (p.uniform) out.push_back(&p);
    return out;
}

bool Variant::writes_alpha() const {
    for (const ResolvedStage& rs : pass->stages)
        if (!rs.form->functions[static_cast<int>(Hook::Alpha)].empty()) return true;
    return false;
}

const VariantParam* Variant::angular_speed() const {
    for (const VariantParam& p : params)
        if (p.spec->role == ParamRole::AngularSpeed) return &p;
    return nullptr;
}

std::vector<const VariantParam*> Variant::baked() const {
    std::vector<const VariantParam*> out;
    for (const auto& p : params)
        if (!p.uniform) out.push_back(&p);
    return out;
}

Result<Variant> make_variant(const TemplateLibrary& library, const Preset& preset,
                             const VariantOptions& options, size_t pass_index) {
    if (pass_index >= preset.passes.size())
        return make_error("preset '" + preset.name + "' has no pass " + std::to_string(pass_index));
    Variant variant;
    variant.preset = &preset;
    variant.pass = &preset.passes[pass_index];
    variant.pass_index = pass_index;
    variant.options = options;
    variant.textures = variant.pass->texture_names();

    std::set<std::string> used;
    bool needs_time = false, needs_source_size = false, needs_frame_count = false;
    for (const ResolvedStage& rs : variant.pass->stages) {
        // Params in declaration order of the spec, so layouts are stable and readable.
        for (const ParamSpec& spec : rs.stage->params) {
            auto v = rs.values.find(spec.name);
            if (v == rs.values.end()) continue;
            VariantParam vp;
            vp.spec = &spec;
            vp.stage = rs.stage;
            vp.value = v->second;
            using Mode = UniformSelection::Mode;
            switch (options.uniforms.mode) {
                case Mode::Default: vp.uniform = spec.runtime; break;
                case Mode::All: vp.uniform = spec.runtime; break;
                case Mode::None: vp.uniform = false; break;
                case Mode::Names:
                    vp.uniform = std::find(options.uniforms.names.begin(), options.uniforms.names.end(),
                                           spec.name) != options.uniforms.names.end();
                    break;
            }
            used.insert(spec.name);
            variant.params.push_back(std::move(vp));
        }
        for (Builtin b : rs.form->builtins) {
            needs_time = needs_time || b == Builtin::Time;
            needs_source_size = needs_source_size || b == Builtin::SourceSize;
            needs_frame_count = needs_frame_count || b == Builtin::FrameCount;
        }
    }

    if (options.uniforms.mode == UniformSelection::Mode::Names) {
        for (const auto& name : options.uniforms.names) {
            const StageSpec* owner = nullptr;
            const ParamSpec* spec = library.find_param(name, &owner);
            if (!spec) return make_error("'" + name + "' is not a param of any stage", {}, 0, "--uniforms");
            if (!spec->runtime)
                return make_error("'" + name + "' cannot be a runtime uniform (runtime = false at " +
                                  spec->where.file + ":" + std::to_string(spec->where.line) + ")", {}, 0, "--uniforms");
            bool anywhere = used.count(name) != 0;
            for (const Pass& p : preset.passes)
                for (const ResolvedStage& rs : p.stages) anywhere = anywhere || rs.values.count(name) != 0;
            if (!anywhere)
                return make_error("'" + name + "' is not used by preset '" + preset.name +
                                  "' (its stage is off or its form does not read it)", {}, 0, "--uniforms");
        }
    }

    // Hosts hand the shader time reduced by one period of the speed it drives, exactly, so no phase
    // depends on the size of raw time; two speeds have no common period to reduce by.
    const VariantParam* speed = nullptr;
    for (const VariantParam& p : variant.params) {
        if (p.spec->role != ParamRole::AngularSpeed) continue;
        if (speed)
            return make_error("pass '" + variant.pass->alias + "' of preset '" + preset.name + "' reads two angular_speed params (" +
                                  speed->spec->name + ", " + p.spec->name + "): hosts reduce time exactly by one speed's period",
                              p.spec->where.file, p.spec->where.line, p.spec->name + ".role");
        speed = &p;
    }

    // outputSize is always present when any stage runs: the pixel grid every stage works on.
    if (!variant.pass->stages.empty()) variant.builtins.push_back(Builtin::OutputSize);
    if (needs_source_size) variant.builtins.push_back(Builtin::SourceSize);
    if (needs_time) variant.builtins.push_back(Builtin::Time);
    if (needs_frame_count) variant.builtins.push_back(Builtin::FrameCount);
    return variant;
}

}  // namespace crtforge
