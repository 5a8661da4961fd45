// Runs a scene through a web framework adapter with examples/webgpu/check.mjs (framework_check.hpp).
#include "runtime/dawn/framework_check.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "crtforge/paths.hpp"
#include "crtforge/value.hpp"
#include "runtime/common/job_checks.hpp"
#include "runtime/common/process_util.hpp"
#include "runtime/common/raw_pictures.hpp"

namespace crtforge::detail {

namespace fs = std::filesystem;

namespace {

constexpr int kFrameworkStartSeconds = 90;       // node, Dawn, the framework and its first pipelines
constexpr int kFrameworkSecondsPerFrame = 10;    // SwiftShader and llvmpipe draw a few frames a second

// check.mjs's --set value: a number, or a colour as r,g,b (what its setParam takes).
Result<std::string> set_value(const std::string& name, const Value& value) {
    if (auto d = std::get_if<double>(&value)) return fmt::format("{}={}", name, *d);
    if (auto i = std::get_if<int64_t>(&value)) return fmt::format("{}={}", name, *i);
    if (auto b = std::get_if<bool>(&value)) return fmt::format("{}={}", name, *b ? 1 : 0);
    if (auto c = std::get_if<Color>(&value)) return fmt::format("{}={},{},{}", name, (*c)[0], (*c)[1], (*c)[2]);
    return job_error("param '" + name + "' is text, which check.mjs's --set does not take", "params");
}

// The last non-empty line of a log: check.mjs's one-line error comes last (dawn.node's own noise
// goes before it).
std::string last_line(const fs::path& path) {
    std::ifstream in(path);
    std::string line, last;
    while (std::getline(in, line))
        if (!trim(line).empty()) last = trim(line);
    return last;
}

}  // namespace

bool is_web_framework(const std::string& name) { return name == "three" || name == "pixi" || name == "babylon"; }

namespace {

// What the machine lacks to run `framework` at all ("" when nothing): its npm package in
// tools/wgsl-runner, and for PixiJS and Babylon.js, which need a core WebGPU adapter, SwiftShader's
// Vulkan driver (lavapipe lacks a feature Dawn's Vulkan backend requires).
std::string framework_setup_problem(const std::string& framework) {
    const char* package = framework == "three" ? "three" : framework == "pixi" ? "pixi.js" : "@babylonjs/core";
    const fs::path manifest = fs::path(data_path("tools/wgsl-runner")) / "node_modules" / package / "package.json";
    std::error_code ec;
    if (!fs::is_regular_file(manifest, ec))
        return fmt::format("the npm package '{}' is not installed (no '{}'): run scripts/setup.sh", package, manifest.string());
    const char* swiftshader = "/usr/lib/chromium/vk_swiftshader_icd.json";
    if (framework != "three" && !fs::is_regular_file(swiftshader, ec))
        return fmt::format("{} runs on Dawn's Vulkan backend over SwiftShader: no '{}' (the Debian package chromium-common; run "
                           "scripts/setup.sh)",
                           framework, swiftshader);
    return {};
}

}  // namespace

Result<std::vector<Image>> render_through_framework(const DawnSceneJob& job, const fs::path& package, const fs::path& scratch) {
    if (!is_web_framework(job.framework)) return job_error("unknown web framework '" + job.framework + "'", "framework");
    // check.mjs pins one time for every frame (--time): enough for a single frame, not a sequence.
    if (!job.times.empty() && job.run.size() != 1)
        return job_error("a framework adapter's sequence runs at the package's own time (frame / fps)", "times");
    if (const std::string problem = framework_setup_problem(job.framework); !problem.empty()) return make_error(problem);
    const std::string node = find_on_path("node");
    if (node.empty()) return make_error("the web framework adapters run on Node.js: install the Debian packages nodejs and npm");
    const fs::path check = fs::path(data_path("examples/webgpu/check.mjs")).lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(check, ec)) return make_error("the WebGPU example is missing: no '" + check.string() + "'");

    // An app that installed the package, as `npm install ./export/npm` leaves it.
    const fs::path app = scratch / fmt::format("app-{}", job.framework);
    fs::remove_all(app, ec);
    fs::create_directories(app / "node_modules", ec);
    fs::create_directory_symlink(fs::absolute(package), app / "node_modules" / "crtforge-presets", ec);
    if (ec) return make_error(fmt::format("cannot make the app folder '{}': {}", app.string(), ec.message()));

    const fs::path inputs = scratch / "framework-inputs.f32", output = scratch / "framework-frame-", log = scratch / "framework.log";
    if (auto s = write_pictures(inputs, job.inputs); !s.ok()) return s.error();
    SpawnSpec spec;
    spec.executable = node;
    spec.args = {check.string(), "--package", app.string(), "--" + job.framework, "on", "--preset", job.preset,
                 "--input", inputs.string(), "--input-width", std::to_string(job.inputs.front().width),
                 "--input-height", std::to_string(job.inputs.front().height), "--width", std::to_string(job.width),
                 "--height", std::to_string(job.height), "--frames", frame_list(job.run), "--capture", frame_list(job.capture),
                 "--output", output.string()};
    if (!job.times.empty()) spec.args.insert(spec.args.end(), {"--time", fmt::format("{}", job.times.front())});
    if (!job.fit.empty()) spec.args.insert(spec.args.end(), {"--fit", job.fit});
    for (const auto& [name, value] : job.params) {
        auto set = set_value(name, value);
        if (!set.ok()) return set.error();
        spec.args.insert(spec.args.end(), {"--set", set.value()});
    }
    spec.env = child_environment({});
    const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (log_fd < 0) return make_error(fmt::format("cannot write '{}': {}", log.string(), std::strerror(errno)));
    spec.output_fd = log_fd;
    auto pid = spawn(spec);
    ::close(log_fd);
    if (!pid.ok()) return pid.error();
    const int seconds = kFrameworkStartSeconds + kFrameworkSecondsPerFrame * static_cast<int>(job.run.size());
    std::optional<int> status = wait_until(pid.value(), ProcessClock::now() + std::chrono::seconds(seconds));
    const std::string adapter = "crtforge-presets/" + job.framework;
    if (!status) {
        ::kill(pid.value(), SIGKILL);
        wait_until(pid.value(), ProcessClock::now() + std::chrono::seconds(10));
        return make_validation_error(fmt::format("{} in check.mjs did not finish within {} s", adapter, seconds));
    }
    fs::remove(inputs, ec);
    if (!WIFEXITED(*status) || WEXITSTATUS(*status) != 0)
        return make_validation_error(fmt::format("{} failed ({}): {}", adapter, describe_status(*status), last_line(log)));

    // check.mjs writes each captured frame to a file of its own: <output><frame>.raw.
    std::vector<Image> images;
    for (int frame : job.capture) {
        const fs::path file = output.string() + std::to_string(frame) + ".raw";
        auto picture = read_pictures(file, job.width, job.height, 1, adapter + " in check.mjs");
        fs::remove(file, ec);
        if (!picture.ok()) return picture.error();
        images.push_back(std::move(picture.value().front()));
    }
    return images;
}

}  // namespace crtforge::detail
