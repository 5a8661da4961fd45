#include "targets/spirv/spirv_writer.hpp"

#include "crtforge/assembler.hpp"

namespace crtforge::spirv {

namespace {
std::string as_bytes(const SpirvBinary& words) {
    // SPIR-V files are little-endian words; this host is little-endian (x86-64, arm64).
    return std::string(reinterpret_cast<const char*>(words.data()), words.size() * sizeof(uint32_t));
}
}  // namespace

Result<TargetOutput> generate(const TargetInput& input, const Options&) {
    TargetOutput out;
    out.files.push_back({ShaderStage::Vertex, ".vert.spv", as_bytes(*input.vertex), {}, {}});
    out.files.push_back({ShaderStage::Fragment, ".frag.spv", as_bytes(*input.fragment), {}, {}});
    if (input.variant->has_uniform_block())
        out.bindings.push_back({kUniformBlockName, "set=0, binding=0 (uniform buffer, std140)"});
    out.bindings.push_back({kSourceTextureName, "set=0, binding=1 (combined image sampler)"});
    return out;
}

std::vector<TargetInfo> records() {
    return {{TargetId::Spirv, "spirv", "SPIR-V 1.0 binaries (Vulkan), fragment + full-screen vertex shader",
             {"vertex", "fragment"}, "vulkan", [](const TargetInput& in) { return generate(in); },
             "spirv/as-compiled/v1"}};
}

}  // namespace crtforge::spirv
