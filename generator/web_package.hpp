// The npm package an export with WGSL carries: npm/ (see web_package.cpp).
#pragma once

#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "crtforge/diagnostic.hpp"

namespace crtforge::detail {

// The package's folder in an export.
inline constexpr const char* kWebPackageDir = "npm/";

// Adds npm/ to an export's files (path -> contents) when the manifest has WGSL: package.json,
// index.mjs, index.d.ts, crt-webgpu.mjs, README.md, a manifest.json with the WGSL entries only, and
// copies of the WGSL modules and LUT PNGs that manifest names, so the folder is the whole package.
// An error (no files added) if the manifest names a file the export does not hold.
Status add_web_package(const nlohmann::ordered_json& manifest, std::map<std::string, std::string>& files);

// The package's fixed files, embedded at build time from examples/webgpu/ (web_package_files.cpp.in).
struct WebPackageSources {
    const char* module;        // crt-webgpu.mjs
    const char* index;         // package/index.mjs
    const char* declarations;  // package/index.d.ts
    const char* readme;        // package/README.md
    const char* three;               // package/three.mjs: the three.js WebGPURenderer pass
    const char* three_declarations;  // package/three.d.ts
    const char* pixi;                // package/pixi.mjs: the PixiJS v8 WebGPURenderer pass
    const char* pixi_declarations;   // package/pixi.d.ts
    const char* babylon;                // package/babylon.mjs: the Babylon.js WebGPUEngine pass
    const char* babylon_declarations;   // package/babylon.d.ts
    const char* framework_pass;         // package/framework-pass.mjs: what the three adapters share
};
const WebPackageSources& web_package_sources();

}  // namespace crtforge::detail
