// Image file I/O on top of OpenImageIO, built as a loadable module (see image_io_module.hpp). OIIO
// reports errors as strings that must be fetched (or it complains at shutdown); every fetched
// message is folded into a one-line Diagnostic.
#include "crtforge/runtime/image_io.hpp"
#include "runtime/image/image_io_module.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include <OpenImageIO/filesystem.h>
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
// Pixels read with `channels` channels into the first slots of each RGBA pixel, completed in place:
// grey (1 or 2 channels) fills R, G and B; a missing alpha is 1. No second full-size copy.
void complete_rgba(Image& image, int channels) {
    const std::size_t count = image.pixel_count();
    for (std::size_t p = 0; p < count; ++p) {
        float* d = image.rgba.data() + p * 4;
        if (channels <= 2) {
            d[3] = channels == 2 ? d[1] : 1.0f;
            d[1] = d[2] = d[0];
        } else if (channels == 3) {
            d[3] = 1.0f;
        }
    }
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

// Writes all of `bytes` to a new file at `path`; every write() and the close() are checked, so a
// full disk or a file-size limit is an error, never a truncated file reported as written.
std::string write_all(const std::string& path, const std::vector<unsigned char>& bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return std::string("cannot open for writing: ") + std::strerror(errno);
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const std::string why = n < 0 ? std::strerror(errno) : "no progress";
            ::close(fd);
            return "write failed after " + std::to_string(done) + " of " + std::to_string(bytes.size()) + " bytes: " + why;
        }
        done += static_cast<size_t>(n);
    }
    if (::close(fd) != 0) return std::string("write failed at close: ") + std::strerror(errno);
    return {};
}

// Encodes `pixels` (of `pixel_type`, RGBA, tightly packed) with the OIIO writer for `format_name`
// into memory, writes the bytes to a temporary file beside `path` with checked writes, then renames
// it into place. (OIIO's own file writing does not report a short write.) The spec carries no
// attributes beyond the ones set here, so nothing time- or host-dependent reaches the file.
Status write_atomically(const std::string& path, const char* format_name, const OIIO::ImageSpec& spec,
                        OIIO::TypeDesc pixel_type, const void* pixels) {
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format_name);
    if (!out) return make_error("OpenImageIO has no " + std::string(format_name) + " writer: " + or_unknown(OIIO::geterror()), path);
    if (!out->supports("ioproxy")) return make_error("OpenImageIO's " + std::string(format_name) + " writer cannot encode to memory", path);

    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput proxy(encoded);
    std::string failure;
    if (!out->set_ioproxy(&proxy) || !out->open(tmp, spec)) {
        failure = "cannot encode: " + or_unknown(out->geterror());
    } else if (!out->write_image(pixel_type, pixels)) {
        failure = "encoding failed: " + or_unknown(out->geterror());
        out->close();
    } else if (!out->close()) {
        failure = "encoding failed: " + or_unknown(out->geterror());
    }
    out.reset();
    if (failure.empty()) failure = write_all(tmp, encoded);

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

static Result<Image> read_image_quietly(const std::string& path);

// While it lives, what the process writes to stderr goes to a temporary file instead: libpng's
// default error handler prints "libpng error: ..." itself before OIIO reports the failure, and a
// crtforge error is one line. Readers take turns (the redirection is process-wide); text captured
// from a read that succeeds (or from another thread meanwhile) is passed on to stderr unchanged.
class StderrCapture {
public:
    StderrCapture() : lock_(mutex()) {
        std::fflush(stderr);
        file_ = std::tmpfile();
        saved_ = file_ ? ::dup(STDERR_FILENO) : -1;
        if (saved_ >= 0) ::dup2(::fileno(file_), STDERR_FILENO);
    }
    ~StderrCapture() {
        const std::string text = release();
        if (!text.empty()) (void)!::write(STDERR_FILENO, text.data(), text.size());
    }
    // Restores stderr and returns what was captured (then nothing is passed on at destruction).
    std::string take() {
        std::string text = release();
        while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
        for (char& c : text)
            if (c == '\n') c = ' ';
        return text;
    }

private:
    static std::mutex& mutex() {
        static std::mutex m;
        return m;
    }
    std::string release() {
        std::string text;
        if (saved_ < 0) return text;
        std::fflush(stderr);
        ::dup2(saved_, STDERR_FILENO);
        ::close(saved_);
        saved_ = -1;
        std::rewind(file_);
        char chunk[512];
        size_t n = 0;
        while ((n = std::fread(chunk, 1, sizeof chunk, file_)) > 0 && text.size() < 4096) text.append(chunk, n);
        std::fclose(file_);
        file_ = nullptr;
        return text;
    }

