#include "tests/retroarch_test_support.hpp"

#include <catch2/catch.hpp>

#include "crtforge/slang_import.hpp"

namespace crtforge::test::retroarch {

Result<std::shared_ptr<TemplateLibrary>> import_into(const std::string& slangp, const std::string& overlay,
                                                     const std::string& root, const std::string& name) {
    SlangImportOptions options;
    options.root = root;
    options.name = name;
    auto imported = import_slangp(slangp, options);
    if (!imported.ok()) return imported.error();
    if (auto s = write_imported_preset(imported.value(), overlay); !s.ok()) return s.error();
    auto lib = TemplateLibrary::load(overlay);
    if (lib.ok())
        if (auto broken = lib.value()->lookup_preset(imported.value().name); !broken.ok()) return broken.error();
    return lib;
}

// Writes `text` as presets/<name>.slangp under `dir`, imports it into overlay/ and returns the
// library; the test fails unless it imports with `passes` passes.
std::shared_ptr<TemplateLibrary> import_text_or_fail(const TempDir& dir, const std::string& name, const std::string& text,
                                                     size_t passes) {
    const std::string slangp = dir / ("presets/" + name + ".slangp");
    write_file(slangp, text);
    auto lib = import_into(slangp, dir / "overlay", dir.path(), name);
    INFO((lib.ok() ? std::string() : lib.error().str()));
    REQUIRE(lib.ok());
    const Preset* preset = lib.value()->find_preset(name);
    REQUIRE(preset);
    REQUIRE(preset->passes.size() == passes);
    return lib.value();
}

// A preset of one pass, `program`, drawn at the display's size.
std::shared_ptr<TemplateLibrary> one_pass_or_fail(const TempDir& dir, const std::string& name, const SlangProgram& program) {
    write_file(dir / ("shaders/" + name + ".slang"), slang_program(program));
    return import_text_or_fail(dir, name, "shaders = 1\nshader0 = ../shaders/" + name + ".slang\nscale_type0 = viewport\n", 1);
}

// The preset's display through `target`'s consumer at `width` x `height`.
Result<std::vector<Image>> render_imported(TargetRenderer& renderer, const TemplateLibrary& lib, const Preset& preset, TargetId target,
                                           const Image& input, int width, int height, std::vector<int> frames,
                                           const VariantOptions& options) {
    auto compiled = compile_scene(lib, preset, options, Cache());
    if (!compiled.ok()) return compiled.error();
    auto outputs = emit_scene(compiled.value(), target, Cache());
    if (!outputs.ok()) return outputs.error();
    auto luts = read_file_luts(preset);
    if (!luts.ok()) return luts.error();
    SceneRenderRequest r;
    r.preset = &preset;
    r.passes = &compiled.value();
    r.target = target;
    r.outputs = &outputs.value();
    r.source = [&](int) -> Result<Image> { return input; };
    r.width = width;
    r.height = height;
    r.frames = std::move(frames);
    r.file_luts = std::move(luts.value());
    r.frame_count_base = 1;
    return renderer.render_scene(r);
}

// render_imported's frames; the test fails, naming the error, unless it renders.
std::vector<Image> render_imported_or_fail(TargetRenderer& renderer, const TemplateLibrary& lib, const Preset& preset, TargetId target,
                                           const Image& input, int width, int height, std::vector<int> frames) {
    auto images = render_imported(renderer, lib, preset, target, input, width, height, std::move(frames));
    INFO((images.ok() ? std::string() : images.error().str()));
    REQUIRE(images.ok());
    return std::move(images).value();
}

void render_on_each(const TemplateLibrary& lib, const std::string& name, std::initializer_list<TargetId> targets, PixelSize source,
                    PixelSize display, const std::function<void(TargetId, const Image&)>& check) {
    const Preset* preset = lib.find_preset(name);
    REQUIRE(preset);
    const Image input = Image::make(source.width, source.height, {0.5f, 0.5f, 0.5f, 1.0f});
    TargetRenderer renderer;
    for (TargetId target : targets) {
        INFO(target_info(target).name);
        check(target, render_imported_or_fail(renderer, lib, *preset, target, input, display.width, display.height, {1}).front());
    }
}

}  // namespace crtforge::test::retroarch
