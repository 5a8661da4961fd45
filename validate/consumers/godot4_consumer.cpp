// "godot4": a real Godot 4 (4.6's official web build in headless Chromium, runtime/godot4) compiles
// and renders the target. Every shader file goes through the shim first (a fast pre-check whose
// errors name GLSL lines) and then through Godot 4's own shader compiler, which is stricter (it
// refuses an uninitialised global the shim accepts): its refusal, with the shader's line, is the
// validate failure. A lone pass renders as the node-mode shader on a TextureRect; a scene runs as
// its users run it, the exported <preset>.tscn with its pipeline script, frame after frame; the
// matrix's host modes use the node shader with no param set, the .tres, or the screen shader.

#include "crtforge/runtime/godot4_engine.hpp"
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
        Godot4Job job;
        if (auto s = consumers::fill_pass_job(4, r, job); !s.ok()) return s.error();
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
    // Chromium runs its WebGL 2 on SwiftShader (tools/godot4-runner/driver.mjs: --use-angle=swiftshader).
    bool draws_on_swiftshader() const override { return true; }

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
