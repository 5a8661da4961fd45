// Presets: any text through parse_preset_file, resolved against the shipped library (so `base`
// can name a shipped preset), then every pass made into variants and assembled into GLSL, which
// fuzzes the assembler with whatever values a preset manages to get past validation.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "crtforge/assembler.hpp"
#include "crtforge/variant.hpp"
#include "fuzz/fuzz_support.hpp"
#include "fuzz/fuzz_targets.hpp"

namespace {

using namespace crtforge;

// The shipped presets as files, the fuzzed one's possible bases. Parsed once.
const std::vector<PresetFile>& shipped_preset_files() {
    static const std::vector<PresetFile> files = [] {
        std::vector<PresetFile> out;
        const TemplateLibrary& library = fuzz::shipped_library();
        for (const auto& entry : std::filesystem::directory_iterator(library.dir() + "/presets")) {
            if (entry.path().extension() != ".toml") continue;
            std::ifstream in(entry.path(), std::ios::binary);
            std::ostringstream text;
            text << in.rdbuf();
            auto file = parse_preset_file(text.str(), entry.path().string(), &library);
            if (file.ok()) out.push_back(std::move(file.value()));
        }
        return out;
    }();
    return files;
}

}  // namespace

int crtforge_fuzz_preset(const uint8_t* data, size_t size) {
    const TemplateLibrary& library = fuzz::shipped_library();
    const std::string text(reinterpret_cast<const char*>(data), size);
    auto file = parse_preset_file(text, "fuzz.toml", &library);
    if (!file.ok()) return 0;

    // The fuzzed file comes first, so it shadows a shipped preset of the same name.
    std::vector<PresetFile> files{file.value()};
    const auto& shipped = shipped_preset_files();
    files.insert(files.end(), shipped.begin(), shipped.end());
    auto preset = library.resolve(files, file.value().name);
    if (!preset.ok()) return 0;

    // Default (most params baked as constants) and All (runtime-capable params as uniforms).
    VariantOptions baked, uniforms;
    uniforms.uniforms.mode = UniformSelection::Mode::All;
    for (size_t pass = 0; pass < preset.value().passes.size(); ++pass)
        for (const VariantOptions* options : {&baked, &uniforms}) {
            auto variant = make_variant(library, preset.value(), *options, pass);
            if (variant.ok()) (void)assemble(library, variant.value());
        }
    return 0;
}
