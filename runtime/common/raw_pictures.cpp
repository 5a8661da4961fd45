#include "runtime/common/raw_pictures.hpp"

#include <bit>
#include <fstream>

#include <fmt/format.h>

#include "runtime/common/process_util.hpp"

namespace crtforge::detail {

namespace fs = std::filesystem;

Status write_pictures(const fs::path& path, const std::vector<const Image*>& pictures) {
    static_assert(std::endian::native == std::endian::little, "the runners' files are little-endian float32");
    std::string bytes;
    for (const Image* image : pictures)
        bytes.append(reinterpret_cast<const char*>(image->rgba.data()), image->rgba.size() * sizeof(float));
    return write_file(path, bytes.data(), bytes.size());
}

Status write_pictures(const fs::path& path, const std::vector<Image>& pictures) {
    std::vector<const Image*> each;
    for (const Image& image : pictures) each.push_back(&image);
    return write_pictures(path, each);
}

Result<std::vector<Image>> read_pictures(const fs::path& path, int width, int height, std::size_t count, const std::string& writer) {
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path, ec);
    const std::size_t one = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4 * sizeof(float);
    if (ec || size != one * count)
        return make_validation_error(
            fmt::format("{} wrote {} bytes of pixels, expected {} picture(s) of {}x{}", writer, ec ? 0 : size, count, width, height));
    std::ifstream in(path, std::ios::binary);
    std::vector<Image> out;
    for (std::size_t i = 0; i < count; ++i) {
        Image image = Image::make(width, height);
        if (!in.read(reinterpret_cast<char*>(image.rgba.data()), static_cast<std::streamsize>(one)))
            return make_validation_error(fmt::format("{}'s pixels in '{}' could not be read", writer, path.string()));
        out.push_back(std::move(image));
    }
    return out;
}

}  // namespace crtforge::detail
