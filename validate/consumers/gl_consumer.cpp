// "gl" and "gl-es": GLSL as an OpenGL / OpenGL ES host uses it — glslang re-parses each file in the
// profile its #version line names, then Mesa's driver (EGL surfaceless: a 4.5 core context for "gl",
// an ES 3 context for "gl-es") compiles, links and renders the pair.
#include <regex>
#include <sstream>

#include "validate/consumers/consumer.hpp"

namespace crtforge {

namespace {

struct GlslVersion {
    int version = 0;
    bool es = false;
};

// The dialect a file declares on its #version line, as a driver reads it.
Result<GlslVersion> declared_version(const std::string& source) {
    static const std::regex version_line(R"(^\s*#\s*version\s+(\d+)(\s+es)?\s*$)");
    std::smatch m;
    std::istringstream lines(source);
    std::string line;
    while (std::getline(lines, line))
        if (std::regex_match(line, m, version_line)) return GlslVersion{std::stoi(m[1]), m[2].matched};
    return make_validation_error("the GLSL file has no #version line");
}

class GlConsumer final : public Consumer {
public:
    explicit GlConsumer(bool es) : es_(es) {}

    Status compile(const OutputFile& f, ConsumerEngines&) const override {
        auto version = declared_version(f.data);
        if (!version.ok()) return version.error();
        auto status = check_glsl(f.data, f.stage, version.value().version, version.value().es);
        if (!status.ok()) return as_validation(status.error());
        return status;
    }

    Result<Image> render(TargetRenderRequest r, ConsumerEngines& engines) const override {
        auto vertex = file_with_role(r, "vertex");
        if (!vertex.ok()) return vertex.error();
        auto fragment = file_with_role(r, "fragment");
        if (!fragment.ok()) return fragment.error();
        auto uniforms = variant_uniforms(r);
        if (!uniforms.ok()) return uniforms.error();
        auto engine = engines.gl(es_);
        if (!engine.ok()) return engine.error();
        // GL binds samplers by name; the binding numbers are unused.
        auto textures = engine_textures(r, [](const std::string&) -> Result<uint32_t> { return 0u; });
        if (!textures.ok()) return textures.error();
        auto job = request_job<GlRenderJob>(r, std::move(uniforms.value()), std::move(textures.value()));
        job.vertex_source = vertex.value()->data;
        job.fragment_source = fragment.value()->data;
        return engine.value()->render(job);
    }

    std::string describe(ConsumerEngines& engines) const override {
        auto g = engines.gl(es_);
        return g.ok() ? g.value()->renderer() : std::string("OpenGL unavailable");
    }

private:
    bool es_;
};

}  // namespace

const Consumer& gl_consumer() {
    static const GlConsumer consumer(false);
    return consumer;
}

const Consumer& gl_es_consumer() {
    static const GlConsumer consumer(true);
    return consumer;
}

}  // namespace crtforge
