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
    if (text == "uber") { sel.mode = Mode::Uber; return sel; }
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
        case Mode::Uber: return "uber";
        case Mode::Names: {
            std::string out;
            for (const auto& n : names) out += (out.empty() ? "" : ",") + n;
            return out;
        }
    }
    return "default";
}

int VariantStage::switch_value(const FormSpec* form) const {
    for (size_t i = 0; i < stage->forms.size(); ++i)
        if (stage->forms[i].name == form->name) return static_cast<int>(i) + 1;
    return 0;
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

const FormSpec* Variant::program_form() const {
    if (stages.size() != 1 || stages.front().forms.empty()) return nullptr;
    const FormSpec* form = stages.front().forms.front();
    return form->program() ? form : nullptr;
}

std::map<std::string, bool> Variant::clamp_to_border_inputs() const {
    std::map<std::string, bool> out;
    for (const PassInput& in : pass->inputs)
        if (in.wrap == Wrap::ClampToBorder) out[in.binding] = in.filter == Filter::Linear;
    return out;
}

bool Variant::writes_alpha() const {
    for (const VariantStage& ss : stages)
        for (const FormSpec* form : ss.forms)
            if (!form->functions[static_cast<int>(Hook::Alpha)].empty()) return true;
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

namespace {

bool contains(const std::vector<std::string>& list, const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
}

// The uber-shader's stages: every stage of the library with a form whose textures the pass binds,
// each with those forms, its switch set to the form the pass runs (0: the pass does not run it),
// and every param one of those forms reads as a uniform holding the pass's value (or the default).
// Selectors are left out: the switch does their work.
void add_uber_stages(const TemplateLibrary& library, Variant& variant) {
    for (const StageSpec& stage : library.stages()) {
        if (stage.program) continue;  // a whole program is not a switchable stage
        VariantStage ss{&stage, {}, true};
        for (const FormSpec& form : stage.forms) {
            bool bound = true;
            for (const std::string& t : form.textures) bound = bound && contains(variant.textures, t);
            if (bound) ss.forms.push_back(&form);
        }
        if (ss.forms.empty()) continue;
        const ResolvedStage* running = variant.pass->find_stage(stage.name);
        VariantParam sw;
        sw.spec = &stage.stage_switch;
        sw.stage = &stage;
        sw.value = int64_t{running ? ss.switch_value(running->form) : 0};
        sw.uniform = true;
        variant.params.push_back(std::move(sw));
        for (const ParamSpec& spec : stage.params) {
            bool read = contains(stage.common_params, spec.name);
            for (const FormSpec* form : ss.forms) read = read || contains(form->params, spec.name);
            if (!read || spec.name == stage.selector) continue;
            VariantParam vp;
            vp.spec = &spec;
            vp.stage = &stage;
            vp.value = spec.default_value;
            if (running)
                if (auto v = running->values.find(spec.name); v != running->values.end()) vp.value = v->second;
            vp.uniform = true;
            variant.params.push_back(std::move(vp));
        }
        variant.stages.push_back(std::move(ss));
    }
}

// A specialised shader's stages: the pass's, one form each, and the params those forms read, each
// baked or a uniform as --uniforms says; `used` collects their names.
void add_pass_stages(Variant& variant, std::set<std::string>& used) {
    const UniformSelection& selection = variant.options.uniforms;
    for (const ResolvedStage& rs : variant.pass->stages) {
        variant.stages.push_back(VariantStage{rs.stage, {rs.form}, false});
        // Params in declaration order of the spec, so layouts are stable and readable.
        for (const ParamSpec& spec : rs.stage->params) {
            auto v = rs.values.find(spec.name);
            if (v == rs.values.end()) continue;
            VariantParam vp;
            vp.spec = &spec;
            vp.stage = rs.stage;
            vp.value = v->second;
            using Mode = UniformSelection::Mode;
            switch (selection.mode) {
                case Mode::Default:
                case Mode::All: vp.uniform = spec.runtime; break;
                case Mode::None: vp.uniform = false; break;
                case Mode::Names: vp.uniform = contains(selection.names, spec.name); break;
                case Mode::Uber: break;  // not a specialised shader: add_uber_stages()
            }
            used.insert(spec.name);
            variant.params.push_back(std::move(vp));
        }
    }
}

}  // namespace

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
    if (variant.uber()) add_uber_stages(library, variant);
    else add_pass_stages(variant, used);
    std::set<Builtin> needs;
    for (const VariantStage& ss : variant.stages)
        for (const FormSpec* form : ss.forms) needs.insert(form->builtins.begin(), form->builtins.end());

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
    // The others in declaration order, so a block's layout does not depend on the forms' lists.
    for (Builtin b : kAllBuiltins)
        if ((b == Builtin::OutputSize && !variant.stages.empty()) || (b != Builtin::OutputSize && needs.count(b)))
            variant.builtins.push_back(b);
    return variant;
}

}  // namespace crtforge
