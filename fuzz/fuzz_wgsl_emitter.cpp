// libFuzzer entry for the wgsl_emitter target; the body is in fuzz_targets.hpp's crtforge_fuzz_wgsl_emitter.
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return crtforge_fuzz_wgsl_emitter(data, size); }
