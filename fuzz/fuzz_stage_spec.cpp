// libFuzzer entry for the stage_spec target; the body is in fuzz_targets.hpp's crtforge_fuzz_stage_spec.
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return crtforge_fuzz_stage_spec(data, size); }
