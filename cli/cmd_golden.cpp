// crtforge golden update [--filter TEXT] [--dir DIR], crtforge golden approve --filter TEXT [--dir DIR] [--device D]
// and crtforge devices
#include <fmt/format.h>

#include "cli/heartbeat.hpp"
#include "cli/cli_common.hpp"
#include "crtforge/paths.hpp"
#include "crtforge/validate/golden.hpp"
#include "crtforge/runtime/render_engine.hpp"

namespace crtforge::cli {

std::string default_golden_dir() {
    if (const char* env = std::getenv("CRTFORGE_GOLDEN"); env && *env) return env;
    return data_path("golden");
}

Runner add_golden_approve_command(CLI::App& golden, const GlobalOptions& g);

Runner add_golden_command(CLI::App& app, const GlobalOptions& g) {
    auto* cmd = app.add_subcommand("golden", "Manage the golden reference images");
    cmd->require_subcommand(1);
    auto* update = cmd->add_subcommand("update", "Re-render goldens with the CPU reference renderer (the only way goldens change)");
    Runner approve = add_golden_approve_command(*cmd, g);
    auto dir = std::make_shared<std::string>(default_golden_dir());
    auto filter = std::make_shared<std::string>();
    update->add_option("--dir", *dir, "Golden directory")->capture_default_str();
    update->add_option("--filter", *filter, "Only re-render goldens whose id contains this text");
    return [&g, dir, filter, update, approve]() {
        if (!update->parsed()) return approve();
        int code = kExitOk;
        auto lib = load_library(g, code);
        if (!lib) return code;
        if (auto s = add_golden_presets(*lib, *dir); !s.ok()) return report(s.error());
        auto written = [&] {
            Heartbeat heartbeat("golden update");  // a long sequence says nothing between its own lines
            return update_goldens(*lib, *dir, *filter);
        }();
        if (!written.ok()) return report(written.error());
        fmt::print("golden update: {} reference images written to {} (manifest lists {})\n", written.value().written, *dir,
                   written.value().planned);
        if (const auto& missing = written.value().unmodelled; !missing.empty())
            fmt::print(stderr,
                       "golden update: {} goldens need your approval ({}): look at a render (crtforge render --preset {} ...) "
                       "and run crtforge golden approve --filter {} (first of them)\n",
                       missing.size(), written.value().unmodelled_reason, missing.front().substr(0, missing.front().find('.')),
                       missing.front());
        return kExitOk;
    };
}

Runner add_golden_approve_command(CLI::App& golden, const GlobalOptions& g) {
    auto* approve = golden.add_subcommand(
        "approve", "Store Vulkan renders (lavapipe) as goldens you have reviewed, marked approved: for stages of your own that the "
                   "reference renderer has no model of");
    auto dir = std::make_shared<std::string>(default_golden_dir());
    auto filter = std::make_shared<std::string>();
    auto device = std::make_shared<std::string>();
    approve->add_option("--dir", *dir, "Golden directory")->capture_default_str();
    approve->add_option("--filter", *filter, "Approve the planned goldens whose id contains this text")->required();
    approve->add_option("--device", *device, "Vulkan device name or index (default: lavapipe)");
    return [&g, dir, filter, device]() {
        int code = kExitOk;
        auto lib = load_library(g, code);
        if (!lib) return code;
        if (auto s = add_golden_presets(*lib, *dir); !s.ok()) return report(s.error());
        EngineOptions vulkan;
        vulkan.device = *device;
        auto written = approve_goldens(*lib, *dir, *filter, vulkan);
        if (!written.ok()) return report(written.error());
        fmt::print("golden approve: {} Vulkan renders stored in {} as approved goldens (manifest lists {})\n",
                   written.value().written, *dir, written.value().planned);
        return kExitOk;
    };
}

Runner add_devices_command(CLI::App& app, const GlobalOptions&) {
    app.add_subcommand("devices", "List the Vulkan devices validate and render can use (--device NAME|INDEX)");
    return []() {
        auto devices = list_vulkan_devices();
        if (!devices.ok()) return report(devices.error());
        for (const auto& d : devices.value()) fmt::print("{}  {}  ({}, {})\n", d.index, d.name, d.type, d.driver);
        return kExitOk;
    };
}

}  // namespace crtforge::cli
