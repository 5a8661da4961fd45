// The boundary between crtforge and its OpenImageIO module. OpenImageIO drags in ~260 shared
// libraries whose loading costs ~0.3 s at every process start, so it lives in a module
// (libcrtforge_imageio.so) that image_io.cpp loads on the first image read or write; commands that
// never touch images (export, generate, list) start in milliseconds.
//
// Both sides are built together by this project with the same compiler and standard library, so
// the table passes C++ types directly.
#pragma once

#include <string>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/image.hpp"

namespace crtforge {

// Raised with every change of the types the table passes (2: Image::device).
inline constexpr int kImageIoModuleVersion = 2;

struct ImageIoModule {
    int version;
    Result<Image> (*read_image)(const std::string& path);
    Status (*write_png)(const std::string& path, const Image& image, int bits);
    Status (*write_exr)(const std::string& path, const Image& image);
};

}  // namespace crtforge

// Exported by the module.
extern "C" const crtforge::ImageIoModule* crtforge_image_io_module();
