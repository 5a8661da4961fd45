// Proof that each target's text is accepted by the compiler its users will run.
#include <cstring>

#include <fmt/format.h>

#include "crtforge/dawn_engine.hpp"
#include "crtforge/target_render.hpp"
#include "targets/godot/godot_shim.hpp"

namespace crtforge {

Status consume_output(TargetId target, const OutputFile& f) {
    Status status = Ok{};
    switch (target) {
        case TargetId::Spirv: {
            if (f.data.size() % 4 != 0) return make_validation_error("SPIR-V file size is not a multiple of 4");
            SpirvBinary words(f.data.size() / 4);
            std::memcpy(words.data(), f.data.data(), f.data.size());
            status = validate_spirv(words);
            break;
        }
        case TargetId::Glsl450: status = check_glsl(f.data, f.stage, 450, false); break;
        case TargetId::Glsl330: status = check_glsl(f.data, f.stage, 330, false); break;
        case TargetId::GlslEs300: status = check_glsl(f.data, f.stage, 300, true); break;
        case TargetId::Hlsl50:
        case TargetId::Hlsl60: status = check_hlsl(f.data, f.stage, "main"); break;
        case TargetId::Godot4:
        case TargetId::Godot3: {
            if (!f.is_shader()) return Ok{};  // the material and the README are not code
            auto shim = godot::wrap_in_shim(f.data, target == TargetId::Godot4 ? 4 : 3);
            if (!shim.ok()) return shim.error();
            CompileOptions options;
            options.optimize = false;
            options.source_name = "<godot shader>";
            auto spirv = compile_to_spirv(shim.value().glsl, options);
            status = spirv.ok() ? Status(Ok{}) : Status(spirv.error());
            break;
        }
        case TargetId::Wgsl: {
            auto engine = shared_dawn_engine();
            if (!engine.ok()) return engine.error();
            auto messages = engine.value()->compile(f.data);
            if (!messages.ok()) return messages.error();
            // Zero errors and zero warnings: a warning in a user's browser console is a defect too.
            if (!messages.value().empty()) {
                const WgslMessage& m = messages.value().front();
                status = make_validation_error(fmt::format("Dawn {}: {} ({} message{})", m.type, m.text,
                                                           messages.value().size(), messages.value().size() == 1 ? "" : "s"),
                                               "<wgsl>", m.line);
            }
            break;
        }
    }
    if (status.ok()) return status;
    Diagnostic d = status.error();
    d.kind = ErrorKind::Validation;  // our output was rejected: a validation failure, not bad input
    return d;
}

}  // namespace crtforge
