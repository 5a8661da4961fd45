// Image file I/O on top of OpenImageIO, built as a loadable module (see image_io_module.hpp). OIIO
// reports errors as strings that must be fetched (or it complains at shutdown); every fetched
// message is folded into a one-line Diagnostic.
#include "crtforge/runtime/image_io.hpp"
#include "runtime/image/image_io_module.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace crtforge {
namespace {

namespace fs = std::filesystem;

std::string or_unknown(std::string message) {
    return message.empty() ? std::string("unknown OpenImageIO error") : message;
}

// The first non-finite value, as "(x, y)" text for the message; empty when all are finite.
std::string first_non_finite(const Image& image) {
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        if (!std::isfinite(image.rgba[i])) {
            // Appended piece by piece: GCC 12 gives a false -Wrestrict on "(" + std::to_string(...).
            const std::size_t pixel = i / 4;
            std::string where = "(";
            where += std::to_string(pixel % static_cast<std::size_t>(image.width));
            where += ", ";
            where += std::to_string(pixel / static_cast<std::size_t>(image.width));
            where += ")";
            return where;
        }
    }
    return {};
}

// Spreads n stored channels (1 grey, 2 grey+alpha, 3 RGB, 4+ RGBA) over RGBA, alpha defaulting to 1.
Image expand_to_rgba(const std::vector<float>& stored, int width, int height, int channels) {
    Image image = Image::make(width, height);
    const std::size_t count = image.pixel_count();
    for (std::size_t p = 0; p < count; ++p) {
        const float* s = stored.data() + p * static_cast<std::size_t>(channels);
        float* d = image.rgba.data() + p * 4;
        if (channels <= 2) {
            d[0] = d[1] = d[2] = s[0];
            d[3] = channels == 2 ? s[1] : 1.0f;
        } else {
            d[0] = s[0];
            d[1] = s[1];
            d[2] = s[2];
            d[3] = channels >= 4 ? s[3] : 1.0f;
        }
    }
    return image;
}

Status check_writable_image(const std::string& path, const Image& image) {
    if (path.empty()) return make_error("no output path given");
    if (image.empty()) return make_error("cannot write an empty image", path);
    if (!image.consistent()) {
        return make_error("malformed image: pixel buffer does not match " + std::to_string(image.width) +
                              "x" + std::to_string(image.height),
                          path);
    }
    if (const std::string where = first_non_finite(image); !where.empty()) {
        return make_error("cannot write non-finite pixel value at " + where, path);
    }
    return Ok{};
}

// Writes `pixels` (of `pixel_type`, RGBA, tightly packed) with the OIIO writer for `format_name`
// to a temporary file beside `path`, then renames it into place. The spec carries no attributes
// beyond the ones set here, so nothing time- or host-dependent reaches the file.
Status write_atomically(const std::string& path, const char* format_name, const OIIO::ImageSpec& spec,
                        OIIO::TypeDesc pixel_type, const void* pixels) {
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format_name);
    if (!out) return make_error("OpenImageIO has no " + std::string(format_name) + " writer: " + or_unknown(OIIO::geterror()), path);

    std::string failure;
    if (!out->open(tmp, spec)) {
        failure = "cannot open for writing: " + or_unknown(out->geterror());
    } else if (!out->write_image(pixel_type, pixels)) {
        failure = "write failed: " + or_unknown(out->geterror());
        out->close();
    } else if (!out->close()) {
        failure = "write failed: " + or_unknown(out->geterror());
    }
    out.reset();

    std::error_code ec;
    if (failure.empty()) {
        fs::rename(tmp, path, ec);
        if (ec) failure = "cannot move the finished file into place: " + ec.message();
    }
    if (!failure.empty()) {
        fs::remove(tmp, ec);  // never leave a half-written file behind
        return make_error(failure, path);
    }
    return Ok{};
}

}  // namespace

