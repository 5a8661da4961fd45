#include "runtime/gl/gl_program.hpp"

#include <algorithm>
#include <array>
#include <set>
#include <vector>

#include <fmt/core.h>

namespace crtforge::gl {
namespace {

// A shader's or program's info log, through the matching pair of GL entry points.
template <typename GetIv, typename GetLog>
std::string info_log(GLuint object, GetIv get_iv, GetLog get_log) {
    GLint length = 0;
    get_iv(object, GL_INFO_LOG_LENGTH, &length);
    if (length <= 0) return {};
    std::string log(static_cast<size_t>(length), '\0');
    GLsizei written = 0;
    get_log(object, length, &written, log.data());
    log.resize(static_cast<size_t>(written > 0 ? written : 0));
    return log;
}

std::string shader_log(const GlFunctions& gl, GLuint shader) { return info_log(shader, gl.GetShaderiv, gl.GetShaderInfoLog); }
std::string program_log(const GlFunctions& gl, GLuint program) { return info_log(program, gl.GetProgramiv, gl.GetProgramInfoLog); }

Diagnostic rejected_shader(const GlFunctions& gl, GLenum stage, GLuint shader) {
    return make_validation_error(fmt::format("GL driver rejected the {} shader: {}",
                                             stage == GL_VERTEX_SHADER ? "vertex" : "fragment",
                                             first_log_line(shader_log(gl, shader))));
}

bool compiled(const GlFunctions& gl, GLuint shader) {
    GLint status = GL_FALSE;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &status);
    return status == GL_TRUE;
}

Result<UniqueShader> compile_shader(const GlFunctions& gl, GLenum stage, const std::string& source) {
    UniqueShader shader(gl, gl.CreateShader(stage));
    if (!shader) return make_error(fmt::format("glCreateShader({}) failed", stage == GL_VERTEX_SHADER ? "vertex" : "fragment"));
    const GLchar* text = source.c_str();
    const auto length = static_cast<GLint>(source.size());
    gl.ShaderSource(shader.get(), 1, &text, &length);
    gl.CompileShader(shader.get());
    if (!compiled(gl, shader.get())) return rejected_shader(gl, stage, shader.get());
    return shader;
}

std::string block_name(const GlFunctions& gl, GLuint program, GLuint index) {
    GLint length = 0;
    gl.GetActiveUniformBlockiv(program, index, GL_UNIFORM_BLOCK_NAME_LENGTH, &length);
    if (length <= 0) return {};
    std::string name(static_cast<size_t>(length), '\0');
    GLsizei written = 0;
    gl.GetActiveUniformBlockName(program, index, length, &written, name.data());
    name.resize(static_cast<size_t>(written > 0 ? written : 0));
    return name;
}

// Scalar/vector/matrix shape of a uniform type: columns, rows and bytes per component; 0 columns
// for a type the block cannot hold or this table does not know.
struct TypeShape {
    int columns = 0, rows = 0, component_bytes = 4;
};

TypeShape type_shape(GLenum type) {
    switch (type) {
        case GL_FLOAT: case GL_INT: case GL_UNSIGNED_INT: case GL_BOOL: return {1, 1};
        case GL_FLOAT_VEC2: case GL_INT_VEC2: case GL_UNSIGNED_INT_VEC2: case GL_BOOL_VEC2: return {1, 2};
        case GL_FLOAT_VEC3: case GL_INT_VEC3: case GL_UNSIGNED_INT_VEC3: case GL_BOOL_VEC3: return {1, 3};
        case GL_FLOAT_VEC4: case GL_INT_VEC4: case GL_UNSIGNED_INT_VEC4: case GL_BOOL_VEC4: return {1, 4};
        case GL_FLOAT_MAT2: return {2, 2};
        case GL_FLOAT_MAT3: return {3, 3};
        case GL_FLOAT_MAT4: return {4, 4};
        case GL_FLOAT_MAT2x3: return {2, 3};
        case GL_FLOAT_MAT2x4: return {2, 4};
        case GL_FLOAT_MAT3x2: return {3, 2};
        case GL_FLOAT_MAT3x4: return {3, 4};
        case GL_FLOAT_MAT4x2: return {4, 2};
        case GL_FLOAT_MAT4x3: return {4, 3};
        case GL_DOUBLE: return {1, 1, 8};
        case GL_DOUBLE_VEC2: return {1, 2, 8};
        case GL_DOUBLE_VEC3: return {1, 3, 8};
        case GL_DOUBLE_VEC4: return {1, 4, 8};
        default: return {};
    }
}

// Where the block's last active member ends, from each member's offset, type, array and matrix
// strides; nullopt when a member's type is not in the table.
std::optional<size_t> used_block_bytes(const GlFunctions& gl, GLuint program, GLuint block) {
    GLint count = 0;
    gl.GetActiveUniformBlockiv(program, block, GL_UNIFORM_BLOCK_ACTIVE_UNIFORMS, &count);
    if (count <= 0) return size_t{0};
    std::vector<GLint> indices(static_cast<size_t>(count));
    gl.GetActiveUniformBlockiv(program, block, GL_UNIFORM_BLOCK_ACTIVE_UNIFORM_INDICES, indices.data());
    std::vector<GLuint> members(indices.begin(), indices.end());
    auto query = [&](GLenum what) {
        std::vector<GLint> values(members.size());
        gl.GetActiveUniformsiv(program, count, members.data(), what, values.data());
        return values;
    };
    const auto types = query(GL_UNIFORM_TYPE), sizes = query(GL_UNIFORM_SIZE), offsets = query(GL_UNIFORM_OFFSET),
               array_strides = query(GL_UNIFORM_ARRAY_STRIDE), matrix_strides = query(GL_UNIFORM_MATRIX_STRIDE),
               row_major = query(GL_UNIFORM_IS_ROW_MAJOR);
    size_t end = 0;
    for (size_t i = 0; i < members.size(); ++i) {
        const TypeShape shape = type_shape(static_cast<GLenum>(types[i]));
        if (shape.columns == 0 || offsets[i] < 0) return std::nullopt;
        size_t element = 0;
        if (shape.columns == 1) {
            element = static_cast<size_t>(shape.rows * shape.component_bytes);
        } else {
            const int major = row_major[i] ? shape.rows : shape.columns, minor = row_major[i] ? shape.columns : shape.rows;
            element = static_cast<size_t>((major - 1) * matrix_strides[i] + minor * shape.component_bytes);
        }
        const size_t elements = static_cast<size_t>(sizes[i] > 1 ? sizes[i] : 1);
        end = std::max(end, static_cast<size_t>(offsets[i]) + (elements - 1) * static_cast<size_t>(array_strides[i]) + element);
    }
    return end;
}

}  // namespace

