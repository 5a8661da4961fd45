// The Godot 3 engine: write the job into a temporary directory, start a private Xvfb, run the
// runner project in tools/godot3-runner/ with godot3 on it, read the pixels back, and turn Godot's
// output into one-line diagnostics.
//
// Processes are started with posix_spawn from argument vectors (no shell, so paths may hold any
// character) and always waited for. xvfb-run is not used: it loses the command's exit status and
// leaves its Xvfb running when its own clean-up fails (seen on Debian 12), and its display-number
// probing races between concurrent runs; `Xvfb -displayfd` picks a free display itself.
#include "crtforge/runtime/godot3_engine.hpp"
#include "crtforge/files.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "crtforge/paths.hpp"
#include "runtime/common/godot_params.hpp"
#include "runtime/common/job_checks.hpp"
#include "runtime/common/process_util.hpp"

extern char** environ;


namespace crtforge {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using detail::job_error;
using detail::child_environment;
using detail::spawn;
using detail::SpawnSpec;
using detail::describe_status;
using detail::find_on_path;
using detail::trim;
using detail::wait_until;
using detail::write_file;

constexpr const char* kPackages = "the Debian packages godot3 and xvfb";
constexpr const char* kRunnerPrefix = "crtforge-godot3-runner: ";
constexpr const char* kOutputMagic = "CRTG3PX1";
constexpr std::size_t kOutputHeaderBytes = 24;
constexpr std::size_t kMaxLogBytes = 4u << 20;  // Godot's output kept for diagnostics
constexpr int kGodot3MaxExtent = kMaxImageDimension;  // the runner's limit too (tools/godot3-runner)
constexpr int kXvfbStartSeconds = 15;

// ---- small helpers --------------------------------------------------------------------------

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(std::move(line));
    }
    return lines;
}

bool contains_nocase(const std::string& text, const std::string& needle) {
    auto it = std::search(text.begin(), text.end(), needle.begin(), needle.end(), [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
    });
    return it != text.end();
}

Status write_text(const fs::path& path, const std::string& text) { return write_file(path, text.data(), text.size()); }

// ---- processes --------------------------------------------------------------------------------

struct Pipe {
    int read = -1, write = -1;
    ~Pipe() { close_both(); }
    void close_read() { if (read >= 0) ::close(read); read = -1; }
    void close_write() { if (write >= 0) ::close(write); write = -1; }
    void close_both() { close_read(); close_write(); }
};

Status open_pipe(Pipe& pipe) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return make_error(fmt::format("pipe() failed: {}", std::strerror(errno)));
    pipe.read = fds[0];
    pipe.write = fds[1];
    return Ok{};
}

// waitpid() that retries on EINTR; the wait status, or -1.
int wait_blocking(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) return -1;
    }
    return status;
}

// A started child that is stopped (signal, then SIGKILL after a grace period) and reaped when the
// guard goes out of scope, unless it was already reaped.
class ChildGuard {
public:
    ChildGuard(pid_t pid, int stop_signal) : pid_(pid), stop_signal_(stop_signal) {}
    ChildGuard(const ChildGuard&) = delete;
    ChildGuard& operator=(const ChildGuard&) = delete;
    ~ChildGuard() { stop(); }
    pid_t pid() const { return pid_; }
    void reaped() { pid_ = -1; }
    void stop() {
        if (pid_ <= 0) return;
        ::kill(pid_, stop_signal_);
        if (stop_signal_ == SIGKILL || !wait_until(pid_, Clock::now() + std::chrono::seconds(3))) {
            ::kill(pid_, SIGKILL);
            wait_blocking(pid_);
        }
        pid_ = -1;
    }

private:
    pid_t pid_;
    int stop_signal_;
};

