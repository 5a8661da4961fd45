// report.json (machine-readable, mergeable across shards), junit.xml (one test case per check) and
// report.html (a contact sheet: pictures first, metrics under each render).
#include <algorithm>
#include <filesystem>
#include <map>

#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/inert_text.hpp"

#include "crtforge/validate/validation.hpp"
#include "crtforge/files.hpp"

namespace crtforge {

using json = nlohmann::ordered_json;

namespace {

json metrics_json(const Verdict& v) {
    return json{{"maxAbs", v.metrics.max_abs}, {"rmse", v.metrics.rmse}, {"psnr", v.metrics.psnr},
                {"ssim", v.metrics.ssim}, {"outlierFraction", v.outlier_fraction}, {"maxTileRmse", v.max_tile_rmse},
                {"flatMax", v.flat_max},
                {"worstPixel", json::array({v.metrics.worst_x, v.metrics.worst_y})}};
}

json golden_json(const GoldenEntry& g) {
    return json{{"id", g.id}, {"preset", g.preset}, {"input", g.input}, {"width", g.width}, {"height", g.height},
                {"inputWidth", g.input_width}, {"inputHeight", g.input_height}, {"frame", g.frame},
                {"tolerance", {{"maxRmse", g.tolerance.max_rmse}, {"outlierThreshold", g.tolerance.outlier_threshold},
                               {"maxOutlierFraction", g.tolerance.max_outlier_fraction}, {"minSsim", g.tolerance.min_ssim},
                               {"maxTileRmse", g.tolerance.max_tile_rmse}, {"why", g.tolerance.why}}}};
}

std::string report_json(const ValidationReport& report) {
    json j;
    j["run"] = {{"id", report.run_id}, {"shard", report.shard_index}, {"shards", report.shard_count}};
    j["summary"] = {{"checks", report.checks.size()}, {"passed", report.passed()}, {"failed", report.failed()}};
    j["consumers"] = json::object();
    for (const auto& [t, c] : report.consumers) j["consumers"][t] = c;
    j["goldens"] = json::array();
    for (const auto& g : report.goldens) j["goldens"].push_back(golden_json(g));
    j["checks"] = json::array();
    for (const CheckResult& c : report.checks) {
        json e{{"preset", c.preset}, {"target", c.target}, {"check", c.check}, {"passed", c.passed}};
        if (!c.message.empty()) e["message"] = c.message;
        if (c.not_rendered) e["status"] = "not-rendered";
        if (c.verdict) e["metrics"] = metrics_json(*c.verdict);
        j["checks"].push_back(std::move(e));
    }
    return j.dump(2) + "\n";
}

std::string junit_xml(const ValidationReport& report) {
    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += fmt::format("<testsuites name=\"crtforge validate\" tests=\"{}\" failures=\"{}\">\n", report.checks.size(), report.failed());
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
            if (c.passed && c.not_rendered) {
                cases += ">\n      <skipped message=\"" + xml_escape(c.message) + "\"/>\n    </testcase>\n";
            } else if (c.passed) {
                cases += "/>\n";
            } else {
                ++failures;
                cases += ">\n      <failure message=\"" + xml_escape(c.message) + "\"/>\n    </testcase>\n";
            }
        }
        out += fmt::format("  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\">\n", xml_escape(t), tests, failures) + cases + "  </testsuite>\n";
    }
    return out + "</testsuites>\n";
}

// A failure's cause without its numbers: checks that failed for one reason (a shader a consumer
// rejects fails every render of that preset on that target) group under one entry.
std::string cause_of(const std::string& message) {
    std::string out;
    for (char c : message) {
        const bool digit = (c >= '0' && c <= '9') || c == '.';
        if (digit) {
            if (out.empty() || out.back() != '#') out += '#';
        } else {
            out += c;
        }
    }
    return out;
}

