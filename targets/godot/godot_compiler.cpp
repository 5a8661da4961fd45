#include "targets/godot/godot_compiler.hpp"
#include "targets/godot/godot3_syntax.hpp"
#include "targets/godot/godot_scene.hpp"
#include "generator/spirv_words.hpp"
#include "targets/godot/spirv_constant_indices.hpp"
#include "targets/godot/spirv_square_matrices.hpp"
#include "targets/spirv_flat_arrays.hpp"
#include "targets/spirv_split_io_structs.hpp"
#include "targets/spirv_gather_lowering.hpp"
#include "targets/float_literals.hpp"
#include "targets/word_scan.hpp"
#include "crtforge/inert_text.hpp"

#include <algorithm>
#include <functional>
#include <map>
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

// Every call of `function` in `text`, its top-level arguments handed to `rewrite`, which returns
// the replacement of the whole call.
std::string rewrite_calls(const std::string& text, const std::string& function,
                          const std::function<std::string(const std::vector<std::string>&)>& rewrite) {
    // A plain scan, not std::regex: this runs over every pass's whole text several times (and on
    // each argument again for the border emulation), where a regex cost a third of an export.
    const std::string call = function + "(";
    std::string out;
    size_t last = 0;
    for (size_t at = text.find(call); at != std::string::npos; at = text.find(call, at + 1)) {
        if (at < last || (at > 0 && detail::is_identifier_char(text[at - 1]))) continue;
        std::vector<std::string> args(1);
        int depth = 0;
        size_t end = at + call.size();
        for (; end < text.size(); ++end) {
            const char c = text[end];
            if (depth == 0 && c == ')') break;
            if (depth == 0 && c == ',') {
                args.emplace_back();
                continue;
            }
            if (c == '(' || c == '[') ++depth;
            if (c == ')' || c == ']') --depth;
            args.back() += c;
        }
        if (end >= text.size()) throw spirv_cross::CompilerError("unbalanced call of " + function);
        for (std::string& a : args) a.erase(0, std::min(a.size(), a.find_first_not_of(' ')));
        out.append(text, last, at - last);
        out += rewrite(args);
        last = end + 1;
    }
    out.append(text, last, std::string::npos);
    return out;
}

// Godot's shading language has no texel-offset variants of texture reads: the offset, in texels
// of level 0, moves the coordinate instead (the same texel for reads of level 0).
std::string without_texel_offsets(std::string text) {
    auto moved = [](const std::vector<std::string>& a, size_t offset) {
        return "(" + a[1] + ") + vec2(" + a[offset] + ") / vec2(textureSize(" + a[0] + ", 0))";
    };
    auto need = [](const std::vector<std::string>& a, size_t n, const char* f) {
        if (a.size() != n) throw spirv_cross::CompilerError(std::string("an unexpected ") + f + " call");
    };
    text = rewrite_calls(text, "textureOffset", [&](const std::vector<std::string>& a) {
        if (a.size() != 3 && a.size() != 4) throw spirv_cross::CompilerError("an unexpected textureOffset call");
        return "texture(" + a[0] + ", " + moved(a, 2) + (a.size() == 4 ? ", " + a[3] : "") + ")";
    });
    text = rewrite_calls(text, "textureLodOffset", [&](const std::vector<std::string>& a) {
        need(a, 4, "textureLodOffset");
        return "textureLod(" + a[0] + ", " + moved(a, 3) + ", " + a[2] + ")";  // (s, P, lod, offset)
    });
    text = rewrite_calls(text, "texelFetchOffset", [&](const std::vector<std::string>& a) {
        need(a, 4, "texelFetchOffset");
        return "texelFetch(" + a[0] + ", (" + a[1] + ") + (" + a[3] + "), " + a[2] + ")";  // (s, P, lod, offset)
    });
    return text;
}