    std::lock_guard<std::mutex> lock_;
    std::FILE* file_ = nullptr;
    int saved_ = -1;
};

Result<Image> oiio_read_image(const std::string& path) {
    StderrCapture captured;
    auto image = read_image_quietly(path);
    if (!image.ok()) {
        // libpng's own line, if any, is part of this one-line error, not a line before it.
        const std::string said = captured.take();
        Diagnostic d = image.error();
        if (!said.empty() && d.message.find(said) == std::string::npos) d.message += " (" + said + ")";
        return d;
    }
    return image;
}

static Result<Image> read_image_quietly(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return make_error("file not found", path);
    if (fs::is_directory(path, ec)) return make_error("is a directory, not an image file", path);
    // A FIFO or a device would block the reader or never end; links are followed to what they name.
    if (!fs::is_regular_file(path, ec)) return make_error("is not a regular file", path);

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
    if (const std::string over = image_budget_error(spec.width, spec.height); !over.empty())
        return close_with("image " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " " + over);
    if (spec.deep) return close_with("deep images are not supported");
    if (spec.depth > 1) return close_with("volume images are not supported");

    // Integer formats arrive normalised to 0..1 by OIIO's conversion to float; no colour transform.
    const int channels = std::min(spec.nchannels, 4);
    // The pixel buffer grows band by band as rows really decode: the header's size is only a claim,
    // and a 65-byte file claiming 8000x8000 must fail on its first band, not after committing 1 GB.
    // reserve() takes address space only; pages are touched when a band is resized in.
    Image image;
    image.width = spec.width;
    image.height = spec.height;
    const std::size_t row_floats = static_cast<std::size_t>(spec.width) * 4;
    image.rgba.reserve(row_floats * static_cast<std::size_t>(spec.height));
    // Bands of rows, so OIIO's own conversion buffers stay a band's size, not the image's.
    constexpr int kBandRows = 256;
    const bool tiled = spec.tile_width > 0;
    for (int y = 0; y < spec.height; y += tiled ? spec.height : kBandRows) {
        const int end = tiled ? spec.height : std::min(spec.height, y + kBandRows);
        image.rgba.resize(row_floats * static_cast<std::size_t>(end));
        float* band = image.at(0, y);
        const bool read = tiled ? in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, band, 4 * sizeof(float))
                                : in->read_scanlines(0, 0, spec.y + y, spec.y + end, 0, 0, channels, OIIO::TypeDesc::FLOAT, band,
                                                     4 * sizeof(float));
        if (!read) return close_with("cannot read pixels (corrupt or truncated file?): " + or_unknown(in->geterror()));
    }
    in->close();

    complete_rgba(image, channels);
    if (const std::string where = first_non_finite(image); !where.empty()) {
        return make_error("non-finite pixel value at " + where, path);
    }
    return image;
}

Status oiio_write_png(const std::string& path, const Image& image, int bits) {
    if (bits != 8 && bits != 16) return make_error("PNG bit depth must be 8 or 16, not " + std::to_string(bits), path);
    if (Status ok = check_writable_image(path, image); !ok) return ok;

    // Quantise here rather than in OIIO so the rounding (nearest, no dither) is ours and exact; into
    // the one buffer of the file's depth (a large image is not held twice more).
    const double max_code = bits == 8 ? 255.0 : 65535.0;
    auto code = [&](float value) { return std::lround(std::clamp(static_cast<double>(value), 0.0, 1.0) * max_code); };
    std::vector<uint16_t> codes;
    std::vector<uint8_t> bytes;
    if (bits == 8) {
        bytes.resize(image.rgba.size());
        for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(code(image.rgba[i]));
    } else {
        codes.resize(image.rgba.size());
        for (std::size_t i = 0; i < codes.size(); ++i) codes[i] = static_cast<uint16_t>(code(image.rgba[i]));
    }

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