// Right after the summary: every failure, each root cause once with how many checks it failed and
// links to them (compile failures included), so a page of 26 identical failures reads as one.
std::string failure_index(const ValidationReport& report) {
    struct Group {
        std::string message;  // the first check's own message
        std::vector<const CheckResult*> checks;
    };
    std::vector<Group> groups;
    std::map<std::string, size_t> index;  // cause -> group
    for (const CheckResult& c : report.checks) {
        if (c.passed || c.not_rendered) continue;
        auto [it, fresh] = index.emplace(cause_of(c.message), groups.size());
        if (fresh) groups.push_back({c.message, {}});
        groups[it->second].checks.push_back(&c);
    }
    if (groups.empty()) return {};
    std::string h = fmt::format("<h2 class=bad>Failures: {} check{}, {} cause{}</h2><ol>\n", report.failed(), report.failed() == 1 ? "" : "s",
                                groups.size(), groups.size() == 1 ? "" : "s");
    for (const Group& g : groups) {
        std::vector<std::string> targets, presets;
        for (const CheckResult* c : g.checks) {
            if (std::find(targets.begin(), targets.end(), c->target) == targets.end()) targets.push_back(c->target);
            if (std::find(presets.begin(), presets.end(), c->preset) == presets.end()) presets.push_back(c->preset);
        }
        auto joined = [](const std::vector<std::string>& items) {
            std::string out;
            for (const std::string& i : items) out += (out.empty() ? "" : ", ") + html_escape(i);
            return out;
        };
        h += fmt::format("<li><b>{} check{}</b> on {} · preset {}<br><code>{}</code><br>", g.checks.size(), g.checks.size() > 1 ? "s" : "",
                         joined(targets), joined(presets), html_escape(g.message));
        size_t shown = 0;
        for (const CheckResult* c : g.checks) {
            if (++shown > 30) {
                h += fmt::format(" … {} more", g.checks.size() - 30);
                break;
            }
            const std::string label = html_escape(c->target + " " + c->check);
            h += c->golden_id.empty() ? label + " " : "<a href=\"#g-" + html_escape(c->golden_id) + "\">" + label + "</a> ";
        }
        h += "</li>\n";
    }
    return h + "</ol>\n";
}

