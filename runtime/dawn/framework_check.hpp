// A preset drawn through one of the npm package's web framework adapters (crtforge-presets/three,
// /pixi, /babylon), as an app built on that framework runs it: examples/webgpu/check.mjs starts
// the framework on Dawn, lets it hold the picture in its own texture and draws the preset with the
// adapter into another. The DawnEngine's persistent runner cannot do this: each framework makes
// its own device (three on Dawn's GLES backend, PixiJS and Babylon.js on its Vulkan backend over
// SwiftShader), so each sequence is one `node check.mjs` process.
#pragma once

#include <filesystem>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/dawn_engine.hpp"

namespace crtforge::detail {

// The adapters check.mjs can run a scene through.
bool is_web_framework(const std::string& name);

// Runs `job` (job.framework set) over the package in `package` (a folder holding the export's
// npm/ files), with `scratch` for the app folder, inputs and outputs. Errors: a bad job or a
// machine without node or the frameworks is an Input error; anything check.mjs reports (the
// adapter, the package or Dawn failing) a Validation error with its one line.
Result<std::vector<Image>> render_through_framework(const DawnSceneJob& job, const std::filesystem::path& package,
                                                    const std::filesystem::path& scratch);

}  // namespace crtforge::detail
