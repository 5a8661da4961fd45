// The tests' entry point: Catch2's, with the CLI's memory policy (the tests render the same large
// images the CLI does).
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "crtforge/runtime/process_memory.hpp"

int main(int argc, char** argv) {
    crtforge::keep_freed_memory();
    return Catch::Session().run(argc, argv);
}
