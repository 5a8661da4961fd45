// report.json (machine-readable, mergeable) and junit.xml (one test case per check) for CI.
#include <nlohmann/json.hpp>

#include "crtforge/validation.hpp"
#include "generator/file_io.hpp"

namespace crtforge {

namespace {

std::string xml_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string report_json(const ValidationReport& report) {
    nlohmann::ordered_json j;
    j["summary"] = {{"checks", report.checks.size()}, {"passed", report.passed()}, {"failed", report.failed()}};
    j["checks"] = nlohmann::ordered_json::array();
    for (const CheckResult& c : report.checks) {
        nlohmann::ordered_json e{{"preset", c.preset}, {"target", c.target}, {"check", c.check}, {"passed", c.passed}};
        if (!c.passed) e["message"] = c.message;
        j["checks"].push_back(std::move(e));
    }
    return j.dump(2) + "\n";
}

std::string junit_xml(const ValidationReport& report) {
    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += "<testsuites name=\"crtforge validate\" tests=\"" + std::to_string(report.checks.size()) +
           "\" failures=\"" + std::to_string(report.failed()) + "\">\n";
    // One suite per target, so CI dashboards group by output language.
    std::vector<std::string> targets;
    for (const auto& c : report.checks)
        if (std::find(targets.begin(), targets.end(), c.target) == targets.end()) targets.push_back(c.target);
    for (const auto& t : targets) {
        size_t tests = 0, failures = 0;
        std::string cases;
        for (const auto& c : report.checks) {
            if (c.target != t) continue;
            ++tests;
            cases += "    <testcase classname=\"" + xml_escape(c.target + "." + c.preset) + "\" name=\"" + xml_escape(c.check) + "\"";
            if (c.passed) {
                cases += "/>\n";
            } else {
                ++failures;
                cases += ">\n      <failure message=\"" + xml_escape(c.message) + "\"/>\n    </testcase>\n";
            }
        }
        out += "  <testsuite name=\"" + xml_escape(t) + "\" tests=\"" + std::to_string(tests) + "\" failures=\"" +
               std::to_string(failures) + "\">\n" + cases + "  </testsuite>\n";
    }
    return out + "</testsuites>\n";
}

}  // namespace

Status write_report(const ValidationReport& report, const std::string& dir) {
    if (auto s = detail::write_file_atomic(dir + "/report.json", report_json(report)); !s.ok()) return s;
    return detail::write_file_atomic(dir + "/junit.xml", junit_xml(report));
}

}  // namespace crtforge
