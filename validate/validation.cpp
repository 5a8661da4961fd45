// Enumerates (preset, target) jobs in a fixed order, keeps this shard's share, and runs each job's
// checks on worker threads: the consumer compiles the target's files, then every golden of the
// preset is rendered through that consumer and judged.
#include "crtforge/validate/validation.hpp"
#include "crtforge/parse_number.hpp"
#include "crtforge/version.hpp"

#include <algorithm>
#include <atomic>
#include <deque>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <mutex>
#include <optional>
#include <thread>

#include <fmt/format.h>

#include "crtforge/exporter.hpp"
#include "crtforge/files.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/validate/godot_inspector.hpp"
#include "crtforge/validate/manifest_host.hpp"
#include "crtforge/validate/target_render.hpp"

namespace crtforge {

size_t ValidationReport::failed() const {
    return static_cast<size_t>(std::count_if(checks.begin(), checks.end(), [](const CheckResult& c) { return !c.passed; }));
}

Result<Shard> Shard::parse(const std::string& text) {
    Shard s;
    const auto pair = parse_int_pair(text, '/');
    if (!pair || pair->second < 1 || pair->first < 1 || pair->first > pair->second || pair->second > 100000)
        return make_error("'" + text + "' is not a shard: expected i/n with 1 <= i <= n <= 100000, e.g. 2/4", {}, 0, "--shard");
    s.index = static_cast<unsigned>(pair->first);
    s.count = static_cast<unsigned>(pair->second);
    return s;
}

namespace {

// Loaded once per run (with the preset's work) and shared read-only by every target's job: the
// golden — read, or rendered by the reference when not stored — and its input.
struct GoldenData {
    explicit GoldenData(const GoldenEntry* e) : entry(e) {}
    const GoldenEntry* entry;
    Result<Image> golden{make_error("not loaded")};
    Result<Image> input{make_error("not loaded")};  // the input at the entry's frame, for the report
    Result<Image> unstable{make_error("not loaded")};  // where the reference flips under jitter (may be empty)
};

// The key of a variant's build options: goldens of the matrix compile other variants than the
// one that ships ("--uniforms all", "--precision medium").
std::string options_key(const VariantOptions& o) { return o.uniforms.str() + "/" + precision_name(o.precision); }

// Compiled once per preset (on whichever worker needs it first) and shared by its targets' jobs:
// the variant that ships, and every other one its goldens ask for.
struct PresetWork {
    const Preset* preset = nullptr;
    std::vector<GoldenData*> goldens;
    std::once_flag once;
    std::map<std::string, Result<std::vector<CompiledVariant>>> compiled;  // by options_key
    std::map<std::string, SharedImage> file_luts;
    std::optional<Diagnostic> lut_error;
};

struct Job {
    PresetWork* work;
    TargetId target;
    std::vector<const GoldenData*> goldens;
    bool second = false;  // renders on the second Vulkan driver: render checks only
};

// The Godot version of a Godot target, 0 for any other.
int godot_version_of(TargetId target) { return target == TargetId::Godot4 ? 4 : target == TargetId::Godot3 ? 3 : 0; }

// The name of a per-pass check: "kind:role" of a single-pass preset, "kind:alias.role" otherwise.
std::string pass_check(const Preset& preset, const Pass& pass, const std::string& kind, const std::string& role) {
    return kind + ":" + (preset.single_pass() ? role : pass.alias + "." + role);
}

// The checks of a preset's files on a target: a compile check per shader role of every pass, and
// on Godot an inspector check per pass (its params as the inspector shows them).
std::vector<std::string> compile_checks(const Preset& preset, TargetId target) {
    std::vector<std::string> checks;
    for (const Pass& pass : preset.passes) {
        for (const std::string& role : target_info(target).shader_roles) checks.push_back(pass_check(preset, pass, "compile", role));
        if (godot_version_of(target)) checks.push_back(pass_check(preset, pass, "inspector", "params"));
    }
    return checks;
}

// What the report shows of a picture: at most 640 pixels wide (the page shows 240), averaged over
// whole blocks of pixels, so a report of 1080p goldens does not spend minutes encoding PNGs.
Image report_picture(const Image& image) {
    const int k = (std::max(image.width, image.height) + 639) / 640;
    if (k <= 1) return image;
    // At least one pixel on each side: a 16384x4 row still has a picture. Each output pixel is the
    // mean of its k x k block, clipped to the image.
    Image out = Image::make(std::max(1, image.width / k), std::max(1, image.height / k));
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            float* px = out.at(x, y);
            int count = 0;
            for (int sy = y * k; sy < std::min(image.height, (y + 1) * k); ++sy)
                for (int sx = x * k; sx < std::min(image.width, (x + 1) * k); ++sx, ++count)
                    for (int c = 0; c < 4; ++c) px[c] += image.at(sx, sy)[c];
            for (int c = 0; c < 4; ++c) px[c] /= static_cast<float>(std::max(1, count));
        }
    return out;
}

// Pictures for the HTML report: the input and golden once per golden, each target's render, and
// a heat-map wherever a comparison failed (a failing render and its heat-map at full size).
Status write_pictures(const std::string& dir, const GoldenEntry& g, const std::string& target, const Image& render,
                      const Image& golden, const Image& input, const Verdict& verdict) {
    const std::string base = dir + "/images/" + g.id;
    std::error_code ec;
    std::filesystem::create_directories(base, ec);
    if (ec) return make_error("cannot create report directory: " + ec.message(), base);
    // Workers of different targets share a golden's folder: the first writes input and golden.
    static std::mutex shared_files;
    {
        std::lock_guard<std::mutex> lock(shared_files);
        if (!std::filesystem::exists(base + "/golden.png")) {
            if (auto s = write_png(base + "/golden.png", report_picture(golden), 8); !s.ok()) return s;
            if (auto s = write_png(base + "/input.png", report_picture(input), 8); !s.ok()) return s;
        }
    }
    if (auto s = write_png(base + "/" + target + ".png", verdict.passed ? report_picture(render) : render, 8); !s.ok()) return s;
    if (!verdict.passed)
        return write_png(base + "/" + target + ".diff.png", diff_heatmap(render, golden, g.tolerance.outlier_threshold), 8);
    return Ok{};
}

std::vector<CheckResult> run_job(const TemplateLibrary& library, const Job& job, const ValidateRequest& request,
                                 const Cache& cache, TargetRenderer& renderer) {
    std::vector<CheckResult> results;
    const Preset* preset = job.work->preset;
    const std::string target = std::string(target_info(job.target).name) + (job.second ? "@" + request.second_label : "");
    auto fail_all = [&](const std::string& message) {
        if (!job.second)
            for (const std::string& check : compile_checks(*preset, job.target))
                results.push_back({preset->name, target, check, false, message, {}, {}});
        for (const GoldenData* g : job.goldens) {
            results.push_back({preset->name, target, "render:" + g->entry->id, false, message, {}, g->entry->id});
            if (g->entry->approved && job.target != TargetId::Spirv)
                results.push_back({preset->name, target, "agree:" + g->entry->id, false, message, {}, g->entry->id});
        }
        return results;
    };
    std::call_once(job.work->once, [&] {
        // Goldens that share a reference (GoldenEntry::shares) are read or rendered once; each
        // is still checked for staleness on its own.
        std::map<std::string, const GoldenData*> loaded;  // by file
        for (GoldenData* d : job.work->goldens) {
            d->input = golden_input(*d->entry, d->entry->frame);
            auto same = loaded.find(d->entry->file());
            if (same != loaded.end() && same->second->golden.ok()) {
                auto current = check_golden_current(library, *d->entry, request.golden_dir);
                d->golden = current.ok() ? same->second->golden : Result<Image>(current.error());
                d->unstable = same->second->unstable;
                continue;
            }
            d->golden = load_golden_image(library, *d->entry, request.golden_dir);
            d->unstable = load_golden_unstable(*d->entry, request.golden_dir);
            loaded[d->entry->file()] = d;
        }
        std::vector<VariantOptions> options{VariantOptions{}};
        for (const GoldenData* d : job.work->goldens) options.push_back(d->entry->variant_options());
        for (const VariantOptions& o : options)
            if (!job.work->compiled.count(options_key(o))) job.work->compiled.emplace(options_key(o), compile_scene(library, *preset, o, cache));
        auto luts = read_file_luts(*preset);
        if (!luts.ok()) job.work->lut_error = luts.error();
        else job.work->file_luts = std::move(luts.value());
    });
    const auto& compiled = job.work->compiled.at(options_key({}));
    if (!compiled.ok()) return fail_all(compiled.error().str());
    if (job.work->lut_error) return fail_all(job.work->lut_error->str());
    // The target's files of every variant the job renders, by options_key.
    std::map<std::string, Result<std::vector<TargetOutput>>> emitted;
    auto outputs_for = [&](const VariantOptions& o) -> const Result<std::vector<TargetOutput>>& {
        const std::string key = options_key(o);
        if (auto it = emitted.find(key); it != emitted.end()) return it->second;
        const auto& passes = job.work->compiled.at(key);
        Result<std::vector<TargetOutput>> out = passes.ok() ? emit_scene(passes.value(), job.target, cache)
                                                            : Result<std::vector<TargetOutput>>(passes.error());
        return emitted.emplace(key, std::move(out)).first->second;
    };
    if (!outputs_for({}).ok()) return fail_all(outputs_for({}).error().str());
    const std::vector<TargetOutput>& outputs = outputs_for({}).value();

    bool compiles = true;
    for (size_t i = 0; i < outputs.size() && !job.second; ++i)  // the first driver's job compiles
        for (const OutputFile& f : outputs[i].files) {
            if (!f.is_shader()) continue;
            const std::string role = f.manifest_role();
            CheckResult r{preset->name, target, pass_check(*preset, preset->passes[i], "compile", role), false, {}, {}, {}};
            auto consumed = renderer.compile(job.target, f);
            r.passed = consumed.ok();
            if (!consumed.ok()) r.message = consumed.error().str();
            compiles = compiles && r.passed;
            results.push_back(std::move(r));
        }
    // What the Godot inspector shows of each pass's params, read back from the shader and material.
    for (size_t i = 0; i < outputs.size() && !job.second && godot_version_of(job.target); ++i) {
        CheckResult r{preset->name, target, pass_check(*preset, preset->passes[i], "inspector", "params"), false, {}, {}, {}};
        const auto problems = godot_inspector_problems(compiled.value()[i].variant, outputs[i], godot_version_of(job.target));
        r.passed = problems.empty();
        for (const std::string& p : problems) r.message += (r.message.empty() ? "" : "; ") + p;
        results.push_back(std::move(r));
    }

    // Never silently green: a rendering run with no golden for this preset on this target says so
    // as its own status, with no metrics (a pass unless --strict).
    if (request.render && !job.second && job.goldens.empty()) {
        CheckResult r{preset->name, target, "render", !request.strict,
                      "not rendered: no golden judges this preset on this target (crtforge golden update makes them; "
                      "crtforge golden approve stores a reviewed render where the reference has no model)",
                      {}, {}};
        r.not_rendered = true;
        results.push_back(std::move(r));
    }

    // Each sequence (a preset on one input, display and fit) renders once for all its frames.
    std::vector<const GoldenEntry*> entries;
    std::map<const GoldenEntry*, const GoldenData*> data_of;
    for (const GoldenData* d : job.goldens) {
        entries.push_back(d->entry);
        data_of[d->entry] = d;
    }
    std::map<const GoldenEntry*, CheckResult> checks, agreements;
    std::map<std::string, Result<std::vector<CompiledVariant>>> manifest_hosted;  // by options_key
    for (const auto& sequence : golden_sequences(entries)) {
        const GoldenEntry& first = *sequence.front();
        std::optional<std::string> failure;
        if (!compiles) failure = "not rendered: the consumer rejected the shader";
        std::vector<Image> images;
        const auto& variant_outputs = outputs_for(first.variant_options());
        if (!failure && !variant_outputs.ok()) failure = variant_outputs.error().str();
        // Vulkan draws as a host that reads only manifest.json binds and fills the passes (read
        // back once per variant the job renders).
        const std::string key = options_key(first.variant_options());
        const std::vector<CompiledVariant>* passes = &job.work->compiled.at(key).value();
        if (!failure && job.target == TargetId::Spirv) {
            auto hosted = manifest_hosted.find(key);
            if (hosted == manifest_hosted.end()) hosted = manifest_hosted.emplace(key, as_manifest_host(*preset, *passes)).first;
            if (!hosted->second.ok()) failure = hosted->second.error().str();
            else passes = &hosted->second.value();
        }
        if (!failure) {
            SceneRenderRequest sr = golden_scene_request(sequence, *preset, *passes, job.target, &variant_outputs.value());
            sr.file_luts = job.work->file_luts;
            auto rendered = renderer.render_scene(sr);
            if (!rendered.ok()) failure = rendered.error().str();
            else images = std::move(rendered.value());
        }
        const double filter_step = renderer.filtered_8bit_step(job.target, *preset);
        for (size_t i = 0; i < sequence.size(); ++i) {
            const GoldenEntry* g = sequence[i];
            const GoldenData* data = data_of.at(g);
            CheckResult r{preset->name, target, "render:" + g->id, false, {}, {}, g->id};
            if (!data->golden.ok()) {
                r.message = data->golden.error().str();
                if (r.message.find("golden update") == std::string::npos) r.message += " (run 'crtforge golden update')";
            } else if (!data->input.ok()) {
                r.message = data->input.error().str();
            } else if (!data->unstable.ok()) {
                r.message = data->unstable.error().str();
            } else if (failure) {
                r.message = *failure;
            } else {
                auto verdict = judge(images[i], data->golden.value(), with_filter_step(g->tolerance, filter_step), renderer.output_quantum(job.target),
                                     &data->unstable.value());
                if (!verdict.ok()) {
                    r.message = verdict.error().str();
                } else {
                    r.passed = verdict.value().passed;
                    r.message = verdict.value().reason;
                    r.verdict = verdict.value();
                    if (!request.report_dir.empty()) {
                        auto written = write_pictures(request.report_dir, *g, target, images[i], data->golden.value(),
                                                      data->input.value(), verdict.value());
                        if (!written.ok()) {
                            r.passed = false;
                            r.message = written.error().str();
                        }
                    }
                }
            }
            if (g->expected_to_fail(target) && r.verdict) {  // a render that failed to run is no expected failure
                // A tracked defect: its failure is expected, within the defect's own measured bound
                // (so a regression on top of it still fails); a pass means the entry must be updated.
                if (r.passed) {
                    r.passed = false;
                    r.message = "passed, but golden/plan.toml expects it to fail (" + g->expect_fail_why +
                                "): remove the target from expect_fail";
                } else {
                    auto bounded = judge(images[i], data->golden.value(), with_filter_step(g->expect_fail_bound, filter_step), renderer.output_quantum(job.target),
                                         &data->unstable.value());
                    r.passed = bounded.ok() && bounded.value().passed;
                    r.message = r.passed ? "expected failure (" + g->expect_fail_why + "): " + r.message
                                         : "worse than the tracked defect (" + g->expect_fail_why + ") allows: " +
                                               (bounded.ok() ? bounded.value().reason : bounded.error().str());
                }
            }
            checks.emplace(g, std::move(r));
        }
        // An approved golden (a user's stage the reference has no model of) is only as good as the
        // render that was approved, so every target must also agree with this run's Vulkan render of
        // the same SPIR-V, judged alike.
        if (first.approved && job.target != TargetId::Spirv) {
            std::vector<Image> vulkan_images;
            std::optional<std::string> vulkan_failure = failure;
            if (!vulkan_failure) {
                SceneRenderRequest sr =
                    golden_scene_request(sequence, *preset, job.work->compiled.at(options_key(first.variant_options())).value(), TargetId::Spirv);
                sr.file_luts = job.work->file_luts;
                auto rendered = renderer.render_scene(sr);
                if (!rendered.ok()) vulkan_failure = "the Vulkan render to agree with failed: " + rendered.error().str();
                else vulkan_images = std::move(rendered.value());
            }
            for (size_t i = 0; i < sequence.size(); ++i) {
                const GoldenEntry* g = sequence[i];
                CheckResult r{preset->name, target, "agree:" + g->id, false, {}, {}, g->id};
                if (vulkan_failure) {
                    r.message = *vulkan_failure;
                } else {
                    auto verdict = judge(images[i], vulkan_images[i], with_filter_step(g->tolerance, filter_step), renderer.output_quantum(job.target));
                    if (!verdict.ok()) {
                        r.message = verdict.error().str();
                    } else {
                        r.passed = verdict.value().passed;
                        r.message = r.passed ? "" : "disagrees with Vulkan: " + verdict.value().reason;
                        r.verdict = verdict.value();
                    }
                }
                agreements.emplace(g, std::move(r));
            }
        }
    }
    for (const GoldenData* d : job.goldens) {
        results.push_back(std::move(checks.at(d->entry)));
        if (auto a = agreements.find(d->entry); a != agreements.end()) results.push_back(std::move(a->second));
    }
    return results;
}

}  // namespace