Result<Image> oiio_read_image(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return make_error("file not found", path);
    if (fs::is_directory(path, ec)) return make_error("is a directory, not an image file", path);

    // Ask every reader for straight alpha: OIIO otherwise premultiplies PNG/TIFF colours by alpha.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path, &config);
    if (!in) return make_error("cannot read image: " + or_unknown(OIIO::geterror()), path);

    const OIIO::ImageSpec spec = in->spec();
    const auto close_with = [&](std::string message) -> Result<Image> {
        in->geterror();  // drop any pending message so OIIO does not print it at destruction
        in->close();
        return make_error(std::move(message), path);
    };
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
        return close_with("image has zero size (" + std::to_string(spec.width) + "x" +
                          std::to_string(spec.height) + ", " + std::to_string(spec.nchannels) + " channels)");
    }
    if (spec.width > kMaxImageDimension || spec.height > kMaxImageDimension) {
        return close_with("image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                          ", larger than the " + std::to_string(kMaxImageDimension) + " pixel limit");
    }
    if (spec.deep) return close_with("deep images are not supported");
    if (spec.depth > 1) return close_with("volume images are not supported");

    // Integer formats arrive normalised to 0..1 by OIIO's conversion to float; no colour transform.
    const int channels = std::min(spec.nchannels, 4);
    std::vector<float> stored(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                              static_cast<std::size_t>(channels));
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, stored.data())) {
        return close_with("cannot read pixels (corrupt or truncated file?): " + or_unknown(in->geterror()));
    }
    in->close();

    Image image = expand_to_rgba(stored, spec.width, spec.height, channels);
    if (const std::string where = first_non_finite(image); !where.empty()) {
        return make_error("non-finite pixel value at " + where, path);
    }
    return image;
}

Status oiio_write_png(const std::string& path, const Image& image, int bits) {
    if (bits != 8 && bits != 16) return make_error("PNG bit depth must be 8 or 16, not " + std::to_string(bits), path);
    if (Status ok = check_writable_image(path, image); !ok) return ok;

    // Quantise here rather than in OIIO so the rounding (nearest, no dither) is ours and exact.
    const double max_code = bits == 8 ? 255.0 : 65535.0;
    std::vector<uint16_t> codes(image.rgba.size());
    for (std::size_t i = 0; i < codes.size(); ++i) {
        const double v = std::clamp(static_cast<double>(image.rgba[i]), 0.0, 1.0);
        codes[i] = static_cast<uint16_t>(std::lround(v * max_code));
    }
    std::vector<uint8_t> bytes;
    if (bits == 8) bytes.assign(codes.begin(), codes.end());

    const OIIO::TypeDesc type = bits == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
    OIIO::ImageSpec spec(image.width, image.height, 4, type);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // alpha is straight: do not un-premultiply
    spec.attribute("png:compressionLevel", 6);    // pinned so OIIO default changes cannot alter bytes
    const void* pixels = bits == 8 ? static_cast<const void*>(bytes.data()) : static_cast<const void*>(codes.data());
    return write_atomically(path, "png", spec, type, pixels);
}

Status oiio_write_exr(const std::string& path, const Image& image) {
    if (Status ok = check_writable_image(path, image); !ok) return ok;

    constexpr float kMaxHalf = 65504.0f;  // a larger float would round to infinity in half
    std::vector<float> pixels(image.rgba.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = std::clamp(image.rgba[i], -kMaxHalf, kMaxHalf);

    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::HALF);
    spec.attribute("compression", "zip");
    // OIIO stamps the current time into the EXR capDate unless DateTime is already set; an empty
    // value is the only way to keep the bytes reproducible without claiming a false date.
    spec.attribute("DateTime", "");
    return write_atomically(path, "openexr", spec, OIIO::TypeDesc::FLOAT, pixels.data());
}

}  // namespace crtforge

// The module's one entry point: the table the main library looks up with dlsym.
extern "C" __attribute__((visibility("default"))) const crtforge::ImageIoModule* crtforge_image_io_module() {
    static const crtforge::ImageIoModule module{crtforge::kImageIoModuleVersion, &crtforge::oiio_read_image,
                                                &crtforge::oiio_write_png, &crtforge::oiio_write_exr};
    return &module;
}
