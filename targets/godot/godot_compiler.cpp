#include "targets/godot/godot_compiler.hpp"
#include "targets/float_literals.hpp"
#include "crtforge/inert_text.hpp"

#include <algorithm>
#include <regex>

#include <fmt/format.h>

#include "crtforge/assembler.hpp"
#include "crtforge/version.hpp"
#include "targets/cross_compile.hpp"

namespace crtforge::godot {

namespace {

// Godot's shading language has no global variables, only constants: SPIRV-Cross prints each OpUndef
// (the optimiser's "any value" for a lane or branch never read) as a global `vec4 _1032;`, which
// Godot 4 refuses ("Expected initialization of constant") and Godot 3 accepts only by luck. Every
// OpUndef becomes an OpConstantNull of its type (same operands; moved out of a function body into
// the globals, before the first function), which SPIRV-Cross prints inline as a zero value.
std::vector<uint32_t> without_undefined_values(std::vector<uint32_t> words) {
    constexpr uint32_t kOpUndef = 1, kOpFunction = 54, kOpConstantNull = 46, kOpTypeVoid = 19;
    if (words.size() < 5) return words;
    std::vector<uint32_t> void_types, out(words.begin(), words.begin() + 5), moved, body;
    bool in_functions = false;
    for (size_t at = 5; at < words.size();) {
        const uint32_t count = words[at] >> 16, opcode = words[at] & 0xffff;
        if (count == 0 || at + count > words.size()) return words;  // malformed: spirv-val said no already
        std::vector<uint32_t> inst(words.begin() + static_cast<long>(at), words.begin() + static_cast<long>(at + count));
        at += count;
        if (opcode == kOpTypeVoid && count >= 2) void_types.push_back(inst[1]);
        if (opcode == kOpFunction) in_functions = true;
        const bool undef = opcode == kOpUndef && count == 3 &&
                           std::find(void_types.begin(), void_types.end(), inst[1]) == void_types.end();
        if (undef) inst[0] = (count << 16) | kOpConstantNull;
        std::vector<uint32_t>& to = undef && in_functions ? moved : (in_functions ? body : out);
        to.insert(to.end(), inst.begin(), inst.end());
    }
    out.insert(out.end(), moved.begin(), moved.end());
    out.insert(out.end(), body.begin(), body.end());
    return out;
}

// TIME wraps (rendering/limits/time/time_rollover_secs, 3600 s by default). A phase TIME * speed
// stays continuous across the wrap when speed * 3600 is a whole number of turns, so the speed
// is rounded to the nearest multiple of 2*pi/3600 rad/s (a change below 0.0009 rad/s). Which param is
// that speed, the spec says (role = "angular_speed").
constexpr const char* kRollover = "3600.0";
constexpr const char* kTau = "6.28318530717959";


}  // namespace

GodotCompiler::GodotCompiler(std::vector<uint32_t> spirv, const Variant& variant, const godot::Options& options)
    : CompilerGLSL(without_undefined_values(std::move(spirv))), variant_(variant), options_(options) {}

std::string GodotCompiler::builtin_expression(const std::string& member) const {
    const bool screen = options_.mode == Mode::Screen;
    if (member == "outputSize") {
        // The node's size in pixels, whatever it is stretched to: UV changes by 1/size per pixel on an
        // axis-aligned node. Rounded, because a node covers whole pixels and the derivative carries
        // ~1e-5 relative error, enough to move samples across floor() edges (mask cells).
        return screen ? "(1.0 / SCREEN_PIXEL_SIZE)" : "round(1.0 / abs(vec2(dFdx(UV.x), dFdy(UV.y))))";
    }
    if (member == "sourceSize") return screen ? "(1.0 / SCREEN_PIXEL_SIZE)" : "(1.0 / TEXTURE_PIXEL_SIZE)";
    if (member == "time") {
        // The spec marks the speed the time feeds (role angular_speed); compile_godot() refused
        // variants with more than one, since one TIME expression can keep only one phase whole.
        for (const VariantParam& p : variant_.params) {
            if (p.spec->role != ParamRole::AngularSpeed) continue;
            const std::string speed = p.uniform ? p.spec->name : float_literal(std::get<double>(p.value));
            // hostTime, when the host sets it (crtforge_pipeline.gd does, every frame), is the time
            // already reduced exactly in double precision (shader_time()); left at -1, TIME with the
            // rounded speed. Sums, not mix(): each branch reaches the shader bit-exact.
            return fmt::format("(max({3}, 0.0) + (1.0 - step(0.0, {3})) * (TIME * (round({0} * {1} / {2}) * {2} / {1}) / {0}))",
                               speed, kRollover, kTau, kHostTime);
        }
        return "TIME";
    }
    // Godot has no frame counter: a uniform the host advances every frame (the exported scene's
    // script does).
    if (member == "frameCount") return "frameCount";
    return member;
}

std::string GodotCompiler::uniform_declaration(const VariantParam& p) const {
    const ParamSpec& s = *p.spec;
    std::string hint, type = glsl_type_for(s.type), value;
    if (s.type == ParamType::Float || s.type == ParamType::Int) {
        const double step = s.step.value_or(s.type == ParamType::Int ? 1.0 : (*s.max - *s.min) / 100.0);
        hint = s.type == ParamType::Int ? fmt::format(" : hint_range({}, {}, {})", static_cast<int64_t>(*s.min),
                                                      static_cast<int64_t>(*s.max), static_cast<int64_t>(step))
                                        : fmt::format(" : hint_range({}, {}, {})", float_literal(*s.min), float_literal(*s.max), float_literal(step));
        value = s.type == ParamType::Int ? std::to_string(std::get<int64_t>(p.value)) : float_literal(std::get<double>(p.value));
    } else if (s.type == ParamType::Color) {
        const Color& c = std::get<Color>(p.value);
        if (options_.godot_version >= 4) {
            hint = " : source_color";
            value = fmt::format("vec3({}, {}, {})", float_literal(c[0]), float_literal(c[1]), float_literal(c[2]));
        } else {  // Godot 3's hint_color is for vec4 only
            type = "vec4";
            hint = " : hint_color";
            value = fmt::format("vec4({}, {}, {}, 1.0)", float_literal(c[0]), float_literal(c[1]), float_literal(c[2]));
        }
    } else {
        value = value_to_string(p.value);
    }
    return fmt::format("uniform {} {}{} = {};", type, s.name, hint, value);
}

void GodotCompiler::prepare() {
    auto o = get_common_options();
    o.es = true;  // Godot's shading language is GLSL ES 3.0 flavoured
    o.version = 300;
    o.vulkan_semantics = false;
    o.fragment.default_float_precision = Options::Highp;
    set_common_options(o);

    // Before the builtins below take Godot's names (UV, COLOR) on purpose.
    detail::rename_reserved_words(*this);

    const bool screen = options_.mode == Mode::Screen;
    auto resources = get_shader_resources();
    // Declared by Godot itself (or by emit_header): hide them and use Godot's names.
    for (const auto& in : resources.stage_inputs) {
        set_remapped_variable_state(in.id, true);
        // Godot 3's SCREEN_UV (and SCREEN_TEXTURE) count rows from the bottom; the effects count
        // them from the top, as UV and Godot 4's SCREEN_UV do (crt_flip_y below).
        set_name(in.id, !screen ? "UV" : options_.godot_version >= 4 ? "SCREEN_UV" : "crt_flip_y(SCREEN_UV)");
    }
    for (const auto& out : resources.stage_outputs) {
        set_remapped_variable_state(out.id, true);
        set_name(out.id, "COLOR");
    }
    // The main input becomes the node's TEXTURE or the screen; any other texture keeps its name
    // and emit_header() declares it as a Godot uniform with its sampling hints.
    for (const auto& img : resources.sampled_images) {
        set_remapped_variable_state(img.id, true);
        if (get_name(img.id) == kSourceTextureName)
            set_name(img.id, !screen ? "TEXTURE" : options_.godot_version >= 4 ? "screen_texture" : "SCREEN_TEXTURE");
    }
    // The uniform block disappears: each member becomes a plain `uniform` (emit_header) or a Godot
    // builtin expression. SPIRV-Cross writes member accesses as <block>.<member>; the block gets a
    // reserved name so compile_godot() can resolve those accesses exactly.
    for (const auto& ub : resources.uniform_buffers) {
        set_remapped_variable_state(ub.id, true);
        set_name(ub.id, kBlockMarker);
        const auto& type = get_type(ub.base_type_id);
        for (uint32_t i = 0; i < type.member_types.size(); ++i) {
            const std::string name = get_member_name(ub.base_type_id, i);
            Builtin builtin{};
            std::string expr = parse_builtin(name, builtin) ? builtin_expression(name) : name;
            for (const VariantParam& p : variant_.params) {
                if (p.spec->name != name) continue;
                if (p.spec->type == ParamType::Color && options_.godot_version < 4) expr = name + ".rgb";
                // SPIR-V holds a bool uniform as a uint; Godot's uniform is a bool (a checkbox in
                // the inspector). compile_godot() turns SPIRV-Cross's `x != 0u` back into `x`; any
                // other use gets the uint it stood for (Godot 3 has no uint(bool): it refuses that).
                if (p.spec->type == ParamType::Bool) {
                    expr = "uint(" + name + ")";
                    bool_members_.push_back(name);
                }
            }
            member_expressions_[name] = expr;
        }
    }
}

std::string GodotCompiler::compile_godot() {
    prepare();
    std::string text = detail::shorten_float_literals(compile());
    for (const std::string& name : bool_members_) {
        const std::string test = std::string(kBlockMarker) + "." + name + " != 0u";
        for (size_t at = text.find(test); at != std::string::npos; at = text.find(test, at + name.size()))
            text.replace(at, test.size(), name);
    }
    std::string out = detail::replace_block_access(text, kBlockMarker, [&](const std::string& member) {
        auto found = member_expressions_.find(member);
        if (found == member_expressions_.end()) throw spirv_cross::CompilerError("unknown uniform member " + member);
        return found->second;
    });
    if (out.find(kBlockMarker) != std::string::npos) throw spirv_cross::CompilerError("unresolved uniform block access");
    if (screen_mode() && variant_.writes_alpha()) {
        // The screen shader replaces what is on screen: a transparent bezel would show the
        // unprocessed picture below, so its alpha is composited over black here.
        const size_t close = out.rfind('}');
        if (close == std::string::npos) throw spirv_cross::CompilerError("no fragment() body to close");
        out.insert(close, "    COLOR = vec4(COLOR.rgb * COLOR.a, 1.0);  // screen mode: the bezel's alpha over black\n");
    }
    if (options_.godot_version >= 4) return out;
    if (screen_mode()) out = with_screen_reads_flipped(out);
    return with_loop_increments(out);
}

std::string GodotCompiler::with_screen_reads_flipped(const std::string& text) {
    // texture(SCREEN_TEXTURE, p) -> textureLod(SCREEN_TEXTURE, crt_flip_y(p), 0.0) and
    // textureLod(SCREEN_TEXTURE, p, lod) -> textureLod(SCREEN_TEXTURE, crt_flip_y(p), lod): the
    // effects' top-down coordinates back to the bottom-up ones Godot 3's screen texture is read
    // with, and its full-resolution level: SCREEN_TEXTURE has mipmaps, and a coordinate quantised
    // per mask cell (or bent by the barrel) would otherwise pick a blurred level where its
    // derivatives jump. Any other read of the screen is refused.
    static const std::regex read(R"(\b(\w+)\(SCREEN_TEXTURE, )");
    std::string out;
    size_t last = 0;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), read); it != std::sregex_iterator(); ++it) {
        const size_t at = static_cast<size_t>(it->position());
        if (at < last) continue;  // inside a coordinate already rewritten
        const std::string function = (*it)[1].str();
        if (function != "texture" && function != "textureLod")
            throw spirv_cross::CompilerError("Godot 3's screen mode cannot flip a " + function + " of SCREEN_TEXTURE");
        const size_t arg = at + static_cast<size_t>(it->length());
        int depth = 0;
        size_t end = arg;  // the end of the coordinate: the ',' or ')' that closes it
        for (; end < text.size(); ++end) {
            if (text[end] == '(') ++depth;
            if ((text[end] == ')' || text[end] == ',') && depth == 0) break;
            if (text[end] == ')') --depth;
        }
        if (end >= text.size()) throw spirv_cross::CompilerError("unbalanced screen texture read");
        if (function == "texture" && text[end] != ')') throw spirv_cross::CompilerError("a biased screen texture read");
        out.append(text, last, at - last);
        out += "textureLod(SCREEN_TEXTURE, crt_flip_y(" + text.substr(arg, end - arg) + ")" + (function == "texture" ? ", 0.0" : "");
        last = end;
    }
    out.append(text, last, std::string::npos);
    return out;
}

