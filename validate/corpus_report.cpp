// The corpus dashboard: corpus.json (the rows, for tools and for merging shards) and corpus.html
// (per target: presets and passes that compile, render and agree with Vulkan; the same per folder;
// the failures grouped by reason, most frequent first; a row per preset with the reason on hover).
#include <fmt/format.h>

#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "crtforge/exporter.hpp"
#include "crtforge/inert_text.hpp"
#include "crtforge/validate/corpus.hpp"

namespace crtforge {

using json = nlohmann::ordered_json;

std::string corpus_reason_class(const std::string& reason) {
    std::string s = reason;
    // The location: everything up to the last "error: " (a nested diagnostic quotes its own).
    if (const size_t at = s.rfind("error: "); at != std::string::npos) s = s.substr(at + 7);
    static const std::regex preset_prefix(R"(^preset [^,]+, target [^:]+: )");
    s = std::regex_replace(s, preset_prefix, "");
    static const std::regex quoted(R"('[^']*')");
    s = std::regex_replace(s, quoted, "'X'");
    static const std::regex numbers(R"([0-9]+(\.[0-9]+)?)");
    s = std::regex_replace(s, numbers, "N");
    if (s.size() > 160) s = s.substr(0, 157) + "...";
    return s;
}

namespace {

struct Tally {
    size_t presets = 0, imported = 0, passes = 0, passes_spirv = 0;
    std::map<std::string, size_t> passes_compiled, rendered, agrees;  // by target
};

bool rendered(const CorpusTargetResult& r) { return r.status == "agrees" || r.status == "differs"; }

void add(Tally& t, const CorpusRow& row) {
    ++t.presets;
    t.imported += row.import_error.empty();
    t.passes += row.passes;
    t.passes_spirv += row.passes_spirv;
    for (const auto& [name, r] : row.targets) {
        t.passes_compiled[name] += r.passes_compiled;
        t.rendered[name] += rendered(r);
        t.agrees[name] += r.status == "agrees";
    }
}

std::string percent(size_t part, size_t whole) {
    return whole ? fmt::format("{:.1f}%", 100.0 * static_cast<double>(part) / static_cast<double>(whole)) : "-";
}

json tally_json(const Tally& t, const std::vector<std::string>& targets) {
    json per = json::object();
    for (const std::string& name : targets) {
        auto get = [&](const std::map<std::string, size_t>& m) { return m.count(name) ? m.at(name) : size_t{0}; };
        per[name] = {{"passesCompiled", get(t.passes_compiled)}, {"rendered", get(t.rendered)}, {"agrees", get(t.agrees)}};
    }
    return json{{"presets", t.presets}, {"imported", t.imported}, {"passes", t.passes}, {"passesSpirv", t.passes_spirv}, {"targets", per}};
}

const char* kStyle = R"(<style>
body{font-family:sans-serif;margin:1.5em;color:#222}
table{border-collapse:collapse;margin:0.5em 0 1.5em}
td,th{border:1px solid #ccc;padding:2px 6px;font-size:13px;text-align:right}
td.l,th.l{text-align:left}
.agrees{background:#d7f5d7}.differs{background:#fde8b0}.render{background:#f9c9c9}
.compile{background:#f6b0b0}.refused{background:#e8c8f0}.skipped{background:#eee;color:#888}
details{margin:0.3em 0}
</style>
)";

std::string cell(const CorpusTargetResult& r, size_t passes) {
    std::string text;
    if (r.status == "agrees") text = r.psnr >= 100 ? "ok" : fmt::format("{:.1f} dB", r.psnr);
    else if (r.status == "differs") text = fmt::format("differs {:.1f}", r.psnr);
    else if (r.status == "compile" || r.status == "refused") text = fmt::format("{} {}/{}", r.status, r.passes_compiled, passes);
    else text = r.status;
    return fmt::format("<td class=\"{}\" title=\"{}\">{}</td>", r.status, html_escape(r.reason), html_escape(text));
}

json row_json(const CorpusRow& row) {
    json targets = json::object();
    for (const auto& [name, r] : row.targets)
        targets[name] = {{"status", r.status}, {"passesCompiled", r.passes_compiled}, {"psnr", r.psnr}, {"reason", r.reason}};
    return {{"preset", row.preset},
            {"folder", row.folder},
            {"passes", row.passes},
            {"importError", row.import_error},
            {"passesSpirv", row.passes_spirv},
            {"spirvError", row.spirv_error},
            {"warnings", row.warnings},
            {"targets", targets},
            {"retroarch", {{"status", row.retroarch}, {"psnr", row.retroarch_psnr}}}};
}

// A PSNR as JSON writes it: identical pictures (infinite PSNR) become null.
bool read_psnr(const json& value, double& out) {
    if (value.is_null()) {
        out = std::numeric_limits<double>::infinity();
        return true;
    }
    if (!value.is_number()) return false;
    out = value.get<double>();
    return true;
}

bool read_string(const json& object, const char* key, std::string& out) {
    auto it = object.find(key);
    if (it == object.end() || !it->is_string()) return false;
    out = it->get<std::string>();
    return true;
}

bool read_count(const json& object, const char* key, size_t& out) {
    auto it = object.find(key);
    if (it == object.end() || !it->is_number_unsigned()) return false;
    out = it->get<size_t>();
    return true;
}

}  // namespace

std::string corpus_row_line(const CorpusRow& row) { return row_json(row).dump(); }

Result<CorpusRow> corpus_row_from_line(const std::string& line) {
    const json parsed = json::parse(line, nullptr, /*allow_exceptions*/ false);
    auto bad = [](const std::string& what) { return make_error("a corpus row is malformed: " + what, {}, 0, "corpus"); };
    if (!parsed.is_object()) return bad("not a JSON object");
    CorpusRow row;
    if (!read_string(parsed, "preset", row.preset) || !read_string(parsed, "folder", row.folder) ||
        !read_count(parsed, "passes", row.passes) || !read_string(parsed, "importError", row.import_error) ||
        !read_count(parsed, "passesSpirv", row.passes_spirv) || !read_string(parsed, "spirvError", row.spirv_error) ||
        !read_count(parsed, "warnings", row.warnings))
        return bad("a field is missing or of the wrong type");
    auto targets = parsed.find("targets");
    if (targets == parsed.end() || !targets->is_object()) return bad("no targets");
    for (const auto& [name, t] : targets->items()) {
        CorpusTargetResult r;
        if (!t.is_object() || !read_string(t, "status", r.status) || !read_count(t, "passesCompiled", r.passes_compiled) ||
            !t.contains("psnr") || !read_psnr(t.at("psnr"), r.psnr) || !read_string(t, "reason", r.reason))
            return bad("target '" + name + "'");
        row.targets[name] = r;
    }
    auto ra = parsed.find("retroarch");
    if (ra == parsed.end() || !ra->is_object() || !read_string(*ra, "status", row.retroarch) || !ra->contains("psnr") ||
        !read_psnr(ra->at("psnr"), row.retroarch_psnr))
        return bad("retroarch");
    return row;
}

std::string corpus_json(const CorpusReport& report) {
    const CorpusRequest& s = report.settings;
    json rows = json::array();
    Tally all;
    for (const CorpusRow& row : report.rows) {
        add(all, row);
        rows.push_back(row_json(row));
    }
    json out{{"root", report.root},
             {"shard", {{"index", report.shard_index}, {"count", report.shard_count}}},
             {"totalPresets", report.total_presets},
             {"targets", report.targets},
             {"settings",
              {{"source", fmt::format("pixel_art {}x{}", s.source_width, s.source_height)},
               {"display", fmt::format("{}x{}", s.display_width, s.display_height)},
               {"frame", s.frame},
               {"minPsnr", s.min_psnr},
               {"smooth", s.smooth},
               {"uniforms", s.uniforms.str()}}},
             {"summary", tally_json(all, report.targets)},
             {"rows", rows}};
    return out.dump(1) + "\n";
}

std::string corpus_html(const CorpusReport& report) {
    const CorpusRequest& s = report.settings;
    std::string h = "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>crtforge corpus</title>\n";
    h += kStyle;
    h += "</head><body>\n<h1>crtforge corpus: " + html_escape(report.root) + "</h1>\n";
    h += fmt::format(
        "<p>{} presets in this report (shard {}/{} of {}). Each is imported, compiled to SPIR-V pass by pass, emitted and "
        "compiled by every target's consumer pass by pass, and rendered by each consumer: frame {} of the generated "
        "pixel_art input at {}x{} on a {}x{} display, judged against the Vulkan render (agrees at PSNR &ge; {} dB); "
        "parameters as uniforms: {}.</p>\n",
        report.rows.size(), report.shard_index, report.shard_count, report.total_presets, s.frame, s.source_width, s.source_height,
        s.display_width, s.display_height, s.min_psnr, html_escape(s.uniforms.str()));

    Tally all;
    std::map<std::string, Tally> folders;
    for (const CorpusRow& row : report.rows) {
        add(all, row);
        add(folders[row.folder], row);
    }
    h += fmt::format("<h2>Summary</h2>\n<p>Imported: {} of {} presets ({}). Passes compiled to SPIR-V: {} of {} ({}).</p>\n",
                     all.imported, all.presets, percent(all.imported, all.presets), all.passes_spirv, all.passes,
                     percent(all.passes_spirv, all.passes));
    h += "<table><tr><th class=\"l\">target</th><th>passes compiled</th><th>presets rendered</th><th>presets agreeing with Vulkan</th></tr>\n";
    for (const std::string& t : report.targets)
        h += fmt::format("<tr><td class=\"l\">{}</td><td>{} / {} ({})</td><td>{} ({})</td><td>{} ({})</td></tr>\n", t,
                         all.passes_compiled[t], all.passes, percent(all.passes_compiled[t], all.passes), all.rendered[t],
                         percent(all.rendered[t], all.presets), all.agrees[t], percent(all.agrees[t], all.presets));
    h += "</table>\n";

    h += "<h2>Per folder</h2>\n<p>Presets agreeing with Vulkan (Vulkan: rendered) / presets, per target.</p>\n<table><tr><th class=\"l\">folder</th><th>presets</th><th>imported</th>";
    for (const std::string& t : report.targets) h += "<th>" + html_escape(t) + "</th>";
    h += "</tr>\n";
    for (auto& [folder, t] : folders) {
        h += fmt::format("<tr><td class=\"l\">{}</td><td>{}</td><td>{}</td>", html_escape(folder), t.presets, t.imported);
        for (const std::string& target : report.targets) h += fmt::format("<td>{}</td>", t.agrees[target]);
        h += "</tr>\n";
    }
    h += "</table>\n";

    // Failures by reason, per step.
    h += "<h2>Failures by reason</h2>\n";
    struct Group {
        size_t count = 0;
        std::string example, reason;
    };
    auto groups_table = [&](const std::string& title, const std::vector<std::pair<std::string, std::string>>& failures) {
        if (failures.empty()) return;
        std::map<std::string, Group> groups;
        for (const auto& [preset, reason] : failures) {
            Group& g = groups[corpus_reason_class(reason)];
            if (g.count++ == 0) g.example = preset, g.reason = reason;
        }
        std::vector<std::pair<std::string, Group>> sorted(groups.begin(), groups.end());
        std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.second.count > b.second.count; });
        h += fmt::format("<details><summary>{}: {} presets, {} reasons</summary>\n<table><tr><th>presets</th><th class=\"l\">reason</th><th class=\"l\">e.g.</th></tr>\n",
                         html_escape(title), failures.size(), sorted.size());
        for (const auto& [cls, g] : sorted)
            h += fmt::format("<tr><td>{}</td><td class=\"l\" title=\"{}\">{}</td><td class=\"l\">{}</td></tr>\n", g.count,
                             html_escape(g.reason), html_escape(cls), html_escape(g.example));
        h += "</table></details>\n";
    };
    {
        std::vector<std::pair<std::string, std::string>> imports, spirv;
        for (const CorpusRow& row : report.rows) {
            if (!row.import_error.empty()) imports.emplace_back(row.preset, row.import_error);
            if (!row.spirv_error.empty()) spirv.emplace_back(row.preset, row.spirv_error);
        }
        groups_table("import", imports);
        groups_table("SPIR-V", spirv);
        for (const std::string& t : report.targets) {
            std::vector<std::pair<std::string, std::string>> failures;
            for (const CorpusRow& row : report.rows) {
                const CorpusTargetResult& r = row.targets.at(t);
                if (r.status != "agrees" && r.status != "skipped" && row.spirv_error.empty()) failures.emplace_back(row.preset, r.reason);
            }
            groups_table(t, failures);
        }
    }

    h += "<h2>Presets</h2>\n<table><tr><th class=\"l\">preset</th><th>passes</th><th>import</th><th>SPIR-V</th>";
    for (const std::string& t : report.targets) h += "<th>" + html_escape(t) + "</th>";
    const bool retroarch = !s.retroarch_dir.empty();
    if (retroarch) h += "<th>RetroArch</th>";
    h += "</tr>\n";
    for (const CorpusRow& row : report.rows) {
        h += fmt::format("<tr><td class=\"l\">{}</td><td>{}</td>", html_escape(row.preset), row.passes);
        h += row.import_error.empty() ? fmt::format("<td class=\"agrees\">ok{}</td>", row.warnings ? fmt::format(" ({} warnings)", row.warnings) : "")
                                      : fmt::format("<td class=\"compile\" title=\"{}\">failed</td>", html_escape(row.import_error));
        if (!row.import_error.empty()) h += "<td class=\"skipped\">-</td>";
        else if (row.spirv_error.empty()) h += fmt::format("<td class=\"agrees\">{}/{}</td>", row.passes_spirv, row.passes);
        else h += fmt::format("<td class=\"compile\" title=\"{}\">{}/{}</td>", html_escape(row.spirv_error), row.passes_spirv, row.passes);
        for (const std::string& t : report.targets) h += cell(row.targets.at(t), row.passes);
        if (retroarch)
            h += fmt::format("<td class=\"{}\">{}</td>", row.retroarch == "not run" ? "skipped" : row.retroarch,
                             row.retroarch == "agrees" || row.retroarch == "differs" ? fmt::format("{:.1f} dB", row.retroarch_psnr)
                                                                                     : row.retroarch);
        h += "</tr>\n";
    }
    h += "</table>\n</body></html>\n";
    return h;
}

Status write_corpus_report(const CorpusReport& report, const std::string& dir) {
    return write_files(dir, {{"corpus.json", corpus_json(report)}, {"corpus.html", corpus_html(report)}});
}

}  // namespace crtforge
