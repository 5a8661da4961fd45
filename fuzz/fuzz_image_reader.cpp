// libFuzzer entry for the image_reader target; the body is in fuzz_targets.hpp's crtforge_fuzz_image_reader.
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return crtforge_fuzz_image_reader(data, size); }
