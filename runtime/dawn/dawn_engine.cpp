// The Dawn engine: one persistent `node tools/wgsl-runner/runner.mjs` process per engine, spoken
// to in JSON lines, with the shader, pixels and uniform bytes exchanged as files in a private
// temporary directory.
//
// The process is a detail::NodeRunner (runtime/common/node_runner.hpp): replies come on their own
// descriptor because dawn.node prints its own messages (compilation logs, uncaptured errors,
// start-up warnings) on stdout, so stdout cannot carry them.
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
#include <cmath>
#include <chrono>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <string_view>
#include <thread>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "crtforge/paths.hpp"
#include "runtime/common/job_checks.hpp"
#include "runtime/common/node_runner.hpp"
#include "runtime/common/process_util.hpp"
#include "runtime/common/raw_pictures.hpp"
#include "runtime/dawn/framework_check.hpp"

extern char** environ;


namespace crtforge {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using detail::find_on_path;
using detail::trim;
using detail::write_file;
using json = nlohmann::json;
using detail::job_error;

constexpr const char* kWebgpuVersion = "0.6.2";  // tools/wgsl-runner/package.json pins it
constexpr int kDawnMaxExtent = kMaxImageDimension;    // llvmpipe's maxTextureDimension2D
constexpr int kStartSeconds = 60;
constexpr int kRequestSeconds = 120;

// ---- small helpers (the process ones are shared with the Godot 3 engine: process_util.hpp) ----


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
        case OutputFormat::Rgba32Float: return "rgba32float";
        case OutputFormat::Rgb10A2Unorm: return "rgb10a2unorm";
        case OutputFormat::R16Float: return "r16float";
        case OutputFormat::Rg16Float: return "rg16float";
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
        case WrapMode::ClampToBorder: break;  // refused by check_job: WebGPU has no border colour
    }
    return "?";
}

Status check_scene_job(const DawnSceneJob& job) {
    if (!job.package_files.count("index.mjs") || !job.package_files.count("manifest.json"))
        return job_error("the package has no index.mjs or manifest.json", "package_files");
    if (job.preset.empty()) return job_error("the preset name is empty", "preset");
    if (job.run.empty() || job.inputs.size() != job.run.size())
        return job_error(fmt::format("{} input pictures for {} frames", job.inputs.size(), job.run.size()), "inputs");
    if (job.capture.empty()) return job_error("no frame is captured", "capture");
    for (int f : job.capture)
        if (std::find(job.run.begin(), job.run.end(), f) == job.run.end())
            return job_error(fmt::format("captured frame {} is not drawn", f), "capture");
    for (int f : job.run)
        if (f < 0) return job_error(fmt::format("frame {} is negative", f), "run");
    if (!job.times.empty() && job.times.size() != job.run.size())
        return job_error(fmt::format("{} times for {} frames", job.times.size(), job.run.size()), "times");
    for (double t : job.times)
        if (!std::isfinite(t)) return job_error("a frame's time is not finite", "times");
    if (!job.fit.empty() && job.fit != "stretch" && job.fit != "aspect" && job.fit != "integer")
        return job_error("the display fit must be stretch, aspect or integer, not '" + job.fit + "'", "fit");
    const detail::JobLimits limits{kDawnMaxExtent, kDawnMaxExtent, kDawnMaxExtent, "Dawn", "maxTextureDimension2D"};
    for (const Image& input : job.inputs) {
        if (input.width != job.inputs.front().width || input.height != job.inputs.front().height)
            return job_error("the input pictures differ in size", "inputs");
        if (auto s = detail::check_job_extent(job.width, job.height, input, limits); !s.ok()) return s;
    }
    if (std::string_view(format_name(job.format)) == "?") return job_error("unknown output format", "format");
    return Ok{};
}

// A param as the package's setParam() takes it: a number, or [r, g, b] for a colour (a bool as 0
// or 1; an enum's name, which no uniform holds, goes as text for the package to refuse).
json package_param(const Value& value) {
    if (auto d = std::get_if<double>(&value)) return *d;
    if (auto i = std::get_if<int64_t>(&value)) return *i;
    if (auto b = std::get_if<bool>(&value)) return *b ? 1 : 0;
    if (auto t = std::get_if<std::string>(&value)) return *t;
    const Color& c = std::get<Color>(value);
    return json::array({c[0], c[1], c[2]});
}