// Godot parses a `for` condition as a statement, so one that starts with a type constructor
// (`float(n) < w`, as SPIRV-Cross prints an int counter compared with a float) reads as a
// declaration and is refused ("Expected an identifier or '[' after type"). In parentheses it is
// an expression.
std::string with_for_conditions_parenthesised(std::string text) {
    static const std::regex kTypeCall(R"(^\s*(float|int|uint|bool|[biu]?vec[234]|mat[234])\s*\()");
    for (size_t at = text.find("for ("); at != std::string::npos; at = text.find("for (", at + 5)) {
        if (at > 0 && (std::isalnum(static_cast<unsigned char>(text[at - 1])) || text[at - 1] == '_')) continue;
        // The condition: between the first and the second `;` outside parentheses.
        size_t begin = std::string::npos, end = std::string::npos;
        int depth = 0;
        for (size_t i = at + 5; i < text.size() && end == std::string::npos; ++i) {
            const char c = text[i];
            if (c == '(') ++depth;
            else if (c == ')' && depth-- == 0) break;
            else if (c == ';' && depth == 0) (begin == std::string::npos ? begin : end) = i;
        }
        if (end == std::string::npos) continue;
        const std::string condition = text.substr(begin + 1, end - begin - 1);
        if (!std::regex_search(condition, kTypeCall)) continue;
        const size_t first = condition.find_first_not_of(' ');
        text.replace(begin + 1, end - begin - 1, condition.substr(0, first) + "(" + condition.substr(first) + ")");
    }
    return text;
}

// TIME wraps (rendering/limits/time/time_rollover_secs, 3600 s by default). A phase TIME * speed
// stays continuous across the wrap when speed * 3600 is a whole number of turns, so the speed
// is rounded to the nearest multiple of 2*pi/3600 rad/s (a change below 0.0009 rad/s). Which param is
// that speed, the spec says (role = "angular_speed").
constexpr const char* kRollover = "3600.0";
constexpr const char* kTau = "6.28318530717959";


}  // namespace

std::vector<uint32_t> in_godot_types(std::vector<uint32_t> words, int godot_version) {
    detail::split_interface_structs(words);  // Godot's varyings are single values
    detail::flatten_arrays_of_arrays(words);
    square_matrices(words);
    detail::lower_texture_gathers(words);  // Godot's language has no textureGather with a component
    if (godot_version < 4) with_loops_unrolled_for_constant_indices(words);  // Godot 3 indexes by constants only
    return words;
}

GodotCompiler::GodotCompiler(std::vector<uint32_t> spirv, const Variant& variant, const godot::Options& options,
                             ShaderStage stage, std::vector<Varying> varyings)
    : CompilerGLSL(without_undefined_values(std::move(spirv))), variant_(variant), options_(options), stage_(stage),
      program_(variant.program_form() != nullptr), varyings_(std::move(varyings)) {}

std::string GodotCompiler::builtin_expression_fragment_size() const {
    // The node's size in pixels, whatever it is stretched to: UV changes by 1/size per pixel on an
    // axis-aligned node. Rounded, because a node covers whole pixels and the derivative carries
    // ~1e-5 relative error, enough to move samples across floor() edges (mask cells).
    return screen_mode() ? "round(1.0 / SCREEN_PIXEL_SIZE)" : "round(1.0 / abs(vec2(dFdx(UV.x), dFdy(UV.y))))";
}

