// What the RetroArch import's tests share: a .slangp imported into a template overlay, and an
// imported preset's display rendered through a target's consumer.
#pragma once

#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "crtforge/runtime/image.hpp"
#include "crtforge/scene.hpp"
#include "crtforge/template_library.hpp"
#include "crtforge/validate/target_render.hpp"
#include "tests/test_support.hpp"

namespace crtforge::test::retroarch {

// `slangp` imported (RetroArch's settings; `name` for the preset's name, "" for the file's) into
// `overlay`, which is then loaded as a template library; the imported preset must resolve.
Result<std::shared_ptr<TemplateLibrary>> import_into(const std::string& slangp, const std::string& overlay, const std::string& root,
                                                     const std::string& name = "");

// Writes `text` as presets/<name>.slangp under `dir`, imports it into overlay/ and returns the
// library; the test fails unless it imports with `passes` passes.
std::shared_ptr<TemplateLibrary> import_text_or_fail(const TempDir& dir, const std::string& name, const std::string& text, size_t passes);

// A preset of one pass, `program`, drawn at the display's size.
std::shared_ptr<TemplateLibrary> one_pass_or_fail(const TempDir& dir, const std::string& name, const SlangProgram& program);

// The preset's display through `target`'s consumer at `width` x `height`.
Result<std::vector<Image>> render_imported(TargetRenderer& renderer, const TemplateLibrary& lib, const Preset& preset, TargetId target,
                                           const Image& input, int width, int height, std::vector<int> frames,
                                           const VariantOptions& options = {});

// render_imported's frames; the test fails, naming the error, unless it renders.
std::vector<Image> render_imported_or_fail(TargetRenderer& renderer, const TemplateLibrary& lib, const Preset& preset, TargetId target,
                                           const Image& input, int width, int height, std::vector<int> frames);

// `name` of `lib` drawn by each of `targets` at `display` from a flat grey picture of `source`
// (frame 1); `check` sees each display, its target named in the test's messages.
void render_on_each(const TemplateLibrary& lib, const std::string& name, std::initializer_list<TargetId> targets, PixelSize source,
                    PixelSize display, const std::function<void(TargetId, const Image&)>& check);

// The four channels of pixel (x, y).
inline const float* pixel_at(const Image& image, int x, int y) { return image.rgba.data() + (size_t(y) * image.width + size_t(x)) * 4; }

}  // namespace crtforge::test::retroarch