Status check_job(const DawnJob& job) {
    if (trim(job.wgsl).empty()) return job_error("the WGSL module is empty", "wgsl");
    if (job.vertex_entry.empty()) return job_error("the vertex entry point name is empty", "vertex_entry");
    if (job.fragment_entry.empty()) return job_error("the fragment entry point name is empty", "fragment_entry");
    const detail::JobLimits limits{kDawnMaxExtent, kDawnMaxExtent, kDawnMaxExtent, "Dawn", "maxTextureDimension2D"};
    if (auto s = detail::check_job_extent(job.width, job.height, job.uses_texture ? *job.input : Image{}, limits); !s.ok())
        return s;
    if (auto s = detail::check_texture_images(job.textures, limits); !s.ok()) return s;
    if (auto s = detail::check_viewport(job.viewport, job.width, job.height); !s.ok()) return s;
    if (auto s = detail::check_clear_color(job.clear_color); !s.ok()) return s;
    if (std::string_view(format_name(job.format)) == "?") return job_error("unknown output format", "format");
    // WebGPU has no border colour: clamp_to_border must be emulated by the shader, not asked of Dawn
    // (the main input's wrap matters only where the module samples it).
    if (job.uses_texture && job.wrap == WrapMode::ClampToBorder) return job_error("WebGPU has no clamp-to-border address mode", "wrap");
    for (std::size_t i = 0; i < job.textures.size(); ++i)
        if (job.textures[i].wrap == WrapMode::ClampToBorder)
            return job_error("WebGPU has no clamp-to-border address mode", detail::texture_field(i, "wrap"));
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
    std::unique_ptr<detail::NodeRunner> runner;
    std::string description;   // from the runner's start-up reply

    fs::path scratch() const { return runner->scratch(); }

    // The start-up reply says whether Dawn found an adapter.
    Status started(const json& r) {
        if (!r.value("ok", false)) {
            const std::string kind = r.value("kind", "");
            const std::string error = r.value("error", "unknown error");
            runner->stop(false);
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

    Status start() {
        if (auto setup = runner_setup(runner_dir); !setup.ok()) return setup;
        detail::NodeRunnerSpec spec;
        spec.name = "the Dawn runner";
        spec.script = runner_dir / "runner.mjs";
        spec.env = {{"EGL_PLATFORM", "surfaceless"}};  // Mesa EGL, no window system
        spec.start_seconds = kStartSeconds;
        spec.ignore_log_line = [](const std::string& line) { return line.find("artificially reduced") != std::string::npos; };
        auto made = detail::NodeRunner::create(std::move(spec), "crtforge-dawn");
        if (!made.ok()) return made.error();
        runner = std::move(made.value());
        auto ready = runner->start();
        if (!ready.ok()) return ready.error();
        return started(ready.value());
    }

    // Sends one request and waits for its reply, restarting the runner first if it died.
    Result<json> request(const json& message, const char* during, int seconds = kRequestSeconds) {
        return runner->request(message, during, seconds, [this](const json& r) { return started(r); });
    }

    // The folder holding exactly `files` (a package), written into the scratch folder on first use:
    // every golden of a preset loads the same package, and Node keeps a module per folder.
    std::vector<std::pair<std::map<std::string, std::string>, fs::path>> packages;
    Result<fs::path> package_folder(const std::map<std::string, std::string>& files) {
        for (const auto& [held, folder] : packages)
            if (held == files) return folder;
        const fs::path folder = scratch() / fmt::format("package{}", packages.size());
        for (const auto& [path, data] : files) {
            const fs::path relative = fs::path(path).lexically_normal();
            if (path.empty() || relative.is_absolute() || *relative.begin() == "..")
                return job_error("a package file's path must stay inside the package: '" + path + "'", "package_files");
            std::error_code ec;
            fs::create_directories((folder / relative).parent_path(), ec);
            if (auto s = write_file(folder / relative, data.data(), data.size()); !s.ok()) return s.error();
        }
        packages.emplace_back(files, folder);
        return folder;
    }
};

DawnEngine::DawnEngine(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

DawnEngine::~DawnEngine() = default;

Status DawnEngine::check_setup() { return runner_setup(fs::path(data_path("tools/wgsl-runner")).lexically_normal()); }

Result<std::unique_ptr<DawnEngine>> DawnEngine::create() {
    try {
        auto impl = std::make_unique<Impl>();
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
        const fs::path shader = impl_->scratch() / "shader.wgsl";
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
        const fs::path dir = impl_->scratch();
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
            {"mipmap", job.mipmap},
            {"mip_filter", filter_name(job.mip_filter)},
            {"unorm8", job.unorm8},
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
        if (job.uses_texture && !job.input->empty()) {
            if (auto s = write_file(input, job.input->rgba.data(), job.input->rgba.size() * sizeof(float)); !s.ok())
                return s.error();
            message["input"] = input.string();
            message["input_width"] = job.input->width;
            message["input_height"] = job.input->height;
        }
        // Each extra texture travels as the input does: raw float32 RGBA in a file of its own.
        json textures = json::array();
        for (std::size_t i = 0; i < job.textures.size(); ++i) {
            const TextureInput& t = job.textures[i];
            json entry = {{"binding", t.binding},
                          {"sampler_binding", t.sampler_binding},
                          {"filter", filter_name(t.filter)},
                          {"wrap", wrap_name(t.wrap)},
                          {"mipmap", t.mipmap},
                          {"mip_filter", filter_name(t.mip_filter)},
                          {"unorm8", t.unorm8}};
            if (!t.image->empty()) {
                const fs::path file = dir / fmt::format("texture{}.f32", i);
                if (auto s = write_file(file, t.image->rgba.data(), t.image->rgba.size() * sizeof(float)); !s.ok())
                    return s.error();
                entry["image"] = file.string();
                entry["width"] = t.image->width;
                entry["height"] = t.image->height;
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

Result<std::vector<Image>> DawnEngine::render_scene(const DawnSceneJob& job) {
    static_assert(std::endian::native == std::endian::little, "the runner's files are little-endian float32");
    if (auto s = check_scene_job(job); !s.ok()) return s.error();
    try {
        std::lock_guard lock(impl_->mutex);
        auto folder = impl_->package_folder(job.package_files);
        if (!folder.ok()) return folder.error();
        if (!job.framework.empty()) return detail::render_through_framework(job, folder.value(), impl_->scratch());
        const fs::path dir = impl_->scratch(), inputs = dir / "inputs.f32", output = dir / "output.f32";
        if (auto s = detail::write_pictures(inputs, job.inputs); !s.ok()) return s.error();
        std::error_code ec;
        fs::remove(output, ec);
        json params = json::object();
        for (const auto& [name, value] : job.params) params[name] = package_param(value);
        json message = {
            {"op", "scene"},
            {"package", folder.value().string()},
            {"preset", job.preset},
            {"width", job.width},
            {"height", job.height},
            {"format", format_name(job.format)},
            {"input_width", job.inputs.front().width},
            {"input_height", job.inputs.front().height},
            {"inputs", inputs.string()},
            {"run", job.run},
            {"capture", job.capture},
            {"params", std::move(params)},
            {"output", output.string()},
        };
        if (!job.times.empty()) message["times"] = job.times;
        if (!job.fit.empty()) message["fit"] = job.fit;
        // A long sequence gets time in proportion: llvmpipe draws a few frames a second at most.
        const int seconds = kRequestSeconds + 2 * static_cast<int>(job.run.size());
        auto reply = impl_->request(message, "scene", seconds);
        fs::remove(inputs, ec);
        if (!reply.ok()) return reply.error();
        const json& r = reply.value();
        if (!r.value("ok", false)) {
            const std::string error = r.value("error", std::string("unknown error"));
            if (r.value("kind", "") == "request") return make_error("the Dawn runner refused the scene request: " + error);
            return make_validation_error("the shipped npm package failed in Dawn: " + error);
        }
        auto images = detail::read_pictures(output, job.width, job.height, job.capture.size(), "the Dawn runner");
        fs::remove(output, ec);
        return images;
    } catch (const std::exception& e) {
        return make_validation_error(fmt::format("the Dawn scene render failed: {}", e.what()));
    }
}

}  // namespace crtforge
