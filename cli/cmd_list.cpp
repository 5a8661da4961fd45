// crtforge list [presets|targets|stages]
#include <fmt/format.h>

#include "cli/cli_common.hpp"

namespace crtforge::cli {

namespace {

std::string range_text(const ParamSpec& p) {
    if (p.type == ParamType::Enum) {
        std::string out;
        for (const auto& v : p.enum_values) out += (out.empty() ? "" : "|") + v;
        return out;
    }
    if (p.min) return fmt::format("{}..{}", *p.min, *p.max);
    if (p.type == ParamType::Color) return "rgb 0..1";
    return "true|false";
}

void print_readable(const TemplateLibrary& lib) {
    fmt::print("Stages (in pass order):\n");
    for (const StageSpec& s : lib.stages()) {
        fmt::print("\n  {}  — {}\n", s.name, s.doc);
        for (const FormSpec& f : s.forms) fmt::print("    form {:<12} {}\n", f.name, f.doc);
        for (const ParamSpec& p : s.params) {
            fmt::print("    {:<20} {:<5} {:<34} default {:<8} {:<5} {}{}\n", p.name, param_type_name(p.type),
                       range_text(p), value_to_string(p.default_value), p.unit,
                       p.runtime ? "[runtime] " : "", p.doc);
        }
    }
    fmt::print("\nPresets:\n");
    for (const Preset& p : lib.presets()) {
        fmt::print("  {:<20} {}\n", p.name, p.doc);
        for (const Pass& pass : p.passes) {
            std::string stages;
            for (const auto& rs : pass.stages)
                stages += (stages.empty() ? "" : ", ") + rs.stage->name + "(" + rs.form->name + ")";
            const std::string label = p.single_pass() ? "stages:" : "pass " + pass.alias + ":";
            fmt::print("  {:<20} {} {}\n", "", label, stages.empty() ? "none (passthrough)" : stages);
        }
    }
    fmt::print("\nTargets:\n");
    for (const TargetInfo& t : all_targets()) fmt::print("  {:<10} {}\n", t.name, t.description);
}

}  // namespace

Runner add_list_command(CLI::App& app, const GlobalOptions& g) {
    auto* cmd = app.add_subcommand("list", "List stages with their params, presets and targets");
    auto what = std::make_shared<std::string>();
    cmd->add_option("what", *what, "presets, targets or stages: one name per line, for scripts")
        ->check(CLI::IsMember({"presets", "targets", "stages"}));
    return [&g, what]() {
        int code = kExitOk;
        auto lib = load_library(g, code);
        if (!lib) return code;
        if (*what == "presets") {
            for (const auto& p : lib->presets()) fmt::print("{}\n", p.name);
        } else if (*what == "targets") {
            for (const auto& t : all_targets()) fmt::print("{}\n", t.name);
        } else if (*what == "stages") {
            for (const auto& s : lib->stages()) fmt::print("{}\n", s.name);
        } else {
            print_readable(*lib);
        }
        return kExitOk;
    };
}

}  // namespace crtforge::cli