// Reads `fd` until EOF (or, with `stop_at_newline`, a newline) or `deadline`; false on timeout.
// Keeps at most kMaxLogBytes.
bool read_until_eof(int fd, Clock::time_point deadline, std::string& out, bool stop_at_newline = false) {
    char buffer[8192];
    for (;;) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) return false;
        pollfd p{fd, POLLIN, 0};
        int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
        if (r < 0 && errno != EINTR) return true;
        if (r <= 0) continue;
        ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
        if (n <= 0) return true;
        if (out.size() < kMaxLogBytes) out.append(buffer, std::min<std::size_t>(static_cast<std::size_t>(n), kMaxLogBytes - out.size()));
        if (stop_at_newline && out.find('\n') != std::string::npos) return true;
    }
}

// ---- Xvfb -------------------------------------------------------------------------------------

struct XServer {
    std::unique_ptr<ChildGuard> process;
    std::string display;  // ":N"
};

Result<XServer> start_xvfb(const std::string& xvfb, const fs::path& scratch) {
    Pipe ready;
    if (auto s = open_pipe(ready); !s.ok()) return s.error();
    const int child_fd = ready.write == 3 ? 4 : 3;
    const fs::path log_path = scratch / "xvfb.log";
    int log_fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (log_fd < 0) return make_error(fmt::format("cannot write '{}': {}", log_path.string(), std::strerror(errno)));
    SpawnSpec spec;
    spec.executable = xvfb;
    // No -auth: the server accepts local clients only (-nolisten tcp), which is all Godot needs.
    spec.args = {"-displayfd", std::to_string(child_fd), "-screen", "0", "64x64x24", "-nolisten", "tcp"};
    spec.env = child_environment({}, {"XAUTHORITY"});
    spec.output_fd = log_fd;
    spec.extra_fd = std::make_pair(ready.write, child_fd);
    auto pid = spawn(spec);
    ::close(log_fd);
    ready.close_write();
    if (!pid.ok()) return pid.error();
    XServer server;
    server.process = std::make_unique<ChildGuard>(pid.value(), SIGTERM);

    // Xvfb writes the display number and a newline once it accepts connections.
    std::string number;
    const auto deadline = Clock::now() + std::chrono::seconds(kXvfbStartSeconds);
    read_until_eof(ready.read, deadline, number, true);
    number = trim(number);
    if (number.empty() || number.find_first_not_of("0123456789") != std::string::npos) {
        server.process->stop();
        std::ifstream log(log_path);
        std::string last, line;
        while (std::getline(log, line))
            if (!trim(line).empty()) last = trim(line);
        return make_error(fmt::format("Xvfb (from {}) did not start{}", kPackages,
                                      last.empty() ? std::string() : ": " + last));
    }
    server.display = ":" + number;
    return server;
}

// ---- job files --------------------------------------------------------------------------------

// The params file the runner reads (godot_params_json, pretty-printed).
Result<std::string> params_json(const std::map<std::string, Value>& params) {
    auto json = detail::godot_params_json(params);
    if (!json.ok()) return json.error();
    return json.value().dump(2) + "\n";
}

// Copies the runner project's files (not its folders) so Godot runs on a private copy.
Status copy_runner(const fs::path& from, const fs::path& to) {
    std::error_code ec;
    if (!fs::is_regular_file(from / "project.godot", ec))
        return make_error(fmt::format("the Godot 3 runner project is missing: no '{}'", (from / "project.godot").string()));
    fs::create_directories(to, ec);
    if (ec) return make_error(fmt::format("cannot create '{}': {}", to.string(), ec.message()));
    for (const fs::directory_entry& entry : fs::directory_iterator(from, ec)) {
        if (!entry.is_regular_file()) continue;
        fs::copy_file(entry.path(), to / entry.path().filename(), fs::copy_options::overwrite_existing, ec);
        if (ec) return make_error(fmt::format("cannot copy '{}': {}", entry.path().string(), ec.message()));
    }
    if (ec) return make_error(fmt::format("cannot list '{}': {}", from.string(), ec.message()));
    return Ok{};
}

Status check_job(const Godot3Job& job) {
    if (job.shader_code.empty()) return job_error("shader code is empty", "shader_code");
    const detail::JobLimits limits{kGodot3MaxExtent, kGodot3MaxExtent, kGodot3MaxExtent, "Godot 3", "the Godot 3 runner's limit"};
    if (auto s = detail::check_job_extent(job.width, job.height, job.input, limits); !s.ok()) return s;
    if (job.frames < 1 || job.frames > 1000)
        return job_error(fmt::format("frames must be between 1 and 1000; got {}", job.frames), "frames");
    if (job.timeout_seconds < 1)
        return job_error(fmt::format("timeout_seconds must be at least 1; got {}", job.timeout_seconds), "timeout_seconds");
    return Ok{};
}

