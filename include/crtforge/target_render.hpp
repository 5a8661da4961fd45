// Renders a target's emitted shaders through the consumer that proves them:
//   spirv              -> the Vulkan engine (lavapipe by default)
//   glsl450 / glsl330  -> the OpenGL driver (Mesa, EGL surfaceless, core profile)
//   glsles300          -> the OpenGL ES driver (Mesa, EGL surfaceless)
//   hlsl50 / hlsl60    -> glslang's HLSL front end -> SPIR-V -> the Vulkan engine, with the D3D
//                         clip-space y convention emulated (rows flipped back)
#pragma once

#include <map>
#include <memory>
#include <string>

#include "crtforge/exporter.hpp"
#include "crtforge/image.hpp"
#include "crtforge/reflection.hpp"
#include "crtforge/render_engine.hpp"
#include "crtforge/uniforms.hpp"

namespace crtforge {

// Feeds one emitted file to the real consumer of its language, as a host would: SPIR-V through
// spirv-val, GLSL re-parsed by glslang in the matching desktop/ES profile, HLSL compiled by
// glslang's HLSL front end to SPIR-V (then spirv-val), WGSL compiled by Dawn, which must report
// no error and no warning. Failures are ErrorKind::Validation.
Status consume_output(TargetId target, const OutputFile& file);

class DawnEngine;
// The process's Dawn engine (one Node.js runner for every thread; its calls are serialised),
// started on first use. A failure to start is returned and retried on the next call.
Result<DawnEngine*> shared_dawn_engine();

struct TargetRenderRequest {
    const CompiledVariant* compiled = nullptr;
    TargetId target = TargetId::Spirv;
    const TargetOutput* output = nullptr;  // the emitted files of that target (required except for spirv)
    Image input;
    SamplerFilter filter = SamplerFilter::Linear;
    int width = 0, height = 0;
    double time = 0.0;
    OutputFormat format = OutputFormat::Rgba16Float;  // float output: no 8-bit quantisation in comparisons
    std::map<std::string, Value> overrides;
};

class GlEngine;

// Owns the engines, created on first use and reused.
class TargetRenderer {
public:
    explicit TargetRenderer(EngineOptions vulkan_options = {});
    ~TargetRenderer();
    Result<Image> render(const TargetRenderRequest& request);
    // One line naming the consumer used for a target (for reports).
    std::string consumer(TargetId target);

private:
    // The SPIR-V a consumer front end made of a target's text (HLSL, the Godot shim), compiled once
    // per distinct source: every golden of a preset renders the same shader.
    struct ConsumerModule {
        SpirvBinary spirv;
        Reflection reflection;
    };
    Result<const ConsumerModule*> consumer_module(const std::string& source, const CompileOptions& options);
    std::map<std::string, ConsumerModule> consumer_modules_;

    Result<RenderEngine*> vulkan();
    Result<GlEngine*> gl(bool es);
    EngineOptions vulkan_options_;
    std::unique_ptr<RenderEngine> vulkan_;
    std::unique_ptr<GlEngine> gl_core_, gl_es_;
};

}  // namespace crtforge
