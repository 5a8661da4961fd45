// "gl", "gl-es" and "gl-es-plain" (WebGL 2's plain uniforms, set by name): GLSL as an OpenGL / OpenGL ES host uses it — glslang re-parses each file in the
// profile its #version line names, then Mesa's driver (EGL surfaceless: a 4.5 core context for "gl",
// an ES 3 context for "gl-es") compiles, links and renders the pair.
#include <cstring>
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

// The std140 bytes of the pass's uniform block as plain uniforms, one per reflected member: what a
// WebGL 2 framework sets by name from the same values.
Result<std::vector<PlainUniform>> plain_uniforms(const TargetRenderRequest& r, const std::vector<uint8_t>& bytes) {
    std::vector<PlainUniform> out;
    for (const ReflectedBlock& block : r.compiled->reflection.uniform_blocks)
        for (const ReflectedMember& m : block.members) {
            using Scalar = ReflectedMember::Scalar;
            if (m.columns != 1 || m.components < 1 || m.components > 4 || m.scalar == Scalar::Other)
                return make_validation_error("uniform member '" + m.name + "' has type " + m.type + ", which no plain uniform takes");
            PlainUniform u;
            u.name = m.name;
            u.components = static_cast<int>(m.components);
            u.kind = m.scalar == Scalar::Float ? PlainUniform::Kind::Float
                   : m.scalar == Scalar::Uint ? PlainUniform::Kind::Uint : PlainUniform::Kind::Int;  // bool as int
            if (m.offset + 4u * static_cast<uint32_t>(u.components) > bytes.size())
                return make_validation_error("uniform member '" + m.name + "' lies past the packed uniform data");
            for (int c = 0; c < u.components; ++c) {
                std::memcpy(&u.values[static_cast<size_t>(c)], bytes.data() + m.offset + 4 * c, 4);
                std::memcpy(&u.ints[static_cast<size_t>(c)], bytes.data() + m.offset + 4 * c, 4);
            }
            out.push_back(u);
        }
    return out;
}

class GlConsumer final : public Consumer {
public:
    GlConsumer(bool es, bool plain) : es_(es), plain_(plain) {}

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
        std::vector<PlainUniform> plain;
        if (plain_) {
            auto flat = plain_uniforms(r, uniforms.value());
            if (!flat.ok()) return flat.error();
            plain = std::move(flat.value());
            uniforms.value().clear();
        }
        auto job = request_job<GlRenderJob>(r, std::move(uniforms.value()), std::move(textures.value()));
        job.plain_uniforms = std::move(plain);
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
    bool plain_;  // the webgl2 target: params and builtins as plain uniforms, set by name
};

}  // namespace

const Consumer& gl_consumer() {
    static const GlConsumer consumer(false, false);
    return consumer;
}

const Consumer& gl_es_consumer() {
    static const GlConsumer consumer(true, false);
    return consumer;
}

const Consumer& gl_es_plain_consumer() {
    static const GlConsumer consumer(true, true);
    return consumer;
}

}  // namespace crtforge
