// A floating-point RGBA image: what the render engine takes as input and hands back as output,
// and what the comparison code and the CPU reference renderer work on.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace crtforge {

// Largest width or height of any image crtforge reads, renders or writes: llvmpipe's largest 2D
// texture and render target (a 16384 x 16384 RGBA float image is already 4 GiB).
inline constexpr int kMaxImageDimension = 16384;

// The image memory budget: no image crtforge reads, renders or writes has more pixels than this
// (4096 x 4096 or 16384 x 1024: 256 MiB as RGBA float; the corpus's largest picture is a 4096 x 4096
// LUT). Readers check it from the file's header, before decoding; a render at the budget stays
// near 2 GiB (docs/hard-cases.md, "Memory": about 100-140 bytes per pixel at the peak).
inline constexpr std::size_t kMaxImagePixels = std::size_t{4096} * 4096;

// What one render may draw into: its display and each pass's framebuffer (4096 x 2304, 16:9 at
// 4096 wide; DCI 4K and UHD fit). Smaller than the image budget: a render keeps several
// framebuffers of a size, each read back, so this bounds it near 2 GiB (super-win at the limit).
inline constexpr std::size_t kMaxRenderPixels = std::size_t{4096} * 2304;

// What a render's source picture may have (an input file, a preset's source size, a golden's
// input size): 4 Mpx, 2560 x 1600. A render holds about sixteen float copies of pictures the
// source's size (the source, the passes at its scale, uploads, read-backs): measured with
// super-win, a 3840 x 2160 source reached 2.12 GB at a 3840 x 2160 display, a 2560 x 1440 one
// 1.91 GB at the render budget's 4096 x 2304. CRT sources are small; a larger picture is a still
// to scale down first.
inline constexpr std::size_t kMaxSourcePixels = std::size_t{2560} * 1600;

namespace detail {
// "is 9.6 Mpx, beyond the <budget> memory budget of 4.1 Mpx (e.g. <examples>)" when width x height
// is past `limit` pixels; empty when it fits (or is not a size at all: the caller refuses that).
inline std::string pixel_budget_error(long long width, long long height, std::size_t limit, const char* budget,
                                      const char* examples) {
    if (width <= 0 || height <= 0 || static_cast<unsigned long long>(width) * static_cast<unsigned long long>(height) <= limit)
        return {};
    auto megapixels = [](unsigned long long pixels) {  // to a tenth, rounded
        const unsigned long long tenths = (pixels + 50000) / 100000;
        return std::to_string(tenths / 10) + "." + std::to_string(tenths % 10);
    };
    return "is " + megapixels(static_cast<unsigned long long>(width) * static_cast<unsigned long long>(height)) + " Mpx, beyond the " +
           budget + " memory budget of " + megapixels(limit) + " Mpx (e.g. " + examples + ")";
}
}  // namespace detail

// Empty when a width x height image fits the budget, else the reason, for a message.
inline std::string image_budget_error(long long width, long long height) {
    return detail::pixel_budget_error(width, height, kMaxImagePixels, "image", "4096x4096");
}

// Empty when a render's source of width x height fits kMaxSourcePixels, else why not.
inline std::string source_budget_error(long long width, long long height) {
    return detail::pixel_budget_error(width, height, kMaxSourcePixels, "source", "2560x1600");
}

// Empty when a render (display or framebuffer) of width x height fits kMaxRenderPixels, else why not.
inline std::string render_budget_error(long long width, long long height) {
    return detail::pixel_budget_error(width, height, kMaxRenderPixels, "render", "4096x2304, 3840x2160");
}

// A picture an engine kept on its device instead of reading it back (RenderJob::keep_on_device):
// only the engine that made it can sample it. owner() says which (the engine's device as the
// engine knows it), so any other engine refuses it instead of reading texels that are not there.
class DevicePicture {
public:
    virtual ~DevicePicture() = default;
    virtual const void* owner() const = 0;
};

// Row-major, row 0 is the TOP row, 4 floats per pixel (R, G, B, A). Values are linear (never
// sRGB-encoded) and may exceed 1.0 or go below 0.0 (HDR intermediates), so nothing clamps them.
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgba;  // width * height * 4 floats; none where `device` holds the picture
    // Set where the picture stayed on an engine's device: rgba is then empty (not consistent()),
    // and only that engine's jobs may sample it.
    std::shared_ptr<const DevicePicture> device;

    // A width x height image filled with `fill`. Sizes <= 0 give an empty image.
    static Image make(int width, int height, std::array<float, 4> fill = {0.0f, 0.0f, 0.0f, 0.0f}) {
        Image image;
        if (width <= 0 || height <= 0) return image;
        image.width = width;
        image.height = height;
        image.rgba.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
        for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
            for (std::size_t c = 0; c < 4; ++c) image.rgba[i + c] = fill[c];
        }
        return image;
    }

    bool empty() const { return width <= 0 || height <= 0; }
    std::size_t pixel_count() const {
        return empty() ? 0 : static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    }
    // True when the pixel buffer matches the declared size (a malformed Image is a caller bug the
    // engine reports rather than reads past).
    bool consistent() const { return rgba.size() == pixel_count() * 4; }

    // Pointer to the 4 floats of pixel (x, y); no bounds check, like operator[].
    float* at(int x, int y) { return rgba.data() + offset(x, y); }
    const float* at(int x, int y) const { return rgba.data() + offset(x, y); }

    std::array<float, 4> pixel(int x, int y) const {
        const float* p = at(x, y);
        return {p[0], p[1], p[2], p[3]};
    }
    void set_pixel(int x, int y, std::array<float, 4> value) {
        float* p = at(x, y);
        for (std::size_t c = 0; c < 4; ++c) p[c] = value[c];
    }

private:
    std::size_t offset(int x, int y) const {
        return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4;
    }
};

// An image nobody changes any more, shared by reference: a scene's LUTs and pass outputs reach
// every pass that reads them without a copy, and an engine recognises a texture it has already
// uploaded by identity() (the same for as long as any copy of this handle lives). Made from an
// Image (moved in); reads as a const Image (a default one reads as empty).
class SharedImage {
public:
    SharedImage() = default;
    SharedImage(Image image) : image_(std::make_shared<const Image>(std::move(image))) {}  // NOLINT: implicit by design

    const Image& operator*() const { return image_ ? *image_ : none(); }
    const Image* operator->() const { return &**this; }
    // What an engine's upload cache holds to keep identity() from being reused by a new image.
    const std::shared_ptr<const Image>& identity() const { return image_; }

private:
    static const Image& none() {
        static const Image none;
        return none;
    }
    std::shared_ptr<const Image> image_;
};

}  // namespace crtforge
