// "godot4": a real Godot 4 (4.6's official web build in headless Chromium, runtime/godot4) compiles
// and renders the target. Every shader file goes through the shim first (a fast pre-check whose
// errors name GLSL lines) and then through Godot 4's own shader compiler, which is stricter (it
// refuses an uninitialised global the shim accepts): its refusal, with the shader's line, is the
// validate failure. A lone pass renders as the node-mode shader on a TextureRect; a scene runs as
// its users run it, the exported <preset>.tscn with its pipeline script, frame after frame; the
// matrix's host modes use the node shader with no param set, the .tres, or the screen shader.
#include <cmath>

#include "crtforge/runtime/godot4_engine.hpp"
#include "crtforge/uniforms.hpp"
#include "targets/godot/godot_compiler.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/consumers/godot_hosting.hpp"
#include "validate/consumers/godot_shim.hpp"

namespace crtforge {

namespace {

class Godot4Consumer final : public Consumer {
public:
    Status compile(const OutputFile& f, ConsumerEngines& engines) const override {
        if (auto shim = consumers::compile_through_shim(f.data, 4, engines); !shim.ok()) return shim;
        Godot4Job job;
        job.shader_code = f.data;
        job.width = job.height = 2;
        job.frames = 1;
        auto drawn = shared_godot4_server().render(job);
        if (!drawn.ok()) return drawn.error();
        return Ok{};
    }

    Result<Image> render(TargetRenderRequest r, ConsumerEngines&) const override {
        if (!r.textures.empty() || !r.viewport.full() || r.format != OutputFormat::Rgba16Float)
            return make_error("this Godot 4 pass reads extra textures, draws into a viewport or stores an 8-bit "
                              "framebuffer: Godot 4 runs such passes in the exported scene (render the preset, not the pass)");
        auto shader = file_with_role(r, "shader");
        if (!shader.ok()) return shader.error();
        Godot4Job job;
        job.shader_code = shader.value()->data;
        if (auto s = consumers::pin_time(job.shader_code); !s.ok()) return s.error();
        if (job.shader_code != shader.value()->data)
            job.params[consumers::kPinnedTime] = std::fmod(r.time, consumers::kGodotTimeRollover);
        job.input = std::move(r.input);
        job.filter = r.filter;
        job.width = r.width;
        job.height = r.height;
        for (const VariantParam* p : r.compiled->variant.uniforms()) job.params[p->spec->name] = p->value;
        for (const auto& [name, value] : r.overrides) job.params[name] = value;
        // What crtforge_pipeline.gd sets every frame: the time reduced exactly.
        if (r.compiled->variant.angular_speed())
            job.params[godot::GodotCompiler::kHostTime] =
                shader_time(r.compiled->variant, effective_values(r.compiled->variant, r.overrides), r.time);
        return shared_godot4_server().render(job);
    }

    Result<std::vector<Image>> render_scene(const SceneRenderRequest& r, ConsumerEngines&) const override {
        Godot4SceneJob job;
        if (auto s = consumers::fill_scene_job(4, TargetId::Godot4, r, job); !s.ok()) return s.error();
        auto images = shared_godot4_server().render_scene(job);
        if (!images.ok()) return images.error();
        return consumers::in_request_order(r.frames, job.capture, images.value());
    }

    // Godot 4's 2D viewports on WebGL 2 store 8 bits a channel.
    double output_quantum() const override { return 1.0 / 255.0; }

    std::string describe(ConsumerEngines&) const override {
        return shared_godot4_server().describe() + ": compiles every shader, renders the node shader and the exported scene";
    }
};

}  // namespace

const Consumer& godot4_consumer() {
    static const Godot4Consumer consumer;
    return consumer;
}

}  // namespace crtforge
