// The fuzz targets' bodies. Each libFuzzer executable (fuzz_<target>.cpp) is one of these behind
// LLVMFuzzerTestOneInput; the GCC test suite (tests/fuzz_corpus_test.cpp) replays the committed
// corpora and regressions through the very same functions. A body accepts any bytes and must
// neither crash nor let an exception escape: every failure is a Diagnostic the body ignores.
// Return values follow libFuzzer: 0, or -1 for an input not worth keeping in the corpus.
#pragma once

#include <cstddef>
#include <cstdint>

int crtforge_fuzz_stage_spec(const uint8_t* data, size_t size);
int crtforge_fuzz_preset(const uint8_t* data, size_t size);
int crtforge_fuzz_wgsl_emitter(const uint8_t* data, size_t size);
int crtforge_fuzz_wgsl_valid(const uint8_t* data, size_t size);
int crtforge_fuzz_image_reader(const uint8_t* data, size_t size);
