// The tests' entry point: Catch2's, with the CLI's memory policy (the tests render the same large
// images the CLI does) and its LUT picture decoder.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "crtforge/lut_file.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/runtime/process_memory.hpp"

int main(int argc, char** argv) {
    crtforge::keep_freed_memory();
    crtforge::set_lut_picture_decoder(&crtforge::read_lut_picture);  // as the CLI: exports ship JPEG LUTs as PNG
    return Catch::Session().run(argc, argv);
}
