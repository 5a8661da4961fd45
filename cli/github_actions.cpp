// Under GitHub Actions (GITHUB_ACTIONS=true): each failed check as an `::error` workflow command
// pointing at the file and line it is about, and a markdown summary table appended to
// $GITHUB_STEP_SUMMARY, so a CI user sees failures on the pull request's files and on the run's page.
#include "cli/github_actions.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>

#include <fmt/format.h>

namespace crtforge::cli {

namespace {

// Workflow-command data escaping (GitHub's toolkit: %, CR and LF in messages; also : and , in
// properties).
std::string escape_data(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '%') out += "%25";
        else if (c == '\r') out += "%0D";
        else if (c == '\n') out += "%0A";
        else out += c;
    }
    return out;
}

std::string escape_property(const std::string& text) {
    std::string out;
    for (char c : escape_data(text)) {
        if (c == ':') out += "%3A";
        else if (c == ',') out += "%2C";
        else out += c;
    }
    return out;
}

// Markdown table cells: no pipes or line breaks.
std::string cell(const std::string& text) {
    std::string out;
    for (char c : text) out += c == '|' ? '/' : (c == '\n' || c == '\r') ? ' ' : c;
    return out;
}

}  // namespace

bool running_on_github_actions() {
    const char* v = std::getenv("GITHUB_ACTIONS");
    return v && std::string(v) == "true";
}

void annotate_for_github(const ValidationReport& report, const std::function<SourceLocation(const std::string& preset)>& preset_file) {
    if (!running_on_github_actions()) return;
    // A message that starts "file:line[:column]: " names its own place (a compile error in a
    // template); otherwise the check is about the preset's file.
    static const std::regex located(R"(^([^\s:][^:]*):(\d+)(?::\d+)?: )");
    size_t printed = 0;
    for (const CheckResult& c : report.checks) {
        if (c.passed) continue;
        if (++printed > 200) break;  // GitHub shows a limited number per step anyway
        std::string file;
        int line = 0;
        std::smatch m;
        if (std::regex_search(c.message, m, located)) {
            file = m[1].str();
            line = std::atoi(m[2].str().c_str());
        } else if (preset_file) {
            const SourceLocation where = preset_file(c.preset);
            file = where.file;
            line = where.line;
        }
        std::string props;
        if (!file.empty()) props = " file=" + escape_property(file) + (line > 0 ? fmt::format(",line={}", line) : "");
        props.append(props.empty() ? " " : ",").append("title=").append(escape_property(c.preset + " " + c.target + " " + c.check));
        fmt::print("::error{}::{}\n", props, escape_data(c.message));
    }

    const char* summary_path = std::getenv("GITHUB_STEP_SUMMARY");
    if (!summary_path || !*summary_path) return;
    std::string md = "### crtforge validate\n\n| target | passed | failed | not rendered |\n|---|---:|---:|---:|\n";
    std::vector<std::string> targets;
    for (const CheckResult& c : report.checks)
        if (std::find(targets.begin(), targets.end(), c.target) == targets.end()) targets.push_back(c.target);
    for (const std::string& t : targets) {
        size_t pass = 0, fail = 0, unrendered = 0;
        for (const CheckResult& c : report.checks)
            if (c.target == t) {
                (c.passed ? pass : fail)++;
                unrendered += c.not_rendered;
            }
        md += fmt::format("| {} | {} | {} | {} |\n", cell(t), pass, fail, unrendered);
    }
    if (report.failed()) {
        md += "\n**Failures**\n\n| preset | target | check | why |\n|---|---|---|---|\n";
        size_t listed = 0;
        for (const CheckResult& c : report.checks)
            if (!c.passed && ++listed <= 100) md += fmt::format("| {} | {} | {} | {} |\n", cell(c.preset), cell(c.target), cell(c.check), cell(c.message));
        if (listed > 100) md += fmt::format("\n... and {} more (report.html)\n", listed - 100);
    }
    std::ofstream(summary_path, std::ios::app) << md << "\n";
}

}  // namespace crtforge::cli
