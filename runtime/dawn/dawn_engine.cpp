// The Dawn engine: one persistent `node tools/wgsl-runner/runner.mjs` process per engine, spoken
// to in JSON lines, with the shader, pixels and uniform bytes exchanged as files in a private
// temporary directory.
//
// The runner's descriptors: stdin is one end of a socketpair (so a write to a dead runner is
// EPIPE through MSG_NOSIGNAL, never SIGPIPE), replies come on a pipe passed as --reply-fd, and
// stdout + stderr go to a log file in the temporary directory. dawn.node prints its own messages
// (compilation logs, uncaptured errors, start-up warnings) on stdout, so stdout cannot carry the
// replies. The log is truncated before each request and its last line explains a crash.
#include "crtforge/runtime/dawn_engine.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <chrono>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "crtforge/paths.hpp"
#include "runtime/common/job_checks.hpp"
#include "runtime/common/process_util.hpp"

extern char** environ;


namespace crtforge {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using detail::child_environment;
using detail::spawn;
using detail::SpawnSpec;
using detail::describe_status;
using detail::find_on_path;
using detail::trim;
using detail::wait_until;
using detail::write_file;
using json = nlohmann::json;
using detail::job_error;

constexpr const char* kWebgpuVersion = "0.6.2";  // tools/wgsl-runner/package.json pins it
constexpr int kMaxExtent = kMaxImageDimension;    // llvmpipe's maxTextureDimension2D
constexpr int kStartSeconds = 60;
constexpr int kRequestSeconds = 120;
constexpr int kStopSeconds = 2;
constexpr std::size_t kMaxReplyBytes = 64u << 20;

// ---- small helpers (the process ones are shared with the Godot 3 engine: process_util.hpp) ----

void close_fd(int& fd) {
    if (fd >= 0) ::close(fd);
    fd = -1;
}

// "" when the npm package is in place at the pinned version, else why not.
std::string webgpu_package_problem(const fs::path& runner_dir) {
    const fs::path manifest = runner_dir / "node_modules" / "webgpu" / "package.json";
    std::ifstream in(manifest);
    if (!in) return fmt::format("the npm package 'webgpu' is not installed (no '{}')", manifest.string());
    json parsed = json::parse(in, nullptr, false);
    if (parsed.is_discarded() || !parsed.is_object() || !parsed.contains("version") || !parsed["version"].is_string())
        return fmt::format("'{}' is not a readable package.json", manifest.string());
    const std::string version = parsed["version"].get<std::string>();
    if (version != kWebgpuVersion)
        return fmt::format("the npm package 'webgpu' in '{}' is version {}, crtforge pins {}",
                           (runner_dir / "node_modules").string(), version, kWebgpuVersion);
    return {};
}

// What this machine lacks to run the Dawn runner at all, before anything starts.
Status runner_setup(const fs::path& runner_dir) {
    if (find_on_path("node").empty())
        return make_error("Dawn rendering needs Node.js: install the Debian packages nodejs and npm ('node' is not on PATH)");
    const fs::path script = runner_dir / "runner.mjs";
    std::error_code ec;
    if (!fs::is_regular_file(script, ec)) return make_error(fmt::format("the WGSL runner is missing: no '{}'", script.string()));
    if (const std::string problem = webgpu_package_problem(runner_dir); !problem.empty())
        return make_error(problem + ": run scripts/setup.sh");
    return Ok{};
}

const char* format_name(OutputFormat format) {
    switch (format) {
        case OutputFormat::Rgba8Unorm: return "rgba8unorm";
        case OutputFormat::Rgba8Srgb: return "rgba8unorm-srgb";
        case OutputFormat::Rgba16Float: return "rgba16float";
    }
    return "?";
}

const char* filter_name(SamplerFilter filter) { return filter == SamplerFilter::Linear ? "linear" : "nearest"; }

// WebGPU's address modes.
const char* wrap_name(WrapMode wrap) {
    switch (wrap) {
        case WrapMode::ClampToEdge: return "clamp-to-edge";
        case WrapMode::Repeat: return "repeat";
        case WrapMode::MirroredRepeat: return "mirror-repeat";
    }
    return "?";
}

Status check_job(const DawnJob& job) {
    if (trim(job.wgsl).empty()) return job_error("the WGSL module is empty", "wgsl");
    if (job.vertex_entry.empty()) return job_error("the vertex entry point name is empty", "vertex_entry");
    if (job.fragment_entry.empty()) return job_error("the fragment entry point name is empty", "fragment_entry");
    const detail::JobLimits limits{kMaxExtent, kMaxExtent, kMaxExtent, "Dawn", "maxTextureDimension2D"};
    if (auto s = detail::check_job_extent(job.width, job.height, job.uses_texture ? job.input : Image{}, limits); !s.ok())
        return s;
    if (auto s = detail::check_texture_images(job.textures, limits); !s.ok()) return s;
    if (auto s = detail::check_viewport(job.viewport, job.width, job.height); !s.ok()) return s;
    if (auto s = detail::check_clear_color(job.clear_color); !s.ok()) return s;
    if (job.format != OutputFormat::Rgba8Unorm && job.format != OutputFormat::Rgba8Srgb &&
        job.format != OutputFormat::Rgba16Float)
        return job_error("unknown output format", "format");
    std::vector<detail::BindingUse> used;
    if (!job.uniform_data.empty()) used.push_back({job.uniform_binding, "uniform_binding"});
    if (job.uses_texture) {
        used.push_back({job.texture_binding, "texture_binding"});
        used.push_back({job.sampler_binding, "sampler_binding"});
    }
    for (std::size_t i = 0; i < job.textures.size(); ++i) {
        used.push_back({job.textures[i].binding, detail::texture_field(i, "binding")});
        used.push_back({job.textures[i].sampler_binding, detail::texture_field(i, "sampler_binding")});
    }
    for (const detail::BindingUse& use : used) {
        if (use.number > 1000)
            return job_error(fmt::format("binding {} is above 1000 (Dawn's maxBindingsPerBindGroup)", use.number),
                             use.field);
    }
    return detail::check_distinct_bindings(used);
}

}  // namespace