std::string report_html(const ValidationReport& report) {
    std::vector<std::string> targets;
    for (const auto& c : report.checks)
        if (std::find(targets.begin(), targets.end(), c.target) == targets.end()) targets.push_back(c.target);
    std::map<std::pair<std::string, std::string>, const CheckResult*> render_checks;  // (golden, target)
    for (const auto& c : report.checks)
        if (!c.golden_id.empty()) render_checks[{c.golden_id, c.target}] = &c;

    std::string h;
    h += "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>crtforge validate</title>\n<style>\n"
         "body{font:14px system-ui,sans-serif;background:#111;color:#ddd;margin:20px}"
         "h1,h2{font-weight:600}table{border-collapse:collapse}td,th{padding:4px 8px;border-bottom:1px solid #333;text-align:left}"
         ".sheet{display:flex;flex-wrap:wrap;gap:8px;margin:6px 0 22px}.strip{flex-wrap:nowrap;overflow-x:auto;margin:2px 0}"
         "figure{margin:0;padding:4px;background:#1c1c1c;border:2px solid #2a2a2a}figure.fail{border-color:#e33}"
         "figure img{display:block;image-rendering:pixelated}figcaption{font-size:12px;min-width:160px}"
         "details>summary{cursor:pointer;font-size:16px;margin:14px 0}a{color:#8bd}"
         ".bad{color:#f66}.ok{color:#7d7}\n</style></head><body>\n";
    h += fmt::format("<h1>crtforge validate: <span class=\"{}\">{} passed, {} failed</span> of {} checks</h1>\n",
                     report.failed() ? "bad" : "ok", report.passed(), report.failed(), report.checks.size());
    h += "<table><tr><th>target</th><th>consumer</th><th>passed</th><th>failed</th><th>max RMSE</th><th>min SSIM</th></tr>\n";
    for (const auto& t : targets) {
        size_t pass = 0, fail = 0;
        double max_rmse = 0, min_ssim = 1;
        for (const auto& c : report.checks) {
            if (c.target != t) continue;
            (c.passed ? pass : fail)++;
            if (c.verdict) {
                max_rmse = std::max(max_rmse, c.verdict->metrics.rmse);
                min_ssim = std::min(min_ssim, c.verdict->metrics.ssim);
            }
        }
        std::string consumer;
        for (const auto& [name, desc] : report.consumers)
            if (name == t) consumer = desc;
        h += fmt::format("<tr><td>{}</td><td>{}</td><td class=ok>{}</td><td class=\"{}\">{}</td><td>{:.5f}</td><td>{:.4f}</td></tr>\n",
                         html_escape(t), html_escape(consumer), pass, fail ? "bad" : "ok", fail, max_rmse, min_ssim);
    }
    h += "</table>\n";
    h += failure_index(report);
    // One figure per (golden, row): the input, the golden, or a target's render with its verdict.
    auto figure = [&](const GoldenEntry& g, const std::string& row, const std::string& label) {
        if (row == "input" || row == "golden")
            return fmt::format("<figure><img src=\"images/{}/{}.png\" alt=\"{}\" width=\"{}\" height=\"{}\"><figcaption style=\"max-width:{}px\">{}</figcaption></figure>\n",
                               html_escape(g.id), row, row, row == "input" ? g.input_width : g.width, row == "input" ? g.input_height : g.height,
                               std::max(160, g.width), label);
        auto it = render_checks.find({g.id, row});
        if (it == render_checks.end()) return std::string();
        const CheckResult& c = *it->second;
        std::string caption = label;
        if (c.verdict)
            caption += fmt::format("<br>RMSE {:.5f} · SSIM {:.4f}<br>max {:.3f} · PSNR {:.1f} dB", c.verdict->metrics.rmse,
                                   c.verdict->metrics.ssim, c.verdict->metrics.max_abs, c.verdict->metrics.psnr);
        if (!c.passed) caption += "<br><span class=bad>" + html_escape(c.message) + "</span>";
        // 1:1 (a scaled CRT picture moirés), the caption as wide as the picture.
        std::string out = fmt::format(
            "<figure class=\"{}\"><img src=\"images/{}/{}.png\" alt=\"{}\" width=\"{}\" height=\"{}\"><figcaption style=\"max-width:{}px\">{}</figcaption></figure>\n",
            c.passed ? "" : "fail", html_escape(g.id), html_escape(row), html_escape(row), g.width, g.height, std::max(160, g.width), caption);
        if (!c.passed && c.verdict)
            out += fmt::format("<figure class=fail><img src=\"images/{}/{}.diff.png\" alt=\"diff\" width=\"{}\" height=\"{}\"><figcaption>{} diff (red = tolerance)</figcaption></figure>\n",
                               html_escape(g.id), html_escape(row), g.width, g.height, html_escape(row));
        return out;
    };
    // Goldens of one sequence (the same scene at several frames) show as strips: a row per
    // source of images, a column per frame.
    std::vector<std::vector<const GoldenEntry*>> sequences;
    std::map<std::string, size_t> sequence_index;
    for (const GoldenEntry& g : report.goldens) {
        bool any = false;
        for (const auto& t : targets) any = any || render_checks.count({g.id, t});
        if (!any) continue;
        auto [it, fresh] = sequence_index.emplace(g.sequence(), sequences.size());
        if (fresh) sequences.emplace_back();
        sequences[it->second].push_back(&g);
    }
    // Sequences with a failing check first, then the passing ones folded away.
    auto failing = [&](const std::vector<const GoldenEntry*>& sequence) {
        for (const GoldenEntry* g : sequence)
            for (const auto& t : targets)
                if (auto it = render_checks.find({g->id, t}); it != render_checks.end() && !it->second->passed) return true;
        return false;
    };
    std::stable_partition(sequences.begin(), sequences.end(), failing);
    std::string current_preset;
    bool folded = false;
    for (const auto& sequence : sequences) {
        const GoldenEntry& first = *sequence.front();
        if (!folded && !failing(sequence)) {
            folded = true;
            current_preset.clear();
            h += "<details><summary>Passing goldens (click to show)</summary>\n";
        }
        if (first.preset != current_preset) {
            current_preset = first.preset;
            h += "<h2>" + html_escape(first.preset) + "</h2>\n";
        }
        for (const GoldenEntry* g : sequence) h += "<a id=\"g-" + html_escape(g->id) + "\"></a>";
        h += "\n";
        const std::string fit = first.fit ? std::string(", ") + display_fit_name(*first.fit) : std::string();
        if (sequence.size() == 1) {
            h += fmt::format("<div>{} — {}×{}{}, frame {}</div>\n<div class=sheet>\n", html_escape(first.input), first.width, first.height, fit,
                             first.frame);
            h += figure(first, "input", "input");
            h += figure(first, "golden", "golden (CPU fp64)");
            for (const auto& t : targets) h += figure(first, t, html_escape(t));
            h += "</div>\n";
            continue;
        }
        std::string frames;
        for (const GoldenEntry* g : sequence) frames += (frames.empty() ? "" : ", ") + std::to_string(g->frame);
        h += fmt::format("<div>{} — {}×{}{}, frames {} (a sequence: each row left to right in time)</div>\n", html_escape(first.input),
                         first.width, first.height, fit, frames);
        std::vector<std::pair<std::string, std::string>> rows = {{"input", "input"}, {"golden", "golden (CPU fp64)"}};
        for (const auto& t : targets) rows.emplace_back(t, html_escape(t));
        for (const auto& [row, label] : rows) {
            std::string strip;
            for (const GoldenEntry* g : sequence) strip += figure(*g, row, label + fmt::format(" · frame {}", g->frame));
            if (!strip.empty()) h += "<div class=\"sheet strip\">\n" + strip + "</div>\n";
        }
    }
    if (folded) h += "</details>\n";
    std::string unrendered;
    for (const auto& c : report.checks)
        if (c.not_rendered) unrendered += "<li>" + html_escape(c.preset + " on " + c.target) + "</li>\n";
    if (!unrendered.empty())
        h += "<h2 class=bad>Not rendered: no golden</h2><p>Compiled only; nothing was rendered or measured. <code>crtforge golden update</code> "
             "makes goldens, <code>crtforge golden approve</code> stores reviewed renders; <code>--strict</code> fails these.</p><ul>\n" +
             unrendered + "</ul>\n";
    return h + "</body></html>\n";
}

}  // namespace