std::string first_log_line(const std::string& log) {
    size_t start = 0;
    while (start < log.size()) {
        size_t end = log.find('\n', start);
        if (end == std::string::npos) end = log.size();
        size_t first = start, last = end;
        while (first < last && (log[first] == ' ' || log[first] == '\t' || log[first] == '\r' || log[first] == '\0')) ++first;
        while (last > first && (log[last - 1] == ' ' || log[last - 1] == '\t' || log[last - 1] == '\r' || log[last - 1] == '\0')) --last;
        if (last > first) return log.substr(first, last - first);
        start = end + 1;
    }
    return "(empty info log)";
}

Result<UniqueProgram> build_program(const GlFunctions& gl, const std::string& vertex_source,
                                    const std::string& fragment_source) {
    auto vertex = compile_shader(gl, GL_VERTEX_SHADER, vertex_source);
    if (!vertex) return vertex.error();
    auto fragment = compile_shader(gl, GL_FRAGMENT_SHADER, fragment_source);
    if (!fragment) return fragment.error();

    UniqueProgram program(gl, gl.CreateProgram());
    if (!program) return make_error("glCreateProgram failed");
    gl.AttachShader(program.get(), vertex.value().get());
    gl.AttachShader(program.get(), fragment.value().get());
    gl.LinkProgram(program.get());
    GLint linked = GL_FALSE;
    gl.GetProgramiv(program.get(), GL_LINK_STATUS, &linked);
    if (linked != GL_TRUE) {
        // Mesa skips compiling a source its shader cache has seen (even from another API or another
        // process) and compiles it at link instead: a compile error then shows up as a failed link
        // ("vertex shader lacks `main'") while the shader's own status and log tell the truth.
        if (!compiled(gl, vertex.value().get())) return rejected_shader(gl, GL_VERTEX_SHADER, vertex.value().get());
        if (!compiled(gl, fragment.value().get())) return rejected_shader(gl, GL_FRAGMENT_SHADER, fragment.value().get());
        return make_validation_error(
            fmt::format("GL driver rejected the program at link: {}", first_log_line(program_log(gl, program.get()))));
    }
    // The shaders may go now: a linked program keeps what it needs (deletion is deferred while attached).
    return program;
}

