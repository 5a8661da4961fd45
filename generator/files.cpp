#include "crtforge/files.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace fs = std::filesystem;

namespace crtforge {

Result<std::string> read_text_file(const std::string& path, std::uintmax_t max_bytes) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (fs::is_directory(status)) return make_error("is a directory, expected a file", path);
    if (!ec && fs::exists(status) && !fs::is_regular_file(status)) return make_error("is not a regular file", path);
    if (max_bytes) {
        const std::uintmax_t size = fs::file_size(path, ec);
        if (!ec && size > max_bytes)
            return make_error("is " + std::to_string(size) + " bytes; at most " + std::to_string(max_bytes) + " are read", path);
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error(std::string("cannot open: ") + std::strerror(errno), path);
    std::ostringstream out;
    out << in.rdbuf();
    if (in.bad()) return make_error("read failed", path);
    // A file that grew after the size check is still bounded.
    if (max_bytes && out.str().size() > max_bytes) return make_error("is over " + std::to_string(max_bytes) + " bytes", path);
    return out.str();
}

Result<std::vector<std::string>> list_files(const std::string& dir, const std::string& ext) {
    std::error_code ec;
    std::vector<std::string> out;
    fs::directory_iterator it(dir, ec);
    if (ec) return make_error("cannot list directory: " + ec.message(), dir);
    for (const auto& entry : it) {
        const std::string name = entry.path().filename().string();
        if (name.size() <= ext.size() || name.compare(name.size() - ext.size(), ext.size(), ext) != 0) continue;
        if (name[0] == '.') continue;  // hidden: an editor's lock or backup (Emacs's .#name.toml links to nothing), not a file of ours
        // One named like a file of this kind but not one (a FIFO, a device, a link to nothing) is an
        // error, not a file silently left out.
        if (!entry.is_regular_file(ec)) return make_error("is not a regular file", dir + "/" + name);
        out.push_back(dir + "/" + name);
    }
    std::sort(out.begin(), out.end());
    return out;
}

Status write_file_atomic(const std::string& path, std::string_view data) {
    std::error_code ec;
    fs::path p(path);
    if (p.has_parent_path()) {
        fs::create_directories(p.parent_path(), ec);
        if (ec) return make_error("cannot create directory: " + ec.message(), p.parent_path().string());
    }
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    const ExitCleanup cleanup(tmp);
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) return make_error(std::string("cannot write: ") + std::strerror(errno), path);
        out.write(data.data(), static_cast<std::streamsize>(data.size()));
        out.close();
        if (!out) {
            fs::remove(tmp, ec);
            return make_error("write failed (disk full?)", path);
        }
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        return make_error("cannot rename into place: " + ec.message(), path);
    }
    return Ok{};
}

std::string file_stem(const std::string& path) { return fs::path(path).stem().string(); }

Result<TemporaryFolder> TemporaryFolder::create(const std::string& prefix) {
    std::error_code ec;
    std::filesystem::path base = std::filesystem::temp_directory_path(ec);
    if (ec) base = "/tmp";
    std::string pattern = (base / (prefix + "-XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr)
        return make_error("cannot create a temporary folder in '" + base.string() + "': " + std::strerror(errno));
    return TemporaryFolder(std::filesystem::path(pattern));
}

TemporaryFolder::~TemporaryFolder() {
    if (path_.empty()) return;
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

}  // namespace crtforge
