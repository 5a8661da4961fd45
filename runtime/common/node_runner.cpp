#include "runtime/common/node_runner.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include <fmt/core.h>

#include "runtime/common/process_util.hpp"

namespace crtforge::detail {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using json = nlohmann::json;

constexpr int kStopSeconds = 4;  // the Godot 4 driver closes Chromium within 2.5 s
constexpr std::size_t kMaxReplyBytes = 64u << 20;

void close_fd(int& fd) {
    if (fd >= 0) ::close(fd);
    fd = -1;
}

}  // namespace

NodeRunner::NodeRunner(NodeRunnerSpec spec, TemporaryFolder scratch) : spec_(std::move(spec)), scratch_(std::move(scratch)) {}

Result<std::unique_ptr<NodeRunner>> NodeRunner::create(NodeRunnerSpec spec, const std::string& scratch_prefix) {
    auto scratch = TemporaryFolder::create(scratch_prefix);
    if (!scratch.ok()) return scratch.error();
    return std::unique_ptr<NodeRunner>(new NodeRunner(std::move(spec), std::move(scratch.value())));
}

NodeRunner::~NodeRunner() { stop(false); }

// The last meaningful line of the runner's log: Node's error, or the library's last complaint.
std::string NodeRunner::last_log_line() const {
    std::ifstream in(log_path());
    std::string line, last, error;
    while (std::getline(in, line)) {
        line = trim(line);
        if (line.empty() || line.rfind("Node.js v", 0) == 0) continue;
        if (spec_.ignore_log_line && spec_.ignore_log_line(line)) continue;
        if (line.find("Error") != std::string::npos && error.empty()) error = line;
        last = line;
    }
    return !error.empty() ? error : last;
}

std::optional<int> NodeRunner::stop(bool kill) {
    close_fd(request_fd_);
    std::optional<int> status;
    if (pid_ > 0) {
        if (!kill) status = wait_until(pid_, Clock::now() + std::chrono::seconds(kStopSeconds));
        if (!status) {
            ::kill(pid_, SIGKILL);
            status = wait_until(pid_, Clock::now() + std::chrono::seconds(10));
        }
        pid_ = -1;
    }
    close_fd(reply_fd_);
    close_fd(log_fd_);
    pending_.clear();
    return status;
}

Diagnostic NodeRunner::failed(const std::string& what) {
    std::optional<int> status = stop(true);
    const std::string log = last_log_line();
    return make_validation_error(fmt::format("{} {}{}{}", spec_.name, what,
                                             status ? " (" + describe_status(*status) + ")" : std::string(),
                                             log.empty() ? std::string() : ": " + log));
}

Result<json> NodeRunner::start() {
    stop(true);
    const std::string node = find_on_path("node");
    if (node.empty())
        return make_error(spec_.name + " needs Node.js: install the Debian packages nodejs and npm ('node' is not on PATH)");
    int sockets[2] = {-1, -1};
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) != 0)
        return make_error(fmt::format("socketpair() failed: {}", std::strerror(errno)));
    int replies[2] = {-1, -1};
    if (::pipe2(replies, O_CLOEXEC) != 0) {
        ::close(sockets[0]);
        ::close(sockets[1]);
        return make_error(fmt::format("pipe() failed: {}", std::strerror(errno)));
    }
    request_fd_ = sockets[0];
    reply_fd_ = replies[0];
    int child_stdin = sockets[1];
    int child_reply = replies[1];
    log_fd_ = ::open(log_path().c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    int child_log = ::open(log_path().c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    auto close_child_ends = [&] {
        close_fd(child_stdin);
        close_fd(child_reply);
        close_fd(child_log);
    };
    if (log_fd_ < 0 || child_log < 0) {
        const std::string why = std::strerror(errno);
        close_child_ends();
        stop(true);
        return make_error(fmt::format("cannot write '{}': {}", log_path().string(), why));
    }
    // The reply pipe becomes descriptor 3 (4 if it already is 3: dup2 onto itself would keep
    // O_CLOEXEC set and the runner would lose it).
    const int reply_number = child_reply == 3 ? 4 : 3;
    SpawnSpec spawn_spec;
    spawn_spec.executable = node;
    spawn_spec.args = {spec_.script.string()};
    spawn_spec.args.insert(spawn_spec.args.end(), spec_.args.begin(), spec_.args.end());
    spawn_spec.args.push_back(fmt::format("--reply-fd={}", reply_number));
    spawn_spec.env = child_environment(spec_.env);
    spawn_spec.input_fd = child_stdin;
    spawn_spec.output_fd = child_log;
    spawn_spec.extra_fd = {{child_reply, reply_number}};
    auto child = spawn(spawn_spec);
    close_child_ends();
    if (!child.ok()) {
        stop(true);
        return child.error();
    }
    pid_ = child.value();
    auto ready = read_reply(Clock::now() + std::chrono::seconds(spec_.start_seconds), spec_.start_seconds, "start");
    if (!ready.ok()) {
        Diagnostic d = ready.error();
        d.kind = ErrorKind::Input;  // a runner that cannot start is the machine's problem
        return d;
    }
    return ready;
}

Result<json> NodeRunner::read_reply(Clock::time_point deadline, int seconds, const char* during) {
    for (;;) {
        std::size_t newline;
        while ((newline = pending_.find('\n')) != std::string::npos) {
            std::string line = trim(pending_.substr(0, newline));
            pending_.erase(0, newline + 1);
            if (line.empty()) continue;
            json parsed = json::parse(line, nullptr, false);
            if (parsed.is_discarded() || !parsed.is_object())
                return failed(fmt::format("sent a reply that is not a JSON object during {} ('{}')", during, line.substr(0, 200)));
            return parsed;
        }
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) return failed(fmt::format("gave no reply within {} s during {} and was killed", seconds, during));
        pollfd p{reply_fd_, POLLIN, 0};
        const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
        if (r < 0 && errno != EINTR) return failed(fmt::format("could not be read: {}", std::strerror(errno)));
        if (r <= 0) continue;
        char buffer[65536];
        const ssize_t n = ::read(reply_fd_, buffer, sizeof buffer);
        if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
        if (n <= 0) return failed(fmt::format("exited during {}", during));
        pending_.append(buffer, static_cast<std::size_t>(n));
        if (pending_.size() > kMaxReplyBytes) return failed("sent a reply larger than 64 MiB");
    }
}

Result<json> NodeRunner::request(const json& message, const char* during, int seconds,
                                 const std::function<Status(const json&)>& started) {
    if (pid_ <= 0) {
        auto ready = start();
        if (!ready.ok()) return ready.error();
        if (started)
            if (auto s = started(ready.value()); !s.ok()) return s.error();
    }
    if (log_fd_ >= 0 && ::ftruncate(log_fd_, 0) != 0) {
        // A log that cannot be truncated only loses its use for diagnostics.
    }
    const std::string line = message.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
    const auto deadline = Clock::now() + std::chrono::seconds(seconds);
    std::size_t sent = 0;
    while (sent < line.size()) {
        const ssize_t n = ::send(request_fd_, line.data() + sent, line.size() - sent, MSG_NOSIGNAL);
        if (n > 0) {
            sent += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && errno == EAGAIN) {
            pollfd p{request_fd_, POLLOUT, 0};
            ::poll(&p, 1, 100);
            if (Clock::now() < deadline) continue;
        }
        return failed(fmt::format("stopped taking requests ({})", n < 0 ? std::strerror(errno) : "timeout"));
    }
    return read_reply(deadline, seconds, during);
}

}  // namespace crtforge::detail
