#include "crtforge/exit_cleanup.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>

namespace crtforge {

namespace {

struct Registry {
    std::mutex mutex;
    std::map<unsigned long long, std::string> paths;
    unsigned long long next = 1;
};

Registry& registry() {
    static Registry* r = new Registry;  // never destroyed: exit_after_cleanup may run during static teardown
    return *r;
}

}  // namespace

ExitCleanup::ExitCleanup(std::string path) {
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    id_ = r.next++;
    r.paths.emplace(id_, std::move(path));
}

ExitCleanup::~ExitCleanup() {
    if (id_ == 0) return;
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.paths.erase(id_);
}

void exit_after_cleanup(const std::string& line, int code) {
    Registry& r = registry();
    // Held to the end: no other thread registers a path meanwhile, and a second thread stopping
    // the process at the same moment (one waiting behind the same stuck queue) says nothing more.
    r.mutex.lock();
    std::fprintf(stderr, "%s\n", line.c_str());
    std::fflush(stderr);
    for (const auto& [id, path] : r.paths) {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    std::fflush(stdout);
    std::_Exit(code);
}

}  // namespace crtforge
