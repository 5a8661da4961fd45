// libFuzzer entry for the wgsl_valid target; the body is in fuzz_targets.hpp's crtforge_fuzz_wgsl_valid.
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return crtforge_fuzz_wgsl_valid(data, size); }
