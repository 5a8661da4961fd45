// libFuzzer entry for the preset target; the body is in fuzz_targets.hpp's crtforge_fuzz_preset.
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return crtforge_fuzz_preset(data, size); }
