// The pipeline host validation runs a scene with: frame by frame, every pass through a target's
// consumer (render_pass), with the inputs the scene model gives each pass. Written apart from the
// reference renderer's own loop, so the two check each other; the Godot 3 consumer runs the
// exported Godot scene instead, a third host.
#pragma once

#include <functional>
#include <vector>

#include "crtforge/validate/target_render.hpp"

namespace crtforge {

using PassRenderer = std::function<Result<Image>(TargetRenderRequest pass)>;

Result<std::vector<Image>> run_scene(const SceneRenderRequest& request, const PassRenderer& render_pass);

// A pass's stored format as a render job's target format, and back: the two enums name the same
// formats, one in the preset's words, one in the runtime's.
OutputFormat output_format(PixelFormat format);
PixelFormat pixel_format(OutputFormat format);

// A generated or file LUT's image (8-bit texels as floats).
Result<SharedImage> scene_lut_image(const LutSpec& lut, const std::map<std::string, SharedImage>& file_luts);

}  // namespace crtforge
