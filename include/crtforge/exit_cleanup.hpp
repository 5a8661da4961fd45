// What a process that must stop at once (a GPU draw that never finishes: the device cannot be
// torn down while it runs, so no destructor may run either) removes on its way out: the staging
// folders and temporary files of outputs still being written, so a run stopped this way leaves
// nothing half-made behind, as a refused run does.
#pragma once

#include <string>

namespace crtforge {

// While it lives, `path` (a file or a folder) is removed by exit_after_cleanup().
class ExitCleanup {
public:
    explicit ExitCleanup(std::string path);
    ~ExitCleanup();
    ExitCleanup(ExitCleanup&& other) noexcept : id_(other.id_) { other.id_ = 0; }
    ExitCleanup& operator=(ExitCleanup&&) = delete;
    ExitCleanup(const ExitCleanup&) = delete;

private:
    unsigned long long id_ = 0;
};

// Prints `line` and a newline on stderr, removes every path registered now, and ends the process
// with `code` without running destructors or atexit handlers (std::_Exit).
[[noreturn]] void exit_after_cleanup(const std::string& line, int code);

}  // namespace crtforge
