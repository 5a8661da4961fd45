#include "process_util.hpp"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <thread>

#include <fmt/core.h>

extern char** environ;

namespace crtforge::detail {

std::string find_on_path(const char* name) {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= dirs.size()) {
        std::size_t end = dirs.find(':', start);
        if (end == std::string::npos) end = dirs.size();
        // An empty PATH entry means the current directory.
        const std::string candidate = (end == start ? std::string(".") : dirs.substr(start, end - start)) + "/" + name;
        struct stat st {};
        if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0)
            return candidate;
        start = end + 1;
    }
    return {};
}

std::string trim(std::string text) {
    auto is_space = [](unsigned char c) { return std::isspace(c) != 0; };
    while (!text.empty() && is_space(static_cast<unsigned char>(text.back()))) text.pop_back();
    std::size_t first = 0;
    while (first < text.size() && is_space(static_cast<unsigned char>(text[first]))) ++first;
    return text.substr(first);
}

Status write_file(const std::filesystem::path& path, const void* data, std::size_t size) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (out && size > 0) out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) return make_error(fmt::format("cannot write '{}'", path.string()));
    return Ok{};
}

std::optional<int> wait_until(pid_t pid, ProcessClock::time_point deadline) {
    for (;;) {
        int status = 0;
        pid_t r = ::waitpid(pid, &status, WNOHANG);
        if (r == pid) return status;
        if (r < 0 && errno != EINTR) return -1;
        if (ProcessClock::now() >= deadline) return std::nullopt;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
}

std::string describe_status(int status) {
    if (WIFEXITED(status)) return fmt::format("exit code {}", WEXITSTATUS(status));
    if (WIFSIGNALED(status)) return fmt::format("signal {} ({})", WTERMSIG(status), ::strsignal(WTERMSIG(status)));
    return "unknown status";
}

std::vector<std::string> child_environment(const std::vector<std::pair<std::string, std::string>>& overrides,
                                           const std::vector<std::string>& dropped) {
    std::vector<std::string> env;
    for (char** e = environ; e && *e; ++e) {
        std::string entry = *e;
        const std::string name = entry.substr(0, entry.find('='));
        const bool replaced = std::find(dropped.begin(), dropped.end(), name) != dropped.end() ||
                              std::any_of(overrides.begin(), overrides.end(), [&](const auto& o) { return o.first == name; });
        if (!replaced) env.push_back(std::move(entry));
    }
    for (const auto& [name, value] : overrides) env.push_back(name + "=" + value);
    return env;
}

}  // namespace crtforge::detail