// ---- reading Godot's output -------------------------------------------------------------------

// "SHADER ERROR: (null): Expected expression, found: PERIOD" + "   At: :3." ->
// "line 3: Expected expression, found: PERIOD".
std::string shader_error_text(const std::vector<std::string>& lines, std::size_t index) {
    std::string text = trim(lines[index].substr(lines[index].find("SHADER ERROR:") + std::strlen("SHADER ERROR:")));
    // Godot prefixes the shader's resource path, "(null)" for a shader made in a script.
    if (text.rfind("(null): ", 0) == 0) text = text.substr(8);
    if (index + 1 < lines.size()) {
        const std::string at = trim(lines[index + 1]);
        std::size_t colon = at.rfind(':');
        if (at.rfind("At:", 0) == 0 && colon != std::string::npos) {
            std::string number = at.substr(colon + 1);
            if (!number.empty() && number.back() == '.') number.pop_back();
            if (!number.empty() && number.find_first_not_of("0123456789") == std::string::npos)
                text = "line " + number + ": " + text;
        }
    }
    return text;
}

// The error Godot's output reports about the shader, if any: its own compiler's "SHADER ERROR",
// or the GL driver refusing the GLSL Godot generated from it.
std::optional<Diagnostic> shader_diagnostic(const std::vector<std::string>& lines) {
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].find("SHADER ERROR:") != std::string::npos)
            return make_validation_error("Godot 3 rejected the shader: " + shader_error_text(lines, i));
    }
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (!contains_nocase(lines[i], "compilation failed") && !contains_nocase(lines[i], "link failed")) continue;
        std::string detail = trim(lines[i]);
        for (std::size_t j = i + 1; j < lines.size() && j < i + 200; ++j) {
            if (contains_nocase(lines[j], "error")) {
                detail = trim(lines[j]);
                break;
            }
        }
        return make_validation_error("Godot 3's GL driver rejected the shader: " + detail);
    }
    return std::nullopt;
}

// The runner's own one-line message, or the last "ERROR:" line Godot printed that is not known noise.
std::string last_message(const std::vector<std::string>& lines) {
    for (const std::string& line : lines) {
        std::size_t at = line.find(kRunnerPrefix);
        if (at != std::string::npos) return trim(line.substr(at + std::strlen(kRunnerPrefix)));
    }
    std::string last;
    for (const std::string& line : lines) {
        const std::string t = trim(line);
        bool error = t.rfind("ERROR:", 0) == 0 || t.rfind("SCRIPT ERROR:", 0) == 0 || t.rfind("FATAL", 0) == 0;
        if (!error || contains_nocase(t, "locale") || contains_nocase(t, "make_dir_recursive")) continue;
        last = t;
    }
    return last;
}

Result<Image> read_output(const fs::path& path, int width, int height) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_validation_error("Godot 3 exited without writing the output pixels");
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t floats = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4;
    if (bytes.size() != kOutputHeaderBytes + floats * sizeof(float) ||
        std::memcmp(bytes.data(), kOutputMagic, 8) != 0)
        return make_validation_error(fmt::format("the Godot 3 runner wrote a malformed output file ({} bytes)", bytes.size()));
    uint32_t header[4];
    std::memcpy(header, bytes.data() + 8, sizeof header);
    if (header[0] != static_cast<uint32_t>(width) || header[1] != static_cast<uint32_t>(height))
        return make_validation_error(fmt::format("the Godot 3 runner wrote {}x{} pixels, expected {}x{}", header[0],
                                                 header[1], width, height));
    Image image = Image::make(width, height);
    std::memcpy(image.rgba.data(), bytes.data() + kOutputHeaderBytes, floats * sizeof(float));
    return image;
}