std::string GodotCompiler::builtin_expression(const std::string& member) const {
    const bool screen = options_.mode == Mode::Screen;
    // A program pass's sizes come from the host (crtforge_pipeline.gd sets them); a vertex stage
    // has no derivatives to find them by. Unset (0), the node's own estimate stands in.
    if (program_ && (member == "outputSize" || member == "viewportSize")) {
        const std::string fallback = stage_ == ShaderStage::Vertex ? (screen ? "vec2(1.0)" : "round(1.0 / TEXTURE_PIXEL_SIZE)")
                                                                    : builtin_expression_fragment_size();
        return "(" + member + ".x > 0.0 ? " + member + " : " + fallback + ")";
    }
    // Godot's GLES3 vertex stage cannot size the screen texture: the screen's size stands in.
    if (member == "sourceSize" && stage_ == ShaderStage::Vertex && screen)
        return "(viewportSize.x > 0.0 ? viewportSize : vec2(1.0))";
    if (member == "outputSize") return builtin_expression_fragment_size();
    // A size in whole pixels: the reciprocal of 1 / 240 in 32 bits is 239.99998, and yo6's
    // round((233.0 - SourceSize.y) / 2.0) then moved its picture a row (-3 for RetroArch's -4).
    if (member == "sourceSize") return screen ? "round(1.0 / SCREEN_PIXEL_SIZE)" : "round(1.0 / TEXTURE_PIXEL_SIZE)";
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
    check_one_pixel_pass();
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
    if (stage_ == ShaderStage::Vertex) {
        // A program's vertex stage: RetroArch's quad corner comes from UV (vertex_text()), so it
        // reads no attributes; each output becomes a varying the fragment stage reads by location.
        if (!resources.stage_inputs.empty())
            throw spirv_cross::CompilerError("the vertex stage reads vertex attributes, which a canvas_item has not");
        varyings_.clear();
        for (const auto& out : resources.stage_outputs) {
            if (!has_decoration(out.id, spv::DecorationLocation))
                throw spirv_cross::CompilerError("a vertex output without a location");
            Varying v;
            v.location = get_decoration(out.id, spv::DecorationLocation);
            v.name = get_name(out.id).empty() ? "crt_varying_" + std::to_string(v.location) : get_name(out.id);
            set_name(out.id, v.name);
            set_remapped_variable_state(out.id, true);
            const spirv_cross::SPIRType& type = get_type(out.type_id);
            const bool integer = type.basetype == spirv_cross::SPIRType::Int || type.basetype == spirv_cross::SPIRType::UInt;
            const bool flat = has_decoration(out.id, spv::DecorationFlat) || type.basetype != spirv_cross::SPIRType::Float;
            v.declaration = "varying " + std::string(flat ? "flat " : "") + variable_decl(type, v.name, out.id) + ";";
            if (integer && options_.godot_version < 4) {
                if (!type.array.empty() || type.columns > 1)
                    throw spirv_cross::CompilerError("Godot 3 has no integer varyings, and an array of them (" + v.name + ") has no float carrier");
                v.integer_type = type_to_glsl(type);
                v.carrier_type = type.vecsize == 1 ? "float" : "vec" + std::to_string(type.vecsize);
                v.declaration = "varying flat " + v.carrier_type + " " + v.carrier() + ";";
            }
            varyings_.push_back(std::move(v));
        }
        if (hands_on_corner_) {  // after the shader's own, at no location of theirs
            Varying v;
            v.location = UINT32_MAX;
            v.name = kCornerVarying;
            v.declaration = std::string("varying vec2 ") + kCornerVarying + ";";  // where the clip position put the pixel, 0..1
            varyings_.push_back(std::move(v));
        }
    }
    // Declared by Godot itself (or by emit_header): hide them and use Godot's names.
    for (const auto& in : resources.stage_inputs) {
        if (stage_ == ShaderStage::Vertex) break;
        set_remapped_variable_state(in.id, true);
        if (program_) {  // a varying the vertex stage writes at the same location
            const uint32_t location = get_decoration(in.id, spv::DecorationLocation);
            auto v = std::find_if(varyings_.begin(), varyings_.end(), [&](const Varying& x) { return x.location == location; });
            if (v == varyings_.end())
                throw spirv_cross::CompilerError("the fragment stage reads location " + std::to_string(location) +
                                                 ", which the vertex stage does not write");
            set_name(in.id, v->name);
            continue;
        }
        // Godot 3's SCREEN_UV (and SCREEN_TEXTURE) count rows from the bottom; the effects count
        // them from the top, as UV and Godot 4's SCREEN_UV do (crt_flip_y below).
        set_name(in.id, !screen ? "UV" : options_.godot_version >= 4 ? "SCREEN_UV" : "crt_flip_y(SCREEN_UV)");
    }
    for (const auto& out : resources.stage_outputs) {
        if (stage_ == ShaderStage::Vertex) break;
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
    std::string text = detail::without_splat_selects(detail::shorten_float_literals(compile()));
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
    if (stage_ == ShaderStage::Fragment) out = with_format_stored(out);
    out = with_one_pixel_sizes(with_for_conditions_parenthesised(with_border_emulated(without_texel_offsets(out))));
    // Godot's matrices are square: matNxN is matN; a non-square one was padded to square in the
    // SPIR-V (spirv_square_matrices), so one here is a bug, refused rather than emitted.
    auto dimension = [](char c) { return c >= '2' && c <= '4'; };
    out = crtforge::detail::rewrite_words(out, [&](std::string_view word) -> std::optional<std::string> {
        if (word.size() != 6 || word.substr(0, 3) != "mat" || !dimension(word[3]) || word[4] != 'x' || !dimension(word[5])) return std::nullopt;
        if (word[3] != word[5]) throw spirv_cross::CompilerError("Godot has no non-square matrix type (" + std::string(word) + ")");
        return std::string(word.substr(0, 4));
    });
    if (stage_ == ShaderStage::Vertex) out = vertex_text(out);
    if (options_.godot_version >= 4) return out;
    out = with_integer_varyings_carried(out);
    if (screen_mode()) out = with_screen_reads_flipped(out);
    return godot3::with_godot3_syntax(out);
}

std::map<std::string, bool> GodotCompiler::border_textures() const {
    std::map<std::string, bool> out;
    for (const auto& [binding, linear] : variant_.clamp_to_border_inputs()) {
        if (binding != kSourceTextureName) out[binding] = linear;
        else if (!screen_mode()) out["TEXTURE"] = linear;  // the screen has nothing outside it to read
    }
    return out;
}

// The pass's format_reduction where fragment() ends; the screen's pass draws the display, whose
// format is the host's.
std::string GodotCompiler::with_format_stored(std::string text) const {
    if (screen_mode() || variant_.pass_index + 1 >= variant_.preset->passes.size()) return text;
    const std::string line = format_reduction(variant_.pass->format);
    if (line.empty()) return text;
    const std::string entry = "void fragment()\n{\n";
    const size_t body = text.find(entry);
    const size_t close = body == std::string::npos ? body : text.find("\n}", body);
    if (close == std::string::npos) throw spirv_cross::CompilerError("no end of fragment() to store the pass's format at");
    if (text.substr(body, close - body).find("return;") != std::string::npos) {
        // sRGB's rounding only moves values by less than a code: such a pass keeps its half floats.
        if (variant_.pass->format == PixelFormat::Rgba8Srgb) return text;
        throw spirv_cross::CompilerError(fmt::format("a fragment stage that returns early cannot store its {} output in Godot",
                                                     pixel_format_name(variant_.pass->format)));
    }
    text.insert(close + 1, "    " + line + "\n");
    return text;
}

std::string GodotCompiler::with_border_emulated(const std::string& text) const {
    // Godot has no border colour (its samplers clamp to the edge): a texture the pass reads
    // clamp_to_border has each read multiplied by the share of its footprint inside the texture,
    // exact for nearest, and for linear at level 0 (as the WGSL emitter does).
    const std::map<std::string, bool> border = border_textures();
    if (border.empty()) return text;
    std::function<std::string(const std::string&)> rewrite = [&](const std::string& source) {
        std::string out = source;
        for (const std::string function : {"texture", "textureLod", "textureGrad"})
            out = rewrite_calls(out, function, [&](const std::vector<std::string>& args) {
                std::string call = function + "(";
                for (size_t i = 0; i < args.size(); ++i) call += (i ? ", " : "") + rewrite(args[i]);
                call += ")";
                auto b = border.find(args[0]);
                if (b == border.end() || args.size() < 2) return call;
                const std::string uv = rewrite(args[1]);
                return "(" + call + " * " +
                       (b->second ? "crt_border_linear(" + uv + ", vec2(textureSize(" + args[0] + ", 0)))" : "crt_border_nearest(" + uv + ")") + ")";
            });
        return out;
    };
    return rewrite(text);
}

std::string GodotCompiler::with_one_pixel_sizes(const std::string& text) const {
    std::map<std::string, godot::OnePixelAxes> thin;  // Godot name -> the axes its pass is 1 pixel on
    for (const PassInput& in : variant_.pass->inputs) {
        const godot::OnePixelAxes axes = godot::one_pixel_axes(*variant_.preset, in.from);
        if (!axes.any()) continue;
        if (in.binding != kSourceTextureName) thin[in.binding] = axes;
        else if (!screen_mode()) thin["TEXTURE"] = axes;  // the screen is the display's size
    }
    if (thin.empty()) return text;
    auto sized = [](const godot::OnePixelAxes& axes, const std::string& size, const std::string& one, const std::string& type) {
        if (axes.x && axes.y) return type + "(" + one + ")";
        return axes.x ? type + "(" + one + ", " + size + ".y)" : type + "(" + size + ".x, " + one + ")";
    };
    std::function<std::string(const std::string&)> rewrite = [&](const std::string& source) {
        return rewrite_calls(source, "textureSize", [&](const std::vector<std::string>& args) {
            std::string call = "textureSize(";
            for (size_t i = 0; i < args.size(); ++i) call += (i ? ", " : "") + rewrite(args[i]);
            call += ")";
            auto t = thin.find(args[0]);
            return t == thin.end() ? call : sized(t->second, call, "1", "ivec2");  // 1 at every level
        });
    };
    std::string out = rewrite(text);
    if (auto t = thin.find("TEXTURE"); t != thin.end())
        out = crtforge::detail::rewrite_words(out, [&](std::string_view word) -> std::optional<std::string> {
            if (word != "TEXTURE_PIXEL_SIZE") return std::nullopt;
            return sized(t->second, "TEXTURE_PIXEL_SIZE", "1.0", "vec2");
        });
    return out;
}

void GodotCompiler::check_one_pixel_pass() const {
    const godot::OnePixelAxes thin = godot::one_pixel_axes(*variant_.preset, variant_.pass_index);
    // A pass of crtforge's own shaders so sized is refused by the scene (godot_scene.cpp).
    if (!program_ || !thin.any() || stage_ != ShaderStage::Fragment) return;
    const std::string what = fmt::format("pass {} is 1 pixel {}, which Godot draws as 2 equal pixels", variant_.pass->alias,
                                         thin.x ? "wide" : "tall");
    // Derivatives across the two pixels are 0 where RetroArch's helper pixel gives the slope, and
    // an implicit level of a mip chain follows them.
    const auto instructions = detail::spirv_instructions(ir.spirv);
    if (!instructions) throw spirv_cross::CompilerError(what + ", and its fragment stage does not parse");
    for (const detail::SpirvInstruction& in : *instructions)
        if (in.opcode >= spv::OpDPdx && in.opcode <= spv::OpFwidthCoarse)
            throw spirv_cross::CompilerError(what + ": its fragment stage reads derivatives, which would then be 0");
    for (const PassInput& in : variant_.pass->inputs)
        if (in.mipmap) throw spirv_cross::CompilerError(what + ": it reads " + in.binding + " through a mip chain, whose level would follow 0 derivatives");
}

std::string GodotCompiler::vertex_text(std::string text) const {
    // SPIRV-Cross names values by their ids, which the fragment stage's compile reuses: the vertex
    // stage's become _v<id>.
    text = crtforge::detail::rewrite_words(text, [](std::string_view word) -> std::optional<std::string> {
        const bool id = word.size() > 1 && word[0] == '_' && word.find_first_not_of("0123456789", 1) == std::string_view::npos;
        if (!id) return std::nullopt;
        return "_v" + std::string(word.substr(1));
    });
    // The import draws RetroArch's quad as a full-screen triangle, its corner from gl_VertexIndex
    // (generator/retroarch/slang_program.cpp); a canvas_item's own quad has that corner as UV.
    // A pass drawn 2 pixels for 1 (godot::one_pixel_axes) holds that axis at the pixel's centre.
    const godot::OnePixelAxes thin = godot::one_pixel_axes(*variant_.preset, variant_.pass_index);
    for (const auto& [corner, uv] : {std::pair<std::string, std::string>{"float((gl_VertexID << 1) & 2)", thin.x ? "0.5" : "UV.x"},
                                     {"float(gl_VertexID & 2)", thin.y ? "0.5" : "UV.y"}})
        for (size_t at = text.find(corner); at != std::string::npos; at = text.find(corner, at + uv.size()))
            text.replace(at, corner.size(), uv);
    if (text.find("gl_VertexID") != std::string::npos)
        throw spirv_cross::CompilerError("the vertex stage reads gl_VertexIndex other than as RetroArch's quad corner");
    const std::string entry = "void vertex()\n{\n";
    const size_t body = text.find(entry);
    if (body == std::string::npos) throw spirv_cross::CompilerError("no vertex() in the vertex stage");
    text.insert(body + entry.size(), "    vec4 crt_position;  // the shader's clip position\n");
    if (screen_mode()) return text;  // the user's node, placed by the user: its own quad
    // RetroArch draws the quad where the shader's clip position puts it (newpixie-mini turns it
    // upside down, metacrt's bufC mirrors it). In the pipeline the host gives the pass's size and
    // the pass's node fills its viewport at the origin, so each corner moves by the clip
    // position's offset from the node's own: nothing where the shader leaves the quad alone (its
    // corners land on exactly 0 and 1). A node of the user's own (no size set) keeps its quad, and
    // an axis drawn 2 pixels for 1 keeps the node's.
    std::string moved;
    if (hands_on_corner_) moved += std::string("    ") + kCornerVarying + " = UV;\n";
    moved += "    if (outputSize.x > 0.0) {\n"
             "        vec2 crt_moved = crt_position.xy / crt_position.w * 0.5 + vec2(0.5);\n";
    for (const auto& [axis, held] : {std::pair<char, bool>{'x', thin.x}, {'y', thin.y}}) {
        if (held) continue;
        moved += fmt::format("        VERTEX.{0} += (crt_moved.{0} - UV.{0}) * outputSize.{0};\n", axis);
        if (hands_on_corner_) moved += fmt::format("        {0}.{1} = crt_moved.{1};\n", kCornerVarying, axis);
    }
    moved += "    }\n";
    return with_vertex_end(std::move(text), body, moved, "have its clip position placed in Godot");
}

std::string GodotCompiler::with_vertex_end(std::string text, size_t body, const std::string& statements, const std::string& what) {
    // Where vertex() ends: its closing brace, the first at the start of a line. Statements there
    // run last only if no return leaves earlier.
    const size_t close = text.find("\n}", body);
    if (close == std::string::npos) throw spirv_cross::CompilerError("no end of vertex()");
    if (text.substr(body, close - body).find("return;") != std::string::npos)
        throw spirv_cross::CompilerError("a vertex stage that returns early cannot " + what);
    text.insert(close + 1, statements);
    return text;
}

std::string GodotCompiler::with_integer_varyings_carried(std::string text) const {
    std::string locals, stores;
    for (const Varying& v : varyings_) {
        if (v.integer_type.empty()) continue;
        if (stage_ == ShaderStage::Vertex) {
            locals += "    " + v.integer_type + " " + v.name + ";\n";
            stores += "    " + v.carrier() + " = " + v.carrier_type + "(" + v.name + ");\n";
        } else {
            locals += "    " + v.integer_type + " " + v.name + " = " + v.integer_type + "(" + v.carrier() + ");\n";
        }
    }
    if (locals.empty()) return text;
    const std::string entry = stage_ == ShaderStage::Vertex ? "void vertex()\n{\n" : "void fragment()\n{\n";
    const size_t body = text.find(entry);
    if (body == std::string::npos) throw spirv_cross::CompilerError("no " + entry.substr(5, entry.find('(') - 5) + "() to carry integer varyings in");
    if (stage_ == ShaderStage::Vertex) {
        text = with_vertex_end(std::move(text), body, stores, "carry its integer varyings in Godot 3");
    }
    text.insert(body + entry.size(), locals);
    return text;
}

std::string GodotCompiler::builtin_to_glsl(spv::BuiltIn builtin, spv::StorageClass storage) {
    switch (builtin) {
        // Vulkan's gl_FragCoord: pixel centres at +0.5 from the top-left. FRAGCOORD (and SCREEN_UV)
        // count rows from the bottom in the Compatibility renderer's SubViewports and from the top in
        // Forward+'s; the node's UV is top-down in both, and the pass's node fills its viewport.
        // The interpolated UV * size lands an ulp either side of the centre, which a shader's
        // floor(gl_FragCoord.x - 0.5) (a mask's column) turns into a whole pixel: the centre is
        // rebuilt exactly, floor() + 0.5, as the rasteriser gives it.
        case spv::BuiltInFragCoord: {
            auto centre = [](const std::string& pixel) { return "vec4(floor(" + pixel + ") + vec2(0.5), FRAGCOORD.zw)"; };
            // Godot 3's SCREEN_UV counts rows from the bottom in every renderer (crt_flip_y: the header's).
            if (screen_mode() && options_.godot_version < 4) return centre("crt_flip_y(SCREEN_UV) / SCREEN_PIXEL_SIZE");
            if (screen_mode()) return centre("SCREEN_UV / SCREEN_PIXEL_SIZE");
            // A program's pixel: where its clip position put it (vertex_text()), the node's UV elsewhere.
            const bool moved = std::any_of(varyings_.begin(), varyings_.end(), [](const Varying& v) { return v.name == kCornerVarying; });
            return centre(std::string(moved ? kCornerVarying : "UV") + " * " + builtin_expression("outputSize"));
        }
        case spv::BuiltInPosition: return "crt_position";
        default: return CompilerGLSL::builtin_to_glsl(builtin, storage);
    }
}

std::string GodotCompiler::with_screen_reads_flipped(const std::string& source) {
    // texture(SCREEN_TEXTURE, p) -> textureLod(SCREEN_TEXTURE, crt_flip_y(p), 0.0) and
    // textureLod(SCREEN_TEXTURE, p, lod) -> textureLod(SCREEN_TEXTURE, crt_flip_y(p), lod): the
    // effects' top-down coordinates back to the bottom-up ones Godot 3's screen texture is read
    // with, and its full-resolution level: SCREEN_TEXTURE has mipmaps, and a coordinate quantised
    // per mask cell (or bent by the barrel) would otherwise pick a blurred level where its
    // derivatives jump (a bias is dropped: there is only the one level to read). texelFetch(
    // SCREEN_TEXTURE, p, lod) reads row size.y - 1 - p.y, written out in place (Godot 3's own
    // functions cannot see SCREEN_TEXTURE); textureSize needs no flip. Any other read of the
    // screen is refused.
    std::function<std::string(const std::string&)> flip_fetches = [&](const std::string& from) {
        return rewrite_calls(from, "texelFetch", [&](const std::vector<std::string>& a) {
            std::vector<std::string> args;
            for (const std::string& arg : a) args.push_back(flip_fetches(arg));
            if (args.size() == 3 && args[0] == "SCREEN_TEXTURE") {
                const std::string p = "(" + args[1] + ")";
                return "texelFetch(SCREEN_TEXTURE, ivec2(" + p + ".x, textureSize(SCREEN_TEXTURE, " + args[2] + ").y - 1 - " + p + ".y), " +
                       args[2] + ")";
            }
            std::string call = "texelFetch(";
            for (size_t i = 0; i < args.size(); ++i) call += (i ? ", " : "") + args[i];
            return call + ")";
        });
    };
    const std::string text = flip_fetches(source);
    static const std::regex read(R"(\b(\w+)\(SCREEN_TEXTURE, )");
    std::string out;
    size_t last = 0;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), read); it != std::sregex_iterator(); ++it) {
        const size_t at = static_cast<size_t>(it->position());
        if (at < last) continue;  // inside a coordinate already rewritten
        const std::string function = (*it)[1].str();
        if (function == "textureSize" || function == "texelFetch") continue;  // no flip / flipped above
        if (function != "texture" && function != "textureLod")
            throw spirv_cross::CompilerError("Godot 3's screen mode cannot flip a " + function + " of SCREEN_TEXTURE");
        // The end of the argument that starts at `from`: the ',' (when `comma` ends it) or ')' at
        // its own depth.
        auto argument_end = [&](size_t from, bool comma) {
            int depth = 0;
            for (size_t end = from; end < text.size(); ++end) {
                if ((text[end] == ')' || (comma && text[end] == ',')) && depth == 0) return end;
                if (text[end] == '(') ++depth;
                if (text[end] == ')') --depth;
            }
            throw spirv_cross::CompilerError("unbalanced screen texture read");
        };
        const size_t arg = at + static_cast<size_t>(it->length());
        const size_t end = argument_end(arg, true);  // the end of the coordinate
        out.append(text, last, at - last);
        out += "textureLod(SCREEN_TEXTURE, crt_flip_y(" + text.substr(arg, end - arg) + ")" + (function == "texture" ? ", 0.0" : "");
        // A bias (crt-lottes-fast's texture(Source, uv, -16.0), which asks for the sharpest level)
        // is dropped with its argument: the read is of level 0 like every other here, exactly
        // RetroArch's for an input without a mip chain, where a bias has nothing to choose from.
        last = function == "texture" && text[end] != ')' ? argument_end(end + 1, false) : end;
    }
    out.append(text, last, std::string::npos);
    return out;
}