// ---- the runner process -----------------------------------------------------------------------

struct DawnEngine::Impl {
    mutable std::mutex mutex;
    fs::path runner_dir = fs::path(data_path("tools/wgsl-runner")).lexically_normal();
    fs::path scratch;          // private temporary directory, removed by the destructor
    pid_t pid = -1;            // the runner, or -1
    int request_fd = -1;       // our end of the runner's stdin socketpair
    int reply_fd = -1;         // read end of the reply pipe
    int log_fd = -1;           // the runner's stdout + stderr file, opened here for truncation
    std::string pending;       // reply bytes read past the last newline
    std::string description;   // from the runner's start-up reply

    ~Impl() {
        stop(false);
        if (!scratch.empty()) {
            std::error_code ec;
            fs::remove_all(scratch, ec);
        }
    }

    fs::path log_path() const { return scratch / "runner.log"; }

    // The last meaningful line of the runner's log: Node's error, or Dawn's last complaint.
    std::string last_log_line() const {
        std::ifstream in(log_path());
        std::string line, last, error;
        while (std::getline(in, line)) {
            line = trim(line);
            if (line.empty() || line.rfind("Node.js v", 0) == 0 || line.find("artificially reduced") != std::string::npos)
                continue;
            if (line.find("Error") != std::string::npos && error.empty()) error = line;
            last = line;
        }
        return !error.empty() ? error : last;
    }

    // Ends the runner: EOF on stdin first (it destroys its device and exits), SIGKILL after
    // kStopSeconds or at once with `kill`; always reaped. The exit status, if it was reaped.
    std::optional<int> stop(bool kill) {
        close_fd(request_fd);
        std::optional<int> status;
        if (pid > 0) {
            if (!kill) status = wait_until(pid, Clock::now() + std::chrono::seconds(kStopSeconds));
            if (!status) {
                ::kill(pid, SIGKILL);
                status = wait_until(pid, Clock::now() + std::chrono::seconds(10));
            }
            pid = -1;
        }
        close_fd(reply_fd);
        close_fd(log_fd);
        pending.clear();
        return status;
    }