// What Godot's output of one job says: a shader rejected, the runner's own refusal by its exit
// code (2 = the job's params or files, 3 = the shader or the render, 4 = a runner script error),
// a crash (`exit_code` -1, `how` describing the signal), or a script error in the scene.
Status diagnose(const std::string& log, int exit_code, const std::string& how) {
    const std::vector<std::string> lines = split_lines(log);
    if (auto diagnostic = shader_diagnostic(lines)) return *diagnostic;
    const std::string message = last_message(lines);
    if (exit_code != 0) {
        if (exit_code == 2 && !message.empty()) return make_error("Godot 3 runner: " + message);
        if (exit_code == 3 && !message.empty()) return make_validation_error("Godot 3 runner: " + message);
        bool crashed = exit_code < 0 || log.find("handle_crash") != std::string::npos;
        if (exit_code == 4)  // the runner's own script failed: its SCRIPT ERROR line says where
            for (const std::string& line : lines)
                if (trim(line).rfind("SCRIPT ERROR:", 0) == 0) return make_validation_error("Godot 3 runner: " + trim(line));
        return make_validation_error(fmt::format("Godot 3 {} ({}){}", crashed ? "crashed" : "failed",
                                                 exit_code < 0 ? how : "exit code " + std::to_string(exit_code),
                                                 message.empty() ? std::string() : ": " + message));
    }
    // A scene's script error does not stop Godot: any the log shows fails the render.
    for (const std::string& line : lines)
        if (trim(line).rfind("SCRIPT ERROR:", 0) == 0)
            return make_validation_error("Godot 3: " + trim(line) + (message.empty() ? std::string() : " (" + message + ")"));
    return Ok{};
}

