// Reflection of a compiled fragment module: the uniform block layout and the texture binding,
// read back from SPIR-V (not from the source), so the manifest describes what the driver sees.
#pragma once

#include <string>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/spirv_compiler.hpp"

namespace crtforge {

struct ReflectedMember {
    enum class Scalar { Float, Int, Uint, Bool, Other };
    std::string name;
    std::string type;   // GLSL spelling: float, int, uint, vec2, vec3, ...
    Scalar scalar = Scalar::Float;  // the same, taken apart: component type,
    uint32_t components = 1;        // components per column (1..4),
    uint32_t columns = 1;           // and columns (over 1: a matrix)
    uint32_t offset = 0;
    uint32_t size = 0;
};

struct ReflectedBlock {
    std::string name;
    uint32_t set = 0, binding = 0, size = 0;
    std::vector<ReflectedMember> members;
};

struct ReflectedTexture {
    std::string name;
    uint32_t set = 0, binding = 0;
};

struct Reflection {
    std::vector<ReflectedBlock> uniform_blocks;
    std::vector<ReflectedTexture> textures;
    std::vector<std::string> names;   // every OpName string left in the module
    uint32_t texture_samples = 0;     // image sample instructions in the module
};

Result<Reflection> reflect(const SpirvBinary& binary);

}  // namespace crtforge