    // The runner is gone or stuck: kill it and describe what happened.
    Diagnostic runner_failed(const std::string& what) {
        std::optional<int> status = stop(true);
        const std::string log = last_log_line();
        return make_validation_error(fmt::format("the Dawn runner {}{}{}", what,
                                                 status ? " (" + describe_status(*status) + ")" : std::string(),
                                                 log.empty() ? std::string() : ": " + log));
    }

    Status start() {
        if (auto setup = runner_setup(runner_dir); !setup.ok()) return setup;
        const std::string node = find_on_path("node");
        const fs::path script = runner_dir / "runner.mjs";

        int sockets[2] = {-1, -1};
        if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) != 0)
            return make_error(fmt::format("socketpair() failed: {}", std::strerror(errno)));
        int replies[2] = {-1, -1};
        if (::pipe2(replies, O_CLOEXEC) != 0) {
            ::close(sockets[0]);
            ::close(sockets[1]);
            return make_error(fmt::format("pipe() failed: {}", std::strerror(errno)));
        }
        request_fd = sockets[0];
        reply_fd = replies[0];
        int child_stdin = sockets[1];
        int child_reply = replies[1];
        log_fd = ::open(log_path().c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
        int child_log = ::open(log_path().c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
        auto close_child_ends = [&] {
            close_fd(child_stdin);
            close_fd(child_reply);
            close_fd(child_log);
        };
        if (log_fd < 0 || child_log < 0) {
            const std::string why = std::strerror(errno);
            close_child_ends();
            stop(true);
            return make_error(fmt::format("cannot write '{}': {}", log_path().string(), why));
        }

        // The reply pipe becomes descriptor 3 (4 if it already is 3: dup2 onto itself would keep
        // O_CLOEXEC set and the runner would lose it).
        const int reply_number = child_reply == 3 ? 4 : 3;
        SpawnSpec spec;
        spec.executable = node;
        spec.args = {script.string(), fmt::format("--reply-fd={}", reply_number)};
        spec.env = child_environment({{"EGL_PLATFORM", "surfaceless"}});  // Mesa EGL, no window system
        spec.input_fd = child_stdin;
        spec.output_fd = child_log;
        spec.extra_fd = {{child_reply, reply_number}};
        auto child = spawn(spec);
        close_child_ends();
        if (!child.ok()) {
            stop(true);
            return child.error();
        }
        pid = child.value();

        // The runner's first line says whether Dawn found an adapter.
        auto ready = read_reply(Clock::now() + std::chrono::seconds(kStartSeconds), "start");
        if (!ready.ok()) {
            Diagnostic d = ready.error();
            d.kind = ErrorKind::Input;  // a runner that cannot start is the machine's problem
            return d;
        }
        const json& r = ready.value();
        if (!r.value("ok", false)) {
            const std::string kind = r.value("kind", "");
            const std::string error = r.value("error", "unknown error");
            stop(false);
            if (kind == "no-adapter")
                return make_error(fmt::format("{}: Dawn renders with Mesa's OpenGL ES 3.1+ through EGL with "
                                              "EGL_PLATFORM=surfaceless (the Debian packages libegl-mesa0 and libgl1-mesa-dri)",
                                              error));
            return make_error("the Dawn runner did not start: " + error);
        }
        const json info = r.value("info", json::object());
        description = fmt::format("Dawn (npm webgpu {}), {} backend, {}: {} ({})", kWebgpuVersion,
                                  info.value("backend", "?"), info.value("featureLevel", "?"), info.value("device", "?"),
                                  info.value("description", "?"));
        return Ok{};
    }

    // The next non-empty reply line, parsed.
    Result<json> read_reply(Clock::time_point deadline, const char* during) {
        for (;;) {
            std::size_t newline;
            while ((newline = pending.find('\n')) != std::string::npos) {
                std::string line = trim(pending.substr(0, newline));
                pending.erase(0, newline + 1);
                if (line.empty()) continue;
                json parsed = json::parse(line, nullptr, false);
                if (parsed.is_discarded() || !parsed.is_object()) {
                    return runner_failed(fmt::format("sent a reply that is not a JSON object during {} ('{}')", during,
                                                     line.substr(0, 200)));
                }
                return parsed;
            }
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
            if (left <= 0)
                return runner_failed(fmt::format("gave no reply within {} s during {} and was killed",
                                                 std::string(during) == "start" ? kStartSeconds : kRequestSeconds, during));
            pollfd p{reply_fd, POLLIN, 0};
            const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
            if (r < 0 && errno != EINTR) return runner_failed(fmt::format("could not be read: {}", std::strerror(errno)));
            if (r <= 0) continue;
            char buffer[65536];
            const ssize_t n = ::read(reply_fd, buffer, sizeof buffer);
            if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
            if (n <= 0) return runner_failed(fmt::format("exited during {}", during));
            pending.append(buffer, static_cast<std::size_t>(n));
            if (pending.size() > kMaxReplyBytes) return runner_failed("sent a reply larger than 64 MiB");
        }
    }

    // Sends one request and waits for its reply, (re)starting the runner first if needed.
    Result<json> request(const json& message, const char* during) {
        if (pid <= 0) {
            if (auto s = start(); !s.ok()) return s.error();
        }
        if (log_fd >= 0 && ::ftruncate(log_fd, 0) != 0) {
            // A log that cannot be truncated only loses its use for diagnostics.
        }
        const std::string line = message.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
        const auto deadline = Clock::now() + std::chrono::seconds(kRequestSeconds);
        std::size_t sent = 0;
        while (sent < line.size()) {
            const ssize_t n = ::send(request_fd, line.data() + sent, line.size() - sent, MSG_NOSIGNAL);
            if (n > 0) {
                sent += static_cast<std::size_t>(n);
                continue;
            }
            if (n < 0 && errno == EINTR) continue;
            if (n < 0 && errno == EAGAIN) {
                pollfd p{request_fd, POLLOUT, 0};
                ::poll(&p, 1, 100);
                if (Clock::now() < deadline) continue;
            }
            return runner_failed(fmt::format("stopped taking requests ({})", n < 0 ? std::strerror(errno) : "timeout"));
        }
        return read_reply(deadline, during);
    }
};