// Writes each project file under `project`; false when one is already there with other content.
Result<bool> add_project_files(const fs::path& project, const std::map<std::string, std::string>& files) {
    for (const auto& [path, data] : files) {
        const fs::path target = project / path;
        std::error_code ec;
        if (fs::exists(target, ec)) {
            std::ifstream in(target, std::ios::binary);
            std::string existing((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            if (existing != data) return false;
            continue;
        }
        fs::create_directories(target.parent_path(), ec);
        if (ec) return make_error(fmt::format("cannot create '{}': {}", target.parent_path().string(), ec.message()));
        if (auto s = write_text(target, data); !s.ok()) return s.error();
    }
    return true;
}

// The part of a render every mode shares: a private runner project in `dir` (plus the job's own
// files), an Xvfb, Godot run on it with `user_args`, and its output turned into diagnostics.
Status run_godot_on(const fs::path& dir, const fs::path& project, const std::vector<std::string>& user_args, int timeout_seconds,
                    std::string* log_out);

Status run_runner(const fs::path& dir, const std::map<std::string, std::string>& project_files,
                  const std::vector<std::string>& user_args, int timeout_seconds) {
    const fs::path project = dir / "project";
    if (auto s = copy_runner(data_path("tools/godot3-runner"), project); !s.ok()) return s;
    if (auto added = add_project_files(project, project_files); !added.ok()) return added.error();
    return run_godot_on(dir, project, user_args, timeout_seconds, nullptr);
}

// Godot 3 on `project` under a private Xvfb (scratch files in `dir`); its output in *log_out.
Status run_godot_on(const fs::path& dir, const fs::path& project, const std::vector<std::string>& user_args, int timeout_seconds,
                    std::string* log_out) {
    const std::string godot = find_on_path("godot3");
    const std::string xvfb = find_on_path("Xvfb");
    if (godot.empty() || xvfb.empty())
        return make_error(fmt::format("Godot 3 rendering needs {} ('{}' is not on PATH)", kPackages,
                                      godot.empty() ? "godot3" : "Xvfb"));
    auto server = start_xvfb(xvfb, dir);
    if (!server.ok()) return server.error();

    Pipe output;
    if (auto s = open_pipe(output); !s.ok()) return s;
    SpawnSpec spec;
    spec.executable = godot;
    spec.args = {"--path", project.string(), "--video-driver", "GLES3", "--audio-driver", "Dummy", "--"};
    spec.args.insert(spec.args.end(), user_args.begin(), user_args.end());
    // Godot's user:// and settings folders go to the scratch directory, not the user's home.
    spec.env = child_environment({{"DISPLAY", server.value().display},
                                  {"XDG_DATA_HOME", (dir / "data").string()},
                                  {"XDG_CONFIG_HOME", (dir / "config").string()}});
    spec.output_fd = output.write;
    auto pid = spawn(spec);
    output.close_write();
    if (!pid.ok()) return pid.error();
    ChildGuard godot_process(pid.value(), SIGKILL);

    const auto deadline = Clock::now() + std::chrono::seconds(timeout_seconds);
    std::string log;
    bool finished = read_until_eof(output.read, deadline, log);
    std::optional<int> status = finished ? wait_until(pid.value(), deadline) : std::nullopt;
    if (!status) {
        godot_process.stop();
        return make_validation_error(fmt::format("Godot 3 did not finish within {} s and was killed", timeout_seconds));
    }
    godot_process.reaped();
    server.value().process->stop();
    if (log_out) *log_out = log;

    if (WIFEXITED(*status)) return diagnose(log, WEXITSTATUS(*status), "");
    return diagnose(log, -1, describe_status(*status));
}

// The job's files in `dir` and the runner's arguments for it (output to dir/output.raw).
Result<std::vector<std::string>> shader_job_args(const Godot3Job& job, const fs::path& dir) {
    static_assert(std::endian::native == std::endian::little, "the runner's files are little-endian float32");
    if (auto s = check_job(job); !s.ok()) return s.error();
    auto params = params_json(job.params);
    if (!params.ok()) return params.error();
    std::vector<std::string> user_args = {
        "--shader=" + (dir / "shader.gdshader").string(),
        "--width=" + std::to_string(job.width),
        "--height=" + std::to_string(job.height),
        std::string("--filter=") + (job.filter == SamplerFilter::Linear ? "linear" : "nearest"),
        "--params=" + (dir / "params.json").string(),
        "--frames=" + std::to_string(job.frames),
        "--output=" + (dir / "output.raw").string(),
    };
    if (auto s = write_text(dir / "shader.gdshader", job.shader_code); !s.ok()) return s.error();
    if (auto s = write_text(dir / "params.json", params.value()); !s.ok()) return s.error();
    if (!job.input.empty()) {
        if (auto s = write_file(dir / "input.raw", job.input.rgba.data(), job.input.rgba.size() * sizeof(float)); !s.ok())
            return s.error();
        user_args.push_back("--input=" + (dir / "input.raw").string());
        user_args.push_back("--input-width=" + std::to_string(job.input.width));
        user_args.push_back("--input-height=" + std::to_string(job.input.height));
    }
    return user_args;
}

// The same for a scene (outputs to dir/frame-<N>.raw).
Result<std::vector<std::string>> scene_job_args(const Godot3SceneJob& job, const fs::path& dir) {
    if (job.scene.rfind("res://", 0) != 0) return job_error("scene must be a res:// path", "scene");
    if (job.width < 2 || job.height < 2 || job.width > kGodot3MaxExtent || job.height > kGodot3MaxExtent)
        return job_error(fmt::format("the display must be 2..{} pixels on each side; got {}x{}", kGodot3MaxExtent, job.width, job.height), "width");
    if (job.run.empty() || job.inputs.size() != job.run.size())
        return job_error("one input picture per frame of run is needed", "inputs");
    for (const Image& input : job.inputs)
        if (input.empty() || input.width != job.inputs.front().width || input.height != job.inputs.front().height)
            return job_error("the input pictures must all have one size", "inputs");
    for (int f : job.capture)
        if (std::find(job.run.begin(), job.run.end(), f) == job.run.end())
            return job_error(fmt::format("captured frame {} is not run", f), "capture");
    if (!(job.fps > 0)) return job_error("fps must be positive", "fps");
    if (!(job.start_time >= 0)) return job_error("start_time must not be negative", "start_time");
    if (job.timeout_seconds < 1) return job_error("timeout_seconds must be at least 1", "timeout_seconds");
    auto params = params_json(job.params);
    if (!params.ok()) return params.error();
    {
        std::ofstream inputs(dir / "inputs.raw", std::ios::binary);
        for (const Image& input : job.inputs)
            inputs.write(reinterpret_cast<const char*>(input.rgba.data()), static_cast<std::streamsize>(input.rgba.size() * sizeof(float)));
        if (!inputs) return make_error("cannot write " + (dir / "inputs.raw").string());
    }
    if (auto s = write_text(dir / "params.json", params.value()); !s.ok()) return s.error();
    std::vector<std::string> user_args = {
        "--scene=" + job.scene,
        "--width=" + std::to_string(job.width),
        "--height=" + std::to_string(job.height),
        "--inputs=" + (dir / "inputs.raw").string(),
        "--input-width=" + std::to_string(job.inputs.front().width),
        "--input-height=" + std::to_string(job.inputs.front().height),
        "--run=" + detail::frame_list(job.run),
        "--capture=" + detail::frame_list(job.capture),
        fmt::format("--fps={}", job.fps),
        fmt::format("--start-time={}", job.start_time),
        fmt::format("--frame-count-base={}", job.frame_count_base),
        "--params=" + (dir / "params.json").string(),
        "--output=" + (dir / "frame-").string(),
    };
    if (!job.fit.empty()) user_args.push_back("--fit=" + job.fit);
    return user_args;
}

Result<std::vector<Image>> scene_outputs(const Godot3SceneJob& job, const fs::path& dir) {
    std::vector<Image> out;
    for (int f : job.capture) {
        auto image = read_output(dir / ("frame-" + std::to_string(f) + ".raw"), job.width, job.height);
        if (!image.ok()) return image.error();
        out.push_back(std::move(image.value()));
    }
    return out;
}

}  // namespace

Result<Image> render_godot3(const Godot3Job& job) {
    auto scratch = TemporaryFolder::create("crtforge-godot3");
    if (!scratch.ok()) return scratch.error();
    const fs::path dir = scratch.value().path();
    auto args = shader_job_args(job, dir);
    if (!args.ok()) return args.error();
    if (auto s = run_runner(dir, {}, args.value(), job.timeout_seconds); !s.ok()) return s.error();
    return read_output(dir / "output.raw", job.width, job.height);
}

Result<std::string> run_godot3_project(const std::string& project_dir, int timeout_seconds) {
    std::error_code ec;
    if (!fs::is_regular_file(fs::path(project_dir) / "project.godot", ec))
        return job_error("no project.godot in '" + project_dir + "'", "project");
    auto scratch = TemporaryFolder::create("crtforge-godot3");
    if (!scratch.ok()) return scratch.error();
    std::string log;
    if (auto s = run_godot_on(scratch.value().path(), project_dir, {}, timeout_seconds, &log); !s.ok()) return s.error();
    return log;
}

Result<std::vector<Image>> render_godot3_scene(const Godot3SceneJob& job) {
    auto scratch = TemporaryFolder::create("crtforge-godot3");
    if (!scratch.ok()) return scratch.error();
    const fs::path dir = scratch.value().path();
    auto args = scene_job_args(job, dir);
    if (!args.ok()) return args.error();
    if (auto s = run_runner(dir, job.project_files, args.value(), job.timeout_seconds); !s.ok()) return s.error();
    return scene_outputs(job, dir);
}

// ---- the server: one Xvfb and one Godot for many jobs -----------------------------------------

struct Godot3Server::Process {
    TemporaryFolder scratch;
    XServer x;
    std::unique_ptr<ChildGuard> godot;
    Pipe output;
    std::string pending;  // output read past the last job's end
    int jobs = 0;
};

Godot3Server::Godot3Server() = default;
Godot3Server::~Godot3Server() { stop(); }

void Godot3Server::stop() {
    if (!process_) return;
    // The runner polls for this file between jobs and quits; a runner busy with a job is killed.
    std::ofstream(process_->scratch.path() / "jobs" / "quit").put('\n');
    if (process_->godot && wait_until(process_->godot->pid(), Clock::now() + std::chrono::milliseconds(500)))
        process_->godot->reaped();
    if (process_->godot) process_->godot->stop();
    if (process_->x.process) process_->x.process->stop();
    process_.reset();
}

Status Godot3Server::start() {
    const std::string godot = find_on_path("godot3");
    const std::string xvfb = find_on_path("Xvfb");
    if (godot.empty() || xvfb.empty())
        return make_error(fmt::format("Godot 3 rendering needs {} ('{}' is not on PATH)", kPackages,
                                      godot.empty() ? "godot3" : "Xvfb"));
    auto scratch = TemporaryFolder::create("crtforge-godot3");
    if (!scratch.ok()) return scratch.error();
    auto p = std::make_unique<Process>(Process{std::move(scratch.value()), {}, {}, {}, {}, 0});
    const fs::path dir = p->scratch.path();
    if (auto s = copy_runner(data_path("tools/godot3-runner"), dir / "project"); !s.ok()) return s;
    auto x = start_xvfb(xvfb, dir);
    if (!x.ok()) return x.error();
    p->x = std::move(x.value());
    // Jobs arrive as files in jobs/ (Godot 3.2 reads neither stdin nor a named pipe).
    std::error_code ec;
    fs::create_directories(dir / "jobs", ec);
    if (ec) return make_error(fmt::format("cannot create '{}': {}", (dir / "jobs").string(), ec.message()));
    if (auto s = open_pipe(p->output); !s.ok()) return s;
    SpawnSpec spec;
    spec.executable = godot;
    spec.args = {"--path", (dir / "project").string(), "--video-driver", "GLES3", "--audio-driver", "Dummy", "--",
                 "--serve=" + (dir / "jobs").string(), "--parent=" + std::to_string(::getpid())};
    spec.env = child_environment({{"DISPLAY", p->x.display},
                                  {"XDG_DATA_HOME", (dir / "data").string()},
                                  {"XDG_CONFIG_HOME", (dir / "config").string()}});
    spec.output_fd = p->output.write;
    auto pid = spawn(spec);
    p->output.close_write();
    if (!pid.ok()) return pid.error();
    p->godot = std::make_unique<ChildGuard>(pid.value(), SIGKILL);
    process_ = std::move(p);
    return Ok{};
}

Status Godot3Server::run(const std::function<Result<std::vector<std::string>>(const fs::path&)>& prepare,
                         const std::map<std::string, std::string>& project_files, int timeout_seconds,
                         const std::function<Status(const fs::path&)>& collect) {
    for (int attempt = 0; attempt < 2; ++attempt) {
        if (!process_)
            if (auto s = start(); !s.ok()) return s;
        Process& p = *process_;
        // A path keeps its content for the life of the process (Godot caches what it loaded):
        // different content at a known path takes a fresh process.
        auto added = add_project_files(p.scratch.path() / "project", project_files);
        if (!added.ok()) return added.error();
        if (!added.value()) {
            stop();
            continue;
        }
        const fs::path dir = p.scratch.path() / ("job-" + std::to_string(p.jobs++));
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec) return make_error(fmt::format("cannot create '{}': {}", dir.string(), ec.message()));
        struct Cleanup {
            fs::path dir;
            ~Cleanup() { std::error_code e; fs::remove_all(dir, e); }
        } cleanup{dir};
        auto args = prepare(dir);
        if (!args.ok()) return args.error();
        nlohmann::json request = nlohmann::json::object();
        for (const std::string& arg : args.value()) {
            const size_t eq = arg.find('=');
            request[arg.substr(2, eq - 2)] = eq == std::string::npos ? std::string() : arg.substr(eq + 1);
        }
        // Written beside, then renamed: the runner never reads half a job.
        const fs::path job_file = p.scratch.path() / "jobs" / ("job-" + std::to_string(p.jobs - 1) + ".json");
        if (auto w = write_text(fs::path(job_file.string() + ".tmp"), request.dump() + "\n"); !w.ok()) return w;
        fs::rename(job_file.string() + ".tmp", job_file, ec);
        if (ec) return make_error(fmt::format("cannot write '{}': {}", job_file.string(), ec.message()));
        // Everything up to "crtforge-godot3-done: <code>" is this job's output.
        constexpr const char* kDone = "crtforge-godot3-done: ";
        const auto deadline = Clock::now() + std::chrono::seconds(timeout_seconds);
        size_t done = std::string::npos;
        while ((done = p.pending.find(kDone)) == std::string::npos || p.pending.find('\n', done) == std::string::npos) {
            char buffer[8192];
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
            if (left <= 0) {
                stop();
                return make_validation_error(fmt::format("Godot 3 did not finish a job within {} s and was killed", timeout_seconds));
            }
            pollfd fd{p.output.read, POLLIN, 0};
            const int r = ::poll(&fd, 1, static_cast<int>(std::min<long long>(left, 1000)));
            if (r < 0 && errno != EINTR) break;
            if (r <= 0) continue;
            const ssize_t n = ::read(p.output.read, buffer, sizeof buffer);
            if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
            if (n <= 0) {  // Godot ended mid-job: a crash
                const std::string log = p.pending;
                std::optional<int> status = p.godot ? wait_until(p.godot->pid(), Clock::now() + std::chrono::seconds(5)) : std::nullopt;
                if (status && p.godot) p.godot->reaped();
                stop();
                return diagnose(log, -1, status ? describe_status(*status) : std::string("its output ended"));
            }
            if (p.pending.size() < kMaxLogBytes) p.pending.append(buffer, static_cast<size_t>(n));
        }
        const size_t end = p.pending.find('\n', done);
        const std::string log = p.pending.substr(0, done);
        const int code = std::atoi(p.pending.substr(done + std::strlen(kDone), end - done - std::strlen(kDone)).c_str());
        p.pending.erase(0, end + 1);
        if (auto s = diagnose(log, code, ""); !s.ok()) return s;
        return collect(dir);
    }
    return make_error("Godot 3: the project files of two jobs disagree even in a fresh process");
}

