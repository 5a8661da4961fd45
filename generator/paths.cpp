// Locating the install prefix at run time (see crtforge/paths.hpp).
#include "crtforge/paths.hpp"

#include <cstdlib>
#include <filesystem>
#include <mutex>

namespace crtforge {

namespace fs = std::filesystem;

namespace {

std::string& explicit_prefix() {
    static std::string prefix;
    return prefix;
}

bool holds_data(const fs::path& prefix) {
    std::error_code ec;
    return fs::is_directory(prefix / "share" / "crtforge" / "templates", ec);
}

std::string find_prefix() {
    if (!explicit_prefix().empty()) return explicit_prefix();
    if (const char* env = std::getenv("CRTFORGE_PREFIX"); env && *env) return env;
    const fs::path exe = running_executable();
    if (exe.empty()) return {};
    // Only the executable's own folder and its parent: a deeper search could find a stranger's.
    for (const fs::path& dir : {exe.parent_path(), exe.parent_path().parent_path()})
        if (holds_data(dir)) return dir.string();
    return {};
}

}  // namespace

std::string running_executable() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string() : exe.string();
}

void set_install_prefix(const std::string& prefix) { explicit_prefix() = prefix; }

const std::string& install_prefix() {
    // Re-evaluated when set_install_prefix() changed the answer; otherwise found once.
    static std::mutex mutex;
    static std::string cached, cached_for;
    static bool found = false;
    std::lock_guard<std::mutex> lock(mutex);
    if (!found || cached_for != explicit_prefix()) {
        cached = find_prefix();
        cached_for = explicit_prefix();
        found = true;
    }
    return cached;
}

std::string data_dir() {
    const std::string& prefix = install_prefix();
    return prefix.empty() ? std::string() : (fs::path(prefix) / "share" / "crtforge").string();
}

std::string data_path(const std::string& relative) {
    const std::string dir = data_dir();
    if (dir.empty()) return relative;
    // A build tree's entries are links into the source tree: name the real files in diagnostics.
    std::error_code ec;
    const fs::path real = fs::canonical(fs::path(dir) / relative, ec);
    return ec ? (fs::path(dir) / relative).string() : real.string();
}

std::string module_path(const std::string& file) {
    const std::string& prefix = install_prefix();
    return (fs::path(prefix.empty() ? "." : prefix) / "lib" / "crtforge" / file).string();
}

}  // namespace crtforge