void GodotCompiler::emit_header() {
    if (stage_ == ShaderStage::Vertex) return;  // the fragment stage's header declares everything
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
    // alpha (a transparent bezel, or a value a RetroArch pass keeps there) must not blend its
    // colour away.
    if ((variant_.writes_alpha() || program_) && variant_.pass_index + 1 < variant_.preset->passes.size())
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
    if (!border_textures().empty()) {
        statement("// clamp_to_border without a border colour (Godot's samplers clamp to the edge): the share of a");
        statement("// read's footprint inside the texture, which the reads are multiplied by.");
        // (Names of crtforge's own: Godot refuses a parameter that shares a global's name.)
        statement("float crt_border_linear(vec2 crt_uv, vec2 crt_size) {");
        statement("    vec2 crt_inside = clamp(min(crt_uv, vec2(1.0) - crt_uv) * crt_size + vec2(0.5), vec2(0.0), vec2(1.0));");
        statement("    return crt_inside.x * crt_inside.y;");
        statement("}");
        statement("float crt_border_nearest(vec2 crt_uv) {");
        statement("    return (crt_uv.x >= 0.0 && crt_uv.y >= 0.0 && crt_uv.x < 1.0 && crt_uv.y < 1.0) ? 1.0 : 0.0;");
        statement("}");
    }
    if (program_) {
        statement("// The pass's output size and the screen's, in pixels, set by the host (crtforge_pipeline.gd does it);");
        statement("// left at 0, the node's size stands in.");
        statement("uniform vec2 outputSize = vec2(0.0);");
        statement("uniform vec2 viewportSize = vec2(0.0);");
        statement("// What the vertex stage hands the fragment stage.");
        for (const Varying& v : varyings_) {
            if (!v.integer_type.empty())
                statement("// ", v.integer_type, " ", v.name, ": Godot 3 has no integer varyings; carried as ", v.carrier_type,
                          " (exact up to 2^24)");
            statement(v.declaration);
        }
    }
    for (const std::string& texture : variant_.textures) {
        const PassInput* input = variant_.pass->find_input(texture);
        statement("// ", texture, ": ", input ? input->from.str() : std::string("set by the host"),
                  options_.godot_version >= 4 ? "" : " (set its filter and repeat flags on the texture)");
        // A LUT read through a mip chain (the scene script makes one) blends its levels.
        const bool mipmap = input && input->mipmap && input->from.kind == TextureSource::Kind::Lut;
        if (options_.godot_version >= 4)
            statement("uniform sampler2D ", texture, " : filter_", filter_name(variant_.texture_filter(texture)), mipmap ? "_mipmap" : "",
                      input && input->wrap == Wrap::Repeat ? ", repeat_enable;" : ", repeat_disable;");
        else
            statement("uniform sampler2D ", texture, ";");
    }
    statement("");
}

void GodotCompiler::emit_function_prototype(spirv_cross::SPIRFunction& func, const spirv_cross::Bitset& return_flags) {
    if (func.self == ir.default_entry_point) {
        statement(stage_ == ShaderStage::Vertex ? "void vertex()" : "void fragment()");
        return;
    }
    CompilerGLSL::emit_function_prototype(func, return_flags);
}

}  // namespace crtforge::godot