Result<Image> Godot3Server::render(const Godot3Job& job) {
    Image image;
    auto s = run([&](const fs::path& dir) { return shader_job_args(job, dir); }, {}, job.timeout_seconds,
                 [&](const fs::path& dir) -> Status {
                     auto out = read_output(dir / "output.raw", job.width, job.height);
                     if (!out.ok()) return out.error();
                     image = std::move(out.value());
                     return Ok{};
                 });
    if (!s.ok()) return s.error();
    return image;
}

Result<std::vector<Image>> Godot3Server::render_scene(const Godot3SceneJob& job) {
    std::vector<Image> images;
    auto s = run([&](const fs::path& dir) { return scene_job_args(job, dir); }, job.project_files, job.timeout_seconds,
                 [&](const fs::path& dir) -> Status {
                     auto out = scene_outputs(job, dir);
                     if (!out.ok()) return out.error();
                     images = std::move(out.value());
                     return Ok{};
                 });
    if (!s.ok()) return s.error();
    return images;
}

std::string godot3_version() {
    static const std::string version = [] {
        const std::string godot = find_on_path("godot3");
        if (godot.empty()) return std::string();
        Pipe output;
        if (!open_pipe(output).ok()) return std::string();
        SpawnSpec spec;
        spec.executable = godot;
        spec.args = {"--version"};
        spec.env = child_environment({}, {"XAUTHORITY"});
        spec.output_fd = output.write;
        auto pid = spawn(spec);
        output.close_write();
        if (!pid.ok()) return std::string();
        ChildGuard process(pid.value(), SIGKILL);
        const auto deadline = Clock::now() + std::chrono::seconds(10);
        std::string text;
        if (!read_until_eof(output.read, deadline, text) || !wait_until(pid.value(), deadline)) return std::string();
        process.reaped();
        // The version is the first line; Godot's locale complaints may follow on stderr.
        for (const std::string& line : split_lines(text)) {
            std::string t = trim(line);
            if (!t.empty() && std::isdigit(static_cast<unsigned char>(t[0]))) return t;
        }
        return std::string();
    }();
    return version;
}

}  // namespace crtforge