std::string GodotCompiler::with_loop_increments(const std::string& text) {
    // Godot 3's parser wants an expression after a for loop's second ';' ("Expected expression,
    // found: QUESTION"), which SPIRV-Cross leaves out when the loop steps inside its body. An
    // increment of zero changes nothing: `x += 0` on the loop's own variable, or on a variable
    // declared for the purpose when the loop declares none.
    // SPIRV-Cross writes `for (;;)` for a loop it cannot put in for's three parts (one whose exit
    // test is not at its head). Godot 3.2.3 refuses that in some places ("Expected expression" at
    // atari-ntsc's cell-list loop, nested in an if) and takes it in others; with all three parts,
    // `true` the condition, it takes it everywhere.
    static const std::regex loop(R"(for \(([^;]*); ?([^;]*); ?\))");
    static const std::regex declared(R"(^(int|uint|float) (\w+))");
    std::string out;
    size_t last = 0;
    int spare = 0;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), loop); it != std::sregex_iterator(); ++it) {
        out.append(text, last, static_cast<size_t>(it->position()) - last);
        std::string init = (*it)[1].str(), step;
        std::smatch var;
        if (std::regex_search(init, var, declared)) {
            step = var[2].str() + (var[1] == "float" ? " += 0.0" : var[1] == "uint" ? " += 0u" : " += 0");
        } else if (init.empty()) {
            const std::string name = "crtforge_loop" + std::to_string(spare++);
            init = "int " + name + " = 0";
            step = name + " += 0";
        } else {
            throw spirv_cross::CompilerError("a for loop with no increment and an initialiser Godot 3 cannot extend: " + init);
        }
        const std::string condition = (*it)[2].str().empty() ? std::string("true") : (*it)[2].str();
        out += "for (" + init + "; " + condition + "; " + step + ")";
        last = static_cast<size_t>(it->position() + it->length());
    }
    out.append(text, last, std::string::npos);
    return out;
}