Status write_report(const ValidationReport& report, const std::string& dir) {
    if (auto s = write_file_atomic(dir + "/report.json", report_json(report)); !s.ok()) return s;
    if (auto s = write_file_atomic(dir + "/junit.xml", junit_xml(report)); !s.ok()) return s;
    return write_file_atomic(dir + "/report.html", report_html(report));
}

namespace {
constexpr const char* kReportEntries[] = {"images", "report.json", "junit.xml", "report.html"};
}  // namespace

Result<StagedReportDir> StagedReportDir::open(const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(dir, ec)) {
        if (!fs::is_directory(dir, ec)) return make_error("is not a folder", dir, 0, "--report");
        if (!fs::is_empty(dir, ec) && !fs::exists(fs::path(dir) / "report.json", ec))
            return make_error("holds files but no report.json: not an earlier report, so it is left alone (choose an empty or new folder)",
                              dir, 0, "--report");
    }
    // Beside the folder, so commit() renames within one file system.
    const fs::path target = fs::absolute(dir, ec).lexically_normal();
    const std::string staging = (target.has_filename() ? target : target.parent_path()).string() + ".staging-" + std::to_string(::getpid());
    fs::remove_all(staging, ec);
    fs::create_directories(staging, ec);
    if (ec) return make_error("cannot create the report's staging folder: " + ec.message(), staging, 0, "--report");
    return StagedReportDir(dir, staging);
}

StagedReportDir::~StagedReportDir() {
    if (staging_.empty()) return;
    std::error_code ec;
    std::filesystem::remove_all(staging_, ec);
}

Status StagedReportDir::commit() {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) return make_error("cannot create the report folder: " + ec.message(), dir_, 0, "--report");
    for (const char* name : kReportEntries) {
        fs::remove_all(fs::path(dir_) / name, ec);
        if (ec) return make_error("cannot remove the earlier report's " + std::string(name) + ": " + ec.message(), dir_, 0, "--report");
    }
    for (const char* name : kReportEntries) {
        const fs::path from = fs::path(staging_) / name;
        if (!fs::exists(from, ec)) continue;
        fs::rename(from, fs::path(dir_) / name, ec);
        if (ec) return make_error("cannot move the report's " + std::string(name) + " into place: " + ec.message(), dir_, 0, "--report");
    }
    fs::remove_all(staging_, ec);
    staging_.clear();
    return Ok{};
}