Result<ProgramBindings> bind_program_interface(const GlFunctions& gl, GLuint program, const std::string& uniform_block,
                                               const std::vector<SamplerUnit>& samplers) {
    ProgramBindings out;
    GLint blocks = 0;
    gl.GetProgramiv(program, GL_ACTIVE_UNIFORM_BLOCKS, &blocks);
    for (GLint i = 0; i < blocks; ++i) {
        const auto index = static_cast<GLuint>(i);
        const std::string name = block_name(gl, program, index);
        if (name != uniform_block) {
            return make_error(fmt::format("the shader uses uniform block '{}' but the job only provides '{}'", name,
                                          uniform_block),
                              {}, 0, "job.uniform_block");
        }
        GLint size = 0;
        gl.GetActiveUniformBlockiv(program, index, GL_UNIFORM_BLOCK_DATA_SIZE, &size);
        gl.UniformBlockBinding(program, index, 0);
        ProgramBindings::Block info;
        info.data_size = static_cast<size_t>(size > 0 ? size : 0);
        info.used_size = std::min(used_block_bytes(gl, program, index).value_or(info.data_size), info.data_size);
        out.uniform_block = info;
    }

    gl.UseProgram(program);
    for (size_t i = 0; i < samplers.size(); ++i) {
        const SamplerUnit& sampler = samplers[i];
        const GLint location = sampler.name.empty() ? -1 : gl.GetUniformLocation(program, sampler.name.c_str());
        if (location != -1) gl.Uniform1i(location, sampler.unit);
        if (i == 0) out.samples_texture = location != -1;
    }
    return out;
}

Status set_plain_uniforms(const GlFunctions& gl, GLuint program, const std::vector<PlainUniform>& uniforms) {
    std::set<std::string> given;
    for (const PlainUniform& u : uniforms) {
        given.insert(u.name);
        if (u.components < 1 || u.components > 4)
            return make_error(fmt::format("plain uniform '{}' has {} components", u.name, u.components), {}, 0, "job.plain_uniforms");
        const GLint location = gl.GetUniformLocation(program, u.name.c_str());
        if (location == -1) continue;
        using Kind = PlainUniform::Kind;
        if (u.kind == Kind::Float) {
            auto* set = std::array{gl.Uniform1fv, gl.Uniform2fv, gl.Uniform3fv, gl.Uniform4fv}[static_cast<size_t>(u.components - 1)];
            set(location, 1, u.values.data());
        } else if (u.kind == Kind::Int || u.components == 1) {
            if (u.kind == Kind::Uint) gl.Uniform1uiv(location, 1, reinterpret_cast<const GLuint*>(u.ints.data()));
            else std::array{gl.Uniform1iv, gl.Uniform2iv, gl.Uniform3iv, gl.Uniform4iv}[static_cast<size_t>(u.components - 1)](location, 1, u.ints.data());
        } else {
            return make_error(fmt::format("plain uniform '{}': uint vectors are not supported", u.name), {}, 0, "job.plain_uniforms");
        }
    }
    GLint count = 0;
    gl.GetProgramiv(program, GL_ACTIVE_UNIFORMS, &count);
    for (GLint i = 0; i < count; ++i) {
        const auto index = static_cast<GLuint>(i);
        GLint block = -1;
        gl.GetActiveUniformsiv(program, 1, &index, GL_UNIFORM_BLOCK_INDEX, &block);
        if (block != -1) continue;
        char name[256] = {};
        GLsizei length = 0;
        GLint size = 0;
        GLenum type = 0;
        gl.GetActiveUniform(program, index, sizeof name, &length, &size, &type, name);
        const bool sampler = type == GL_SAMPLER_2D || type == GL_INT_SAMPLER_2D || type == GL_UNSIGNED_INT_SAMPLER_2D;
        if (!sampler && !given.count(name))
            return make_error(fmt::format("the shader's uniform '{}' is not among the job's plain uniforms", name), {}, 0,
                              "job.plain_uniforms");
    }
    return Ok{};
}

}  // namespace crtforge::gl
