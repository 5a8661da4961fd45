// "godot3": a real Godot 3 (Debian's godot3 under Xvfb, runtime/godot3) renders the target. A scene
// runs as its users run it: the export's ready-made scene (<preset>.tscn, its pipeline script,
// every pass's shader and the LUTs) instanced in a game window, frame after frame. A lone pass
// (`crtforge render` of one pass) is the node-mode shader on a TextureRect. Both shaders also
// compile through the shim, which checks them as GLSL with Godot 3's builtins.

#include <fmt/format.h>

#include "crtforge/runtime/godot3_engine.hpp"
#include "validate/consumers/consumer.hpp"
#include "validate/consumers/godot_hosting.hpp"
#include "validate/consumers/godot_shim.hpp"

namespace crtforge {

namespace {

class Godot3Consumer final : public Consumer {
public:
    // The shim first (its errors name GLSL lines precisely), then the real Godot 3: its own shader
    // language parser is stricter than GLSL in places the shim cannot know (a user's stage once
    // passed the shim and was rejected by Godot). The persistent server keeps this cheap.
    Status compile(const OutputFile& f, ConsumerEngines& engines) const override {
        if (auto shim = consumers::compile_through_shim(f.data, 3, engines); !shim.ok()) return shim;
        if (f.manifest_role() != "shader") return Ok{};  // screen shaders: the matrix's host modes render them
        Godot3Job job;
        job.shader_code = f.data;
        job.width = job.height = 2;
        job.frames = 1;
        auto drawn = engines.godot3().render(job);
        if (!drawn.ok()) return drawn.error();
        return Ok{};
    }

    Result<Image> render(TargetRenderRequest r, ConsumerEngines& engines) const override {
        Godot3Job job;
        if (auto s = consumers::fill_pass_job(3, r, job); !s.ok()) return s.error();
        return engines.godot3().render(job);
    }

    Result<std::vector<Image>> render_scene(const SceneRenderRequest& r, ConsumerEngines& engines) const override {
        Godot3SceneJob job;
        if (auto s = consumers::fill_scene_job(3, TargetId::Godot3, r, job); !s.ok()) return s.error();
        auto images = engines.godot3().render_scene(job);
        if (!images.ok()) return images.error();
        return consumers::in_request_order(r.frames, job.capture, images.value());
    }

    // The exported scene's last pass is an 8-bit viewport (llvmpipe truncates to it).
    double output_quantum() const override { return 1.0 / 255.0; }

    std::string describe(ConsumerEngines&) const override {
        const std::string version = godot3_version();
        return version.empty() ? std::string("Godot 3 unavailable")
                               : "Godot " + version + " (GLES3 on Mesa, Xvfb): compiles every node shader, renders the exported scene";
    }
};

}  // namespace

const Consumer& godot3_consumer() {
    static const Godot3Consumer consumer;
    return consumer;
}

}  // namespace crtforge