DawnEngine::DawnEngine(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

DawnEngine::~DawnEngine() = default;

Status DawnEngine::check_setup() { return runner_setup(fs::path(data_path("tools/wgsl-runner")).lexically_normal()); }

Result<std::unique_ptr<DawnEngine>> DawnEngine::create() {
    try {
        auto impl = std::make_unique<Impl>();
        std::error_code ec;
        fs::path base = fs::temp_directory_path(ec);
        if (ec) base = "/tmp";
        std::string pattern = (base / "crtforge-dawn-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr)
            return make_error(fmt::format("cannot create a temporary directory in '{}': {}", base.string(),
                                          std::strerror(errno)));
        impl->scratch = pattern;
        if (auto s = impl->start(); !s.ok()) return s.error();
        return std::unique_ptr<DawnEngine>(new DawnEngine(std::move(impl)));
    } catch (const std::exception& e) {
        return make_error(fmt::format("the Dawn engine could not start: {}", e.what()));
    }
}

std::string DawnEngine::adapter_description() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->description;
}

Result<std::vector<WgslMessage>> DawnEngine::compile(const std::string& wgsl) {
    try {
        std::lock_guard lock(impl_->mutex);
        const fs::path shader = impl_->scratch / "shader.wgsl";
        if (auto s = write_file(shader, wgsl.data(), wgsl.size()); !s.ok()) return s.error();
        auto reply = impl_->request({{"op", "compile"}, {"wgsl", shader.string()}}, "compile");
        if (!reply.ok()) return reply.error();
        const json& r = reply.value();
        if (!r.value("ok", false)) {
            const std::string error = "the Dawn runner refused the compile request: " + r.value("error", std::string("?"));
            return r.value("kind", "") == "request" ? make_error(error) : make_validation_error(error);
        }
        std::vector<WgslMessage> messages;
        for (const json& m : r.value("messages", json::array())) {
            WgslMessage message;
            message.type = m.value("type", "");
            message.line = m.value("lineNum", 0);
            message.column = m.value("linePos", 0);
            message.text = m.value("message", "");
            messages.push_back(std::move(message));
        }
        return messages;
    } catch (const std::exception& e) {
        return make_validation_error(fmt::format("the Dawn runner's reply could not be read: {}", e.what()));
    }
}

Result<Image> DawnEngine::render(const DawnJob& job) {
    static_assert(std::endian::native == std::endian::little, "the runner's files are little-endian float32");
    if (auto s = check_job(job); !s.ok()) return s.error();
    try {
        std::lock_guard lock(impl_->mutex);
        const fs::path dir = impl_->scratch;
        const fs::path shader = dir / "shader.wgsl", input = dir / "input.f32", uniform = dir / "uniform.bin",
                       output = dir / "output.f32";
        if (auto s = write_file(shader, job.wgsl.data(), job.wgsl.size()); !s.ok()) return s.error();
        std::error_code ec;
        fs::remove(output, ec);
        json message = {
            {"op", "render"},
            {"wgsl", shader.string()},
            {"vertex_entry", job.vertex_entry},
            {"fragment_entry", job.fragment_entry},
            {"width", job.width},
            {"height", job.height},
            {"format", format_name(job.format)},
            {"filter", filter_name(job.filter)},
            {"wrap", wrap_name(job.wrap)},
            {"texture", job.uses_texture},
            {"uniform_binding", job.uniform_binding},
            {"texture_binding", job.texture_binding},
            {"sampler_binding", job.sampler_binding},
            {"output", output.string()},
            {"clear", {job.clear_color[0], job.clear_color[1], job.clear_color[2], job.clear_color[3]}},
        };
        if (!job.viewport.full())
            message["viewport"] = {job.viewport.x, job.viewport.y, job.viewport.width, job.viewport.height};
        if (!job.uniform_data.empty()) {
            if (auto s = write_file(uniform, job.uniform_data.data(), job.uniform_data.size()); !s.ok()) return s.error();
            message["uniform"] = uniform.string();
        }
        if (job.uses_texture && !job.input.empty()) {
            if (auto s = write_file(input, job.input.rgba.data(), job.input.rgba.size() * sizeof(float)); !s.ok())
                return s.error();
            message["input"] = input.string();
            message["input_width"] = job.input.width;
            message["input_height"] = job.input.height;
        }
        // Each extra texture travels as the input does: raw float32 RGBA in a file of its own.
        json textures = json::array();
        for (std::size_t i = 0; i < job.textures.size(); ++i) {
            const TextureInput& t = job.textures[i];
            json entry = {{"binding", t.binding},
                          {"sampler_binding", t.sampler_binding},
                          {"filter", filter_name(t.filter)},
                          {"wrap", wrap_name(t.wrap)}};
            if (!t.image.empty()) {
                const fs::path file = dir / fmt::format("texture{}.f32", i);
                if (auto s = write_file(file, t.image.rgba.data(), t.image.rgba.size() * sizeof(float)); !s.ok())
                    return s.error();
                entry["image"] = file.string();
                entry["width"] = t.image.width;
                entry["height"] = t.image.height;
            }
            textures.push_back(std::move(entry));
        }
        if (!textures.empty()) message["textures"] = std::move(textures);
        auto reply = impl_->request(message, "render");
        if (!reply.ok()) return reply.error();
        const json& r = reply.value();
        if (!r.value("ok", false)) {
            const std::string error = r.value("error", std::string("unknown error"));
            if (r.value("kind", "") == "request") return make_error("the Dawn runner refused the render request: " + error);
            const int line = r.value("line", 0), column = r.value("column", 0);
            if (line > 0) {
                Diagnostic d = make_validation_error("Dawn rejected the WGSL: " + error);
                d.line = line;
                d.column = column;
                return d;
            }
            return make_validation_error("Dawn rejected the render: " + error);
        }

        Image image = Image::make(job.width, job.height);
        const std::size_t expected = image.rgba.size() * sizeof(float);
        const std::uintmax_t size = fs::file_size(output, ec);
        std::ifstream in(output, std::ios::binary);
        if (ec || size != expected || !in.read(reinterpret_cast<char*>(image.rgba.data()), static_cast<std::streamsize>(expected)))
            return make_validation_error(fmt::format("the Dawn runner wrote {} bytes of pixels, expected {} for {}x{}",
                                                     ec ? 0 : size, expected, job.width, job.height));
        in.close();
        fs::remove(output, ec);
        return image;
    } catch (const std::exception& e) {
        return make_validation_error(fmt::format("the Dawn render failed: {}", e.what()));
    }
}

}  // namespace crtforge
