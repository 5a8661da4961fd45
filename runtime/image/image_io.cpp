// read_image / write_png / write_exr: forwarders to the OpenImageIO module, loaded once on first use.
#include "crtforge/runtime/image_io.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "crtforge/paths.hpp"
#include "runtime/image/image_io_module.hpp"

namespace crtforge {

namespace {

struct LoadedModule {
    const ImageIoModule* table = nullptr;
    std::string error;
};

// The module sits in <prefix>/lib/crtforge (crtforge/paths.hpp), or wherever CRTFORGE_IMAGEIO_MODULE
// points.
const LoadedModule& module() {
    static LoadedModule loaded;
    static std::once_flag once;
    std::call_once(once, [] {
        const char* env = std::getenv("CRTFORGE_IMAGEIO_MODULE");
        const std::string path = env && *env ? env : module_path("libcrtforge_imageio.so");
        void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = ::dlerror();
            loaded.error = "cannot load the image I/O module " + path + ": " + (why ? why : "unknown error") +
                           " (install libopenimageio2.4 with scripts/setup.sh, and build crtforge)";
            return;
        }
        using Entry = const ImageIoModule* (*)();
        auto entry = reinterpret_cast<Entry>(::dlsym(handle, "crtforge_image_io_module"));
        const ImageIoModule* table = entry ? entry() : nullptr;
        if (!table || table->version != kImageIoModuleVersion) {
            loaded.error = "the image I/O module " + path + " is from another crtforge build; rebuild crtforge";
            return;
        }
        loaded.table = table;  // kept loaded for the life of the process
    });
    return loaded;
}

}  // namespace

Result<Image> read_image(const std::string& path) {
    const LoadedModule& m = module();
    if (!m.table) return make_error(m.error, path);
    return m.table->read_image(path);
}

Result<LutImage> read_lut_picture(const std::string& path) {
    auto image = read_image(path);
    if (!image.ok()) return image.error();
    const Image& in = image.value();
    LutImage out;
    out.width = in.width;
    out.height = in.height;
    out.rgba.resize(in.rgba.size());
    for (size_t i = 0; i < in.rgba.size(); ++i) out.rgba[i] = static_cast<uint8_t>(std::lround(std::clamp(in.rgba[i], 0.0f, 1.0f) * 255.0f));
    return out;
}

Status write_png(const std::string& path, const Image& image, int bits) {
    const LoadedModule& m = module();
    if (!m.table) return make_error(m.error, path);
    return m.table->write_png(path, image, bits);
}

Status write_exr(const std::string& path, const Image& image) {
    const LoadedModule& m = module();
    if (!m.table) return make_error(m.error, path);
    return m.table->write_exr(path, image);
}

}  // namespace crtforge
