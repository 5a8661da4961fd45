// File helpers with Result errors, shared by the generator, validation and the CLI: reading a
// whole file, a sorted directory listing, and atomic writes (temp file + rename).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "crtforge/diagnostic.hpp"
#include "crtforge/exit_cleanup.hpp"

namespace crtforge {

// The whole file. A directory, a FIFO or a device is refused before it is opened (reading one
// would block or never end), and so is a file over `max_bytes` (0: no bound).
Result<std::string> read_text_file(const std::string& path, std::uintmax_t max_bytes = 0);
// The bound for data files crtforge writes and reads back (golden manifest, report shards, cache
// entries): far above any real one, far below what would exhaust memory.
inline constexpr std::uintmax_t kMaxDataFileBytes = std::uintmax_t{256} << 20;
// The files in dir whose names end with `ext`, sorted by name (deterministic order); hidden names
// (a leading '.') are left out. One so named that is not a regular file is an error naming it.
Result<std::vector<std::string>> list_files(const std::string& dir, const std::string& ext);
// Writes to "<path>.tmp-<pid>" then renames, so readers never see a half-written file; creates the
// parent directories.
Status write_file_atomic(const std::string& path, std::string_view data);
std::string file_stem(const std::string& path);  // "a/b/classic.toml" -> "classic"

// A fresh folder "<system temp>/<prefix>-XXXXXX" (mkdtemp), removed with everything in it when
// the object goes.
class TemporaryFolder {
public:
    static Result<TemporaryFolder> create(const std::string& prefix);
    TemporaryFolder(TemporaryFolder&& other) noexcept : path_(std::move(other.path_)), cleanup_(std::move(other.cleanup_)) { other.path_.clear(); }
    TemporaryFolder& operator=(TemporaryFolder&&) = delete;
    TemporaryFolder(const TemporaryFolder&) = delete;
    ~TemporaryFolder();
    const std::filesystem::path& path() const { return path_; }

private:
    explicit TemporaryFolder(std::filesystem::path path) : path_(std::move(path)), cleanup_(path_.string()) {}
    std::filesystem::path path_;
    ExitCleanup cleanup_;
};

}  // namespace crtforge