Status copy_report_images(const std::vector<std::string>& shard_dirs, const std::string& out) {
    namespace fs = std::filesystem;
    for (const std::string& dir : shard_dirs) {
        std::error_code ec;
        const fs::path images = fs::path(dir) / "images";
        if (!fs::is_directory(images, ec)) continue;
        for (auto it = fs::recursive_directory_iterator(images, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
            if (!it->is_regular_file(ec)) continue;
            const fs::path to = fs::path(out) / "images" / fs::relative(it->path(), images, ec);
            if (fs::exists(to, ec)) continue;
            fs::create_directories(to.parent_path(), ec);
            if (!ec) fs::copy_file(it->path(), to, ec);
            if (ec) return make_error("cannot copy a shard's picture: " + ec.message(), it->path().string(), 0, "--out");
        }
        if (ec) return make_error("cannot read the shard's pictures: " + ec.message(), images.string());
    }
    return Ok{};
}

namespace {

// A golden id, preset or target names a folder or file of the merged report (images/<id>/<target>.png):
// one plain path component, never a way out of the report's folder.
bool plain_component(const std::string& s) {
    if (s.empty() || s.size() > 255 || s[0] == '.') return false;
    return std::all_of(s.begin(), s.end(), [](char c) { return c != '/' && c != '\\' && static_cast<unsigned char>(c) >= 0x20; });
}

}  // namespace

Result<ValidationReport> merge_reports(const std::vector<std::string>& dirs) {
    ValidationReport merged;
    std::map<std::string, GoldenEntry> goldens;
    std::vector<std::string> golden_order;
    std::map<unsigned, std::string> shard_paths;  // index -> report, to refuse repeats
    for (const auto& dir : dirs) {
        const std::string path = dir + "/report.json";
        auto text = read_text_file(path, kMaxDataFileBytes);
        if (!text.ok()) return text.error();
        json j = json::parse(text.value(), nullptr, false);
        if (j.is_discarded() || !j.contains("checks")) return make_error("not a crtforge report", path);
        // Shards of one run, each once, all of them.
        const json* run = j.contains("run") && j["run"].is_object() ? &j["run"] : nullptr;
        if (!run || !(*run)["id"].is_string() || !(*run)["shard"].is_number_unsigned() || !(*run)["shards"].is_number_unsigned())
            return make_error("report without a run id and shard (made by an older crtforge? run validate again)", path, 0, "run");
        const std::string id = (*run)["id"].get<std::string>();
        const unsigned index = (*run)["shard"].get<unsigned>(), count = (*run)["shards"].get<unsigned>();
        if (shard_paths.empty()) {
            merged.run_id = id;
            merged.shard_count = count;
        } else if (id != merged.run_id) {
            return make_error("shard of another run (" + id + ", not " + merged.run_id + " like " + shard_paths.begin()->second +
                                  "): merge the shards of one validate run",
                              path, 0, "run.id");
        } else if (count != merged.shard_count) {
            return make_error(fmt::format("shard of {} shards, but {} says {}", count, shard_paths.begin()->second, merged.shard_count),
                              path, 0, "run.shards");
        }
        if (index < 1 || index > count) return make_error(fmt::format("shard {} of {} is out of range", index, count), path, 0, "run.shard");
        if (auto [it, fresh] = shard_paths.emplace(index, path); !fresh)
            return make_error(fmt::format("shard {}/{} twice: also {}", index, count, it->second), path, 0, "run.shard");
        try {
            for (const auto& [t, c] : j.at("consumers").items())
                if (std::none_of(merged.consumers.begin(), merged.consumers.end(), [&](const auto& p) { return p.first == t; }))
                    merged.consumers.emplace_back(t, c.get<std::string>());
            for (const auto& g : j.at("goldens")) {
                GoldenEntry e;
                e.id = g.at("id");
                e.preset = g.at("preset");
                e.input = g.at("input");
                e.width = g.at("width");
                e.height = g.at("height");
                e.input_width = g.at("inputWidth");
                e.input_height = g.at("inputHeight");
                e.frame = g.at("frame");
                if (!plain_component(e.id)) return make_error("golden id '" + e.id + "' is not a plain name", path, 0, "goldens.id");
                const auto& t = g.at("tolerance");
                e.tolerance = {t.at("maxRmse"), t.at("outlierThreshold"), t.at("maxOutlierFraction"), t.at("minSsim"),
                               t.value("maxTileRmse", 0.0), t.at("why")};
                if (goldens.emplace(e.id, e).second) golden_order.push_back(e.id);
            }
            for (const auto& c : j.at("checks")) {
                CheckResult r{c.at("preset"), c.at("target"), c.at("check"), c.at("passed"), c.value("message", ""), {}, {}};
                if (r.check.rfind("render:", 0) == 0) r.golden_id = r.check.substr(7);
                r.not_rendered = c.value("status", "") == "not-rendered";
                if (r.check.rfind("agree:", 0) == 0) r.golden_id = r.check.substr(6);
                for (const std::string* name : {&r.preset, &r.target, &r.golden_id})
                    if (!name->empty() && !plain_component(*name))
                        return make_error("check names '" + *name + "', which is not a plain name", path, 0, "checks");
                if (c.contains("metrics")) {
                    const auto& m = c.at("metrics");
                    Verdict v;
                    v.passed = r.passed;
                    v.reason = r.passed ? "" : r.message;
                    v.metrics.max_abs = m.at("maxAbs");
                    v.metrics.rmse = m.at("rmse");
                    v.metrics.psnr = m.at("psnr");
                    v.metrics.ssim = m.at("ssim");
                    v.metrics.worst_x = m.at("worstPixel")[0];
                    v.metrics.worst_y = m.at("worstPixel")[1];
                    v.outlier_fraction = m.at("outlierFraction");
                    v.max_tile_rmse = m.value("maxTileRmse", 0.0);
                    v.flat_max = m.value("flatMax", 0.0);
                    r.verdict = v;
                }
                merged.checks.push_back(std::move(r));
            }
        } catch (const std::exception& e) {
            return make_error(std::string("malformed report: ") + e.what(), path);
        }
    }
    if (shard_paths.size() != merged.shard_count) {
        std::string missing;
        for (unsigned i = 1; i <= merged.shard_count && missing.size() < 200; ++i)
            if (!shard_paths.count(i)) missing += (missing.empty() ? "" : ", ") + fmt::format("{}/{}", i, merged.shard_count);
        return make_error("shards missing: " + missing + " (merge every shard of the run)", shard_paths.begin()->second, 0, "run.shards");
    }
    merged.shard_index = merged.shard_count = 1;  // the whole run again
    for (const auto& id : golden_order) merged.goldens.push_back(goldens.at(id));
    // Restore the unsharded order: preset, then target order, then compile before render checks
    // in golden order.
    auto target_rank = [](const std::string& t) {
        const auto& all = all_targets();
        for (size_t i = 0; i < all.size(); ++i)
            if (t == all[i].name) return i;
        return all.size();
    };
    // Compile checks in the target's shader order, then renders in golden order.
    auto check_rank = [&](const CheckResult& c) -> size_t {
        const TargetInfo* target = find_target(c.target);
        const std::vector<std::string> none;
        const auto& roles = target ? target->shader_roles : none;
        for (size_t i = 0; i < roles.size(); ++i)
            if (c.check == "compile:" + roles[i]) return i;
        return roles.size() + static_cast<size_t>(std::find(golden_order.begin(), golden_order.end(), c.golden_id) - golden_order.begin());
    };
    std::stable_sort(merged.checks.begin(), merged.checks.end(), [&](const CheckResult& a, const CheckResult& b) {
        if (a.preset != b.preset) return a.preset < b.preset;
        if (a.target != b.target) return target_rank(a.target) < target_rank(b.target);
        return check_rank(a) < check_rank(b);
    });
    return merged;
}

}  // namespace crtforge