Result<ValidationReport> run_validation(const TemplateLibrary& library, const ValidateRequest& request,
                                        const Cache& cache, const ProgressFn& progress) {
    for (const auto& name : request.presets)
        if (auto p = library.lookup_preset(name); !p.ok()) return p.error();
    std::vector<TargetId> targets = request.targets;
    if (targets.empty())
        for (const auto& t : all_targets()) targets.push_back(t.id);

    ValidationReport report;
    report.shard_index = request.shard.index;
    report.shard_count = request.shard.count;
    report.run_id = request.run_id;
    if (report.run_id.empty()) {
        std::string what = fmt::format("{}|render {}|full {}|", CRTFORGE_VERSION, request.render, request.full_matrix);
        for (const auto& p : request.presets) what += "preset " + p + "|";
        for (TargetId t : targets) what += std::string("target ") + target_info(t).name + "|";
        for (const auto& i : request.inputs) what += "input " + i + "|";
        if (request.render)
            if (auto manifest = read_text_file(request.golden_dir + "/manifest.json", kMaxDataFileBytes); manifest.ok()) what += manifest.value();
        report.run_id = Cache::key({what}).substr(0, 16);
    }
    if (request.render) {
        auto goldens = load_golden_manifest(request.golden_dir);
        if (!goldens.ok()) return goldens.error();
        for (const auto& in : request.inputs) {
            bool known = false;
            for (const auto& g : goldens.value()) known = known || g.input == in;
            if (!known) return make_error("no golden uses input '" + in + "'", {}, 0, "--input");
        }
        for (const auto& g : goldens.value())
            if ((request.inputs.empty() || std::find(request.inputs.begin(), request.inputs.end(), g.input) != request.inputs.end()) &&
                (request.full_matrix || !g.full_matrix))
                report.goldens.push_back(g);
    }

    // A shard takes every count-th (preset, target) pair, so work spreads evenly and the shards'
    // reports concatenate back into the full, ordered report.
    std::set<TargetId> vulkan_rendered;
    {
        TargetRenderer probe(request.vulkan);
        for (TargetId t : targets)
            if (probe.renders_on_vulkan(t)) vulkan_rendered.insert(t);
    }
    // The goldens a target judges (a matrix entry may name its targets).
    auto judged_by = [](const std::vector<const GoldenData*>& goldens, TargetId t) {
        std::vector<const GoldenData*> out;
        for (const GoldenData* d : goldens)
            if (d->entry->judged_by(target_info(t).name)) out.push_back(d);
        return out;
    };
    // One render check per golden, and an agreement check per approved golden off SPIR-V.
    auto render_checks = [](const std::vector<const GoldenData*>& goldens, TargetId t) {
        size_t n = goldens.size();
        for (const GoldenData* d : goldens) n += d->entry->approved && t != TargetId::Spirv;
        return n;
    };
    std::vector<Job> jobs;
    std::deque<PresetWork> presets;  // stable addresses for the jobs' pointers
    std::deque<GoldenData> golden_data;
    size_t index = 0;
    size_t total = 0;
    for (const Preset& p : library.presets()) {
        if (!request.presets.empty() && std::find(request.presets.begin(), request.presets.end(), p.name) == request.presets.end())
            continue;
        PresetWork* work = nullptr;  // made when this shard takes the preset's first job
        std::vector<const GoldenData*> goldens;
        auto add_job = [&](TargetId t, bool second) {
            if (index++ % request.shard.count != request.shard.index - 1) return;
            if (!work) {
                work = &presets.emplace_back();
                work->preset = &p;
                for (const GoldenEntry& g : report.goldens) {
                    if (g.preset != p.name) continue;
                    GoldenData& d = golden_data.emplace_back(&g);
                    work->goldens.push_back(&d);
                    goldens.push_back(&d);
                }
            }
            auto mine = judged_by(goldens, t);
            // The second driver's jobs render only: the first driver's compile checks stand for both.
            total += (second ? 0 : compile_checks(p, t).size()) + render_checks(mine, t) + (request.render && !second && mine.empty());
            jobs.push_back(Job{work, t, std::move(mine), second});
        };
        for (TargetId t : targets) add_job(t, false);
        // The Vulkan-rendered targets again on the second driver.
        if (request.second_vulkan && request.render)
            for (TargetId t : targets)
                if (vulkan_rendered.count(t)) add_job(t, true);
    }

    std::vector<std::vector<CheckResult>> results(jobs.size());
    std::atomic<size_t> next{0}, done{0};
    std::mutex progress_mutex;
    auto worker = [&] {
        TargetRenderer renderer(request.vulkan);  // engines are per thread
        std::unique_ptr<TargetRenderer> second;
        for (size_t i = next++; i < jobs.size(); i = next++) {
            if (jobs[i].second && !second) second = std::make_unique<TargetRenderer>(*request.second_vulkan);
            results[i] = run_job(library, jobs[i], request, cache, jobs[i].second ? *second : renderer);
            std::lock_guard<std::mutex> lock(progress_mutex);
            for (const auto& r : results[i]) {
                ++done;
                if (progress) progress(done, total, r);
            }
        }
    };
    const unsigned threads = std::max(1u, std::min<unsigned>(request.jobs, static_cast<unsigned>(jobs.size())));
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    for (auto& r : results) report.checks.insert(report.checks.end(), r.begin(), r.end());

    if (request.render) {
        TargetRenderer describe(request.vulkan);
        for (TargetId t : targets) report.consumers.emplace_back(target_info(t).name, describe.consumer(t));
        if (request.second_vulkan) {
            TargetRenderer other(*request.second_vulkan);
            for (TargetId t : targets)
                if (vulkan_rendered.count(t))
                    report.consumers.emplace_back(std::string(target_info(t).name) + "@" + request.second_label, other.consumer(t));
        }
    }
    return report;
}

}  // namespace crtforge
