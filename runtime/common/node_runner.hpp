// A persistent Node.js helper spoken to in JSON lines: the Dawn engine's tools/wgsl-runner and the
// Godot 4 engine's tools/godot4-runner are both one. The process's stdin is one end of a
// socketpair (a write to a dead runner is EPIPE through MSG_NOSIGNAL, never SIGPIPE), replies
// come on a pipe passed as --reply-fd=N, and stdout + stderr go to a log file in a private
// temporary directory (the runners' own libraries print there), truncated before each request so
// its last line explains a crash. The first reply, sent without a request, says whether start-up
// worked. Not thread-safe: the owner serialises requests.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "crtforge/diagnostic.hpp"
#include "crtforge/files.hpp"

namespace crtforge::detail {

struct NodeRunnerSpec {
    std::string name;                    // "the Dawn runner": the subject of every error
    std::filesystem::path script;        // the .mjs to run
    std::vector<std::string> args;       // after the script (--reply-fd is added)
    std::vector<std::pair<std::string, std::string>> env;  // set in the runner's environment
    int start_seconds = 60;              // for the start-up reply
    // Log lines that explain nothing (start-up banners); skipped when describing a crash.
    std::function<bool(const std::string&)> ignore_log_line;
};

class NodeRunner {
public:
    // A private temporary directory named after `scratch_prefix` ("crtforge-dawn") is made now.
    static Result<std::unique_ptr<NodeRunner>> create(NodeRunnerSpec spec, const std::string& scratch_prefix);
    ~NodeRunner();
    NodeRunner(const NodeRunner&) = delete;
    NodeRunner& operator=(const NodeRunner&) = delete;

    // The private directory for the files a request names; removed with the runner.
    const std::filesystem::path& scratch() const { return scratch_.path(); }
    bool running() const { return pid_ > 0; }

    // Starts the process and returns its start-up reply (which may say ok: false; the caller
    // explains it). A process that cannot start or gives no reply is an Input error.
    Result<nlohmann::json> start();
    // Sends one request and waits up to `seconds` for its reply, (re)starting the runner first
    // when it is not running (`started` is then called with the start-up reply, which must say
    // ok). A runner that dies, stalls or answers garbage is killed: a Validation error.
    Result<nlohmann::json> request(const nlohmann::json& message, const char* during, int seconds,
                                   const std::function<Status(const nlohmann::json&)>& started = {});
    // Ends the runner: EOF on stdin first, SIGKILL after 2 s (at once with `kill`); reaped.
    std::optional<int> stop(bool kill);

private:
    NodeRunner(NodeRunnerSpec spec, TemporaryFolder scratch);
    std::filesystem::path log_path() const { return scratch_.path() / "runner.log"; }
    std::string last_log_line() const;
    Diagnostic failed(const std::string& what);
    Result<nlohmann::json> read_reply(std::chrono::steady_clock::time_point deadline, int seconds, const char* during);

    NodeRunnerSpec spec_;
    TemporaryFolder scratch_;  // removed after the runner stops (members go after the destructor's body)
    pid_t pid_ = -1;
    int request_fd_ = -1;   // our end of the runner's stdin socketpair
    int reply_fd_ = -1;     // read end of the reply pipe
    int log_fd_ = -1;       // the runner's stdout + stderr file, opened here for truncation
    std::string pending_;   // reply bytes read past the last newline
};

}  // namespace crtforge::detail