void GodotCompiler::emit_header() {
    const Preset& preset = *variant_.preset;
    const bool screen = options_.mode == Mode::Screen;
    statement("// crtforge ", CRTFORGE_VERSION, ": preset ", preset.name, ". ", inert_comment(preset.doc));
    statement("// Godot ", options_.godot_version, " canvas_item. Generated from SPIR-V: edit the crtforge templates, not this file.");
    if (screen) {
        statement("// Screen mode: put it on a ColorRect covering the screen; it post-processes what is drawn below.");
    } else {
        const bool linear = variant_.texture_filter("source") == Filter::Linear;
        if (options_.godot_version >= 4) {
            statement("// Node mode: put it on the node showing the picture (TextureRect, Sprite2D, a SubViewport's texture);");
            statement("// set the node's texture_filter to ", linear ? "Linear" : "Nearest", ".");
        } else {
            statement("// Node mode: put it on the node showing the picture (TextureRect, Sprite, a Viewport's texture);");
            statement("// turn the texture's Filter flag ", linear ? "on" : "off", " (Import dock, or Texture.flags).");
            // dFdx gives the node's size in pixels; GLES2 has no derivatives and would show the raw picture.
            statement("// Needs the GLES3 renderer: it reads dFdx, which GLES2 lacks (Godot then shows the raw picture).");
        }
    }
    bool uses_time = false;
    for (Builtin b : variant_.builtins) uses_time = uses_time || b == Builtin::Time;
    if (uses_time) {
        if (const VariantParam* speed = variant_.angular_speed()) {
            statement("// Time: crtforge_pipeline.gd (the exported scene) sets ", kHostTime, " every frame to the exact phase time,");
            statement("// seconds reduced modulo 2*pi/", speed->spec->name, " in double precision. Without it (", kHostTime, " < 0) the shader");
            statement("// uses TIME, which wraps at rendering/limits/time/time_rollover_secs (3600 s by default): then ", speed->spec->name, " is");
            statement("// rounded to a multiple of 2*pi/3600 rad/s so the motion stays continuous across the wrap, and the");
            statement("// phase drifts from the exact one by up to t * pi/3600 rad at t seconds.");
        } else {
            statement("// TIME wraps at rendering/limits/time/time_rollover_secs (3600 s by default).");
        }
    }
    statement("shader_type canvas_item;");
    // A pass before the last writes data for the next pass, not a picture to composite: its
    // alpha (a transparent bezel) must not blend its colour away.
    if (variant_.writes_alpha() && variant_.pass_index + 1 < variant_.preset->passes.size())
        statement("render_mode blend_disabled;");
    statement("");
    if (screen && options_.godot_version < 4) {
        statement("// Godot 3's SCREEN_UV and SCREEN_TEXTURE count rows from the bottom of the screen.");
        statement("vec2 crt_flip_y(vec2 p) { return vec2(p.x, 1.0 - p.y); }");
        statement("");
    }
    if (screen && options_.godot_version >= 4)
        statement("uniform sampler2D screen_texture : hint_screen_texture, filter_", filter_name(variant_.texture_filter("source")), ", repeat_disable;");
    // Godot 4 folds each stage's params under its own heading in the inspector.
    const StageSpec* group = nullptr;
    for (const VariantParam* p : variant_.uniforms()) {
        if (options_.godot_version >= 4 && p->stage != group) {
            group = p->stage;
            statement("group_uniforms ", group->name, ";");
        }
        statement("// ", p->stage->name, ": ", inert_comment(p->spec->doc), p->spec->unit.empty() ? "" : " (" + inert_comment(p->spec->unit) + ")");
        statement(uniform_declaration(*p));
    }
    if (group) statement("group_uniforms;");
    if (uses_time && variant_.angular_speed()) {
        statement("// Seconds reduced exactly by the host (crtforge_pipeline.gd); negative: use TIME.");
        statement("uniform float ", kHostTime, " = -1.0;");
    }
    for (Builtin b : variant_.builtins)
        if (b == Builtin::FrameCount) {
            statement("// Frames since the first, set every frame by the host (crtforge_pipeline.gd does it).");
            statement("uniform int frameCount = 0;");
        }
    for (const std::string& texture : variant_.textures) {
        const PassInput* input = variant_.pass->find_input(texture);
        statement("// ", texture, ": ", input ? input->from.str() : std::string("set by the host"),
                  options_.godot_version >= 4 ? "" : " (set its filter and repeat flags on the texture)");
        if (options_.godot_version >= 4)
            statement("uniform sampler2D ", texture, " : filter_", filter_name(variant_.texture_filter(texture)),
                      input && input->wrap == Wrap::Repeat ? ", repeat_enable;" : ", repeat_disable;");
        else
            statement("uniform sampler2D ", texture, ";");
    }
    statement("");
}

void GodotCompiler::emit_function_prototype(spirv_cross::SPIRFunction& func, const spirv_cross::Bitset& return_flags) {
    if (func.self == ir.default_entry_point) {
        statement("void fragment()");
        return;
    }
    CompilerGLSL::emit_function_prototype(func, return_flags);
}

}  // namespace crtforge::godot
