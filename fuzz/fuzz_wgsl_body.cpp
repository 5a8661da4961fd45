// The SPIR-V -> WGSL emitter (targets/wgsl/), given the input as a fragment module next to the
// shipped full-screen vertex shader, as the wgsl target does. Two targets share this file:
//  - wgsl_emitter: any bytes, read as little-endian words (a trailing partial word is dropped);
//    finds what malformed SPIR-V does to the reader and the emitter.
//  - wgsl_valid: only modules spirv-val accepts; what the emitter must translate or refuse cleanly.
#include <cstring>

#include "crtforge/assembler.hpp"
#include "crtforge/spirv_compiler.hpp"
#include "fuzz/fuzz_support.hpp"
#include "fuzz/fuzz_targets.hpp"
#include "targets/wgsl/wgsl_emitter.hpp"

namespace {

using namespace crtforge;

SpirvBinary words_of(const uint8_t* data, size_t size) {
    SpirvBinary words(size / 4);
    if (!words.empty()) std::memcpy(words.data(), data, words.size() * 4);
    return words;
}

void emit(const SpirvBinary& fragment) {
    wgsl::EmitOptions options;
    options.block_instance_names[kUniformBlockName] = kUniformInstanceName;
    (void)wgsl::emit_wgsl({{&fuzz::fullscreen_vertex(), "vs_main"}, {&fragment, "fs_main"}}, options);
}

}  // namespace

int crtforge_fuzz_wgsl_emitter(const uint8_t* data, size_t size) {
    emit(words_of(data, size));
    return 0;
}

int crtforge_fuzz_wgsl_valid(const uint8_t* data, size_t size) {
    const SpirvBinary fragment = words_of(data, size);
    if (!validate_spirv(fragment).ok()) return -1;  // not kept: the corpus holds valid modules only
    emit(fragment);
    return 0;
}
