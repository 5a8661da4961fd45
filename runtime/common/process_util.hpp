// Small POSIX helpers shared by the engines that drive an external process (the Godot 3 engine,
// the Dawn engine): finding an executable, writing scratch files, waiting with a deadline,
// describing how a child ended, and building its environment.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "crtforge/diagnostic.hpp"

namespace crtforge::detail {

using ProcessClock = std::chrono::steady_clock;

// The executable `name` found on PATH, or "".
std::string find_on_path(const char* name);

// `text` without leading and trailing white space.
std::string trim(std::string text);

// Writes `size` bytes to `path` (truncating); an Input error naming the path on failure.
Status write_file(const std::filesystem::path& path, const void* data, std::size_t size);

// Waits for `pid` until `deadline`: its wait status, -1 if waitpid failed, nullopt if it still runs.
std::optional<int> wait_until(pid_t pid, ProcessClock::time_point deadline);

// "exit code 3", "signal 9 (Killed)".
std::string describe_status(int status);

struct SpawnSpec {
    std::string executable;               // absolute path; also argv[0]
    std::vector<std::string> args;        // argv[1..]
    std::vector<std::string> env;         // the whole environment
    int input_fd = -1;                    // becomes stdin; -1 = /dev/null
    int output_fd = -1;                   // becomes stdout and stderr; -1 = /dev/null
    std::optional<std::pair<int, int>> extra_fd;  // (fd here, fd number in the child)
};

// Starts the process with no blocked signals and default handlers; every descriptor not named in
// `spec` is closed in the child (crtforge opens them all O_CLOEXEC). An Input error if it cannot.
Result<pid_t> spawn(const SpawnSpec& spec);

// This process's environment with `overrides` set and every name in `dropped` removed.
std::vector<std::string> child_environment(const std::vector<std::pair<std::string, std::string>>& overrides,
                                           const std::vector<std::string>& dropped = {});

}  // namespace crtforge::detail
