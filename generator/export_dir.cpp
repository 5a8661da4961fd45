// An export directory replaced all at once: written in full beside --out, then swapped in, under
// a lock, so a reader never sees a manifest describing files that are missing, stale or another
// run's.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "crtforge/exporter.hpp"
#include "crtforge/files.hpp"

namespace crtforge {

namespace fs = std::filesystem;

namespace {

// flock() on a file beside the directory: released by the kernel when the process dies, so a
// killed export never leaves a lock held. The holder removes the file before it lets go, so none
// stays beside --out; a process that opened the file before that removal and locks it after finds
// its inode no longer at the path, and tries again on the new file.
class DirLock {
public:
    explicit DirLock(std::string path) : path_(std::move(path)) {
        for (int attempt = 0; attempt < 100; ++attempt) {
            fd_ = ::open(path_.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
            if (fd_ < 0) return;
            if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) return;  // held by another export
            struct stat held {}, named {};
            if (::fstat(fd_, &held) == 0 && ::stat(path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
                held.st_dev == named.st_dev) {
                locked_ = true;
                return;
            }
            ::close(fd_);  // removed by the holder we waited for: lock the file now at the path
            fd_ = -1;
        }
    }
    ~DirLock() {
        if (locked_) ::unlink(path_.c_str());  // while still held: see the class comment
        if (fd_ >= 0) ::close(fd_);
    }
    DirLock(const DirLock&) = delete;
    DirLock& operator=(const DirLock&) = delete;
    bool locked() const { return locked_; }

private:
    std::string path_;
    int fd_ = -1;
    bool locked_ = false;
};

bool same_contents(const std::string& dir, const std::map<std::string, std::string>& files) {
    std::error_code ec;
    size_t count = 0;
    for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
        if (it->is_regular_file(ec)) ++count;
    if (ec || count != files.size()) return false;
    for (const auto& [path, data] : files) {
        auto existing = read_text_file(dir + "/" + path);
        if (!existing.ok() || existing.value() != data) return false;
    }
    return true;
}

// The export's own list of what it wrote, beside its files: a later export replaces a folder only
// when it holds nothing else (a folder the user added files to, or that merely holds a file named
// manifest.json, is not crtforge's to delete).
constexpr const char* kIndexName = ".crtforge-export";
constexpr const char* kIndexHeader = "crtforge export: the files below are this folder's whole content\n";

std::string index_text(const std::map<std::string, std::string>& files) {
    std::string text = kIndexHeader;
    for (const auto& [path, data] : files) text.append(path).append("\n");
    return text;
}

// "" when every entry of `dir` is a file its index lists (or a folder holding one); otherwise why not.
std::string not_an_earlier_export(const fs::path& dir) {
    auto index = read_text_file((dir / kIndexName).string(), 16u << 20);
    if (!index.ok() || index.value().rfind(kIndexHeader, 0) != 0)
        return "is not a crtforge export (it has no " + std::string(kIndexName) + " index)";
    std::set<std::string> listed, folders;
    std::istringstream lines(index.value().substr(std::string(kIndexHeader).size()));
    for (std::string line; std::getline(lines, line);)
        if (!line.empty()) {
            listed.insert(line);
            for (fs::path up = fs::path(line).parent_path(); !up.empty(); up = up.parent_path()) folders.insert(up.generic_string());
        }
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::none, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
        const std::string relative = fs::relative(it->path(), dir, ec).generic_string();
        if (relative == kIndexName) continue;
        const bool known = it->is_symlink(ec) ? false
                         : it->is_directory(ec) ? folders.count(relative) != 0
                         : it->is_regular_file(ec) && listed.count(relative) != 0;
        if (!known) return "holds '" + relative + "', which no crtforge export wrote";
    }
    if (ec) return "cannot be listed: " + ec.message();
    return "";
}

}  // namespace

Status write_export(const std::string& out, const std::map<std::string, std::string>& exported) {
    std::map<std::string, std::string> files = exported;
    files[kIndexName] = index_text(exported);
    std::error_code ec;
    const fs::path target = fs::path(out).lexically_normal();
    const fs::path name = target.filename().empty() ? target.parent_path().filename() : target.filename();
    const fs::path dir = target.filename().empty() ? target.parent_path() : target;
    const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
    if (name.empty() || name == "." || name == "..") return make_error("needs a directory name", out, 0, "--out");
    fs::create_directories(parent, ec);
    if (ec) return make_error("cannot create the parent directory: " + ec.message(), parent.string(), 0, "--out");
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) return make_error("exists and is not a directory", out, 0, "--out");
    // Replacing a folder that is not an earlier export would delete a user's files.
    if (fs::is_directory(dir, ec) && !fs::is_empty(dir, ec))
        if (const std::string why = not_an_earlier_export(dir); !why.empty())
            return make_error("exists and " + why + ": give a new or empty directory", out, 0, "--out");

    std::string hidden = ".";
    hidden.append(name.string()).append(".crtforge-");  // appends: GCC 12 misreads a chain of + here (-Wrestrict)
    const std::string base = (parent / hidden).string();
    DirLock lock(base + "lock");
    if (!lock.locked()) return make_error("another crtforge export is writing this directory; try again when it ends", out, 0, "--out");

    // Leftovers of an interrupted run: put back a directory moved aside but never replaced, then
    // remove half-written stagings.
    const fs::path old = base + "old";
    if (!fs::exists(dir, ec) && fs::is_directory(old, ec)) fs::rename(old, dir, ec);
    fs::remove_all(old, ec);
    const fs::path staging = base + "staging";
    fs::remove_all(staging, ec);

    if (fs::is_directory(dir, ec) && same_contents(dir.string(), files)) return Ok{};  // nothing to write
    for (const auto& [path, data] : files)
        if (auto s = write_file_atomic((staging / path).string(), data); !s.ok()) {
            fs::remove_all(staging, ec);
            return s;
        }
    // The swap: the old export aside, the new one in, the old one gone. A kill between the two
    // renames leaves the old export at <parent>/.<name>.crtforge-old, which the next run puts back.
    if (fs::exists(dir, ec)) {
        fs::rename(dir, old, ec);
        if (ec) {
            fs::remove_all(staging, ec);
            return make_error("cannot move the previous export aside: " + ec.message(), out, 0, "--out");
        }
    }
    fs::rename(staging, dir, ec);
    if (ec) {
        const std::string why = ec.message();
        std::error_code restore;
        fs::rename(old, dir, restore);
        fs::remove_all(staging, restore);
        return make_error("cannot move the new export into place: " + why, out, 0, "--out");
    }
    fs::remove_all(old, ec);
    return Ok{};
}

}  // namespace crtforge
