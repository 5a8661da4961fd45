// Stage specs (templates/stages/*.toml): any text through parse_stage_spec.
#include <string>

#include "crtforge/template_library.hpp"
#include "fuzz/fuzz_targets.hpp"

int crtforge_fuzz_stage_spec(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    (void)crtforge::parse_stage_spec(text, "fuzz.toml");
    return 0;
}
