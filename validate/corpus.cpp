// run_corpus(): each preset of the shard imported into a folder of its own (removed when done), its
// passes compiled to SPIR-V one by one (a failing pass does not hide the rest), every target's
// emitter and consumer compile per pass, the scene rendered by each target's consumer and judged
// against the Vulkan render (a consumer on another driver also against Vulkan on that driver).
// Worker threads each own their engines (TargetRenderer); the heavy
// consumers (Godot, Dawn) are the process's shared servers, started once per run.
#include "crtforge/validate/corpus.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <optional>
#include <regex>
#include <thread>

#include <fmt/format.h>

#include "crtforge/exporter.hpp"
#include "crtforge/files.hpp"
#include "crtforge/runtime/image_compare.hpp"
#include "crtforge/runtime/image_io.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/slang_import.hpp"
#include "crtforge/template_library.hpp"
#include "crtforge/validate/target_render.hpp"

namespace crtforge {

namespace fs = std::filesystem;

Result<std::vector<std::string>> list_corpus_presets(const std::string& root) {
    std::error_code ec;
    if (!fs::is_directory(root, ec)) return make_error("is not a folder", root, 0, "corpus");
    std::vector<std::string> found;
    fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
        const fs::directory_entry& entry = *it;
        std::error_code e;
        if (entry.is_symlink(e) || !entry.is_regular_file(e) || entry.path().extension() != ".slangp") continue;
        found.push_back(fs::relative(entry.path(), root, e).generic_string());
    }
    if (ec) return make_error("cannot list: " + ec.message(), root, 0, "corpus");
    std::sort(found.begin(), found.end());
    return found;
}

namespace {

constexpr size_t kMaxReason = 400;

// A diagnostic as one line of the report, the run's temporary folder shown as "<imported>" so
// the same corpus gives the same report.
std::string one_line(const Diagnostic& d) {
    static const std::regex overlay(R"([^ :']*crtforge-corpus-[A-Za-z0-9]{6}/overlay/)");
    std::string s = std::regex_replace(d.str(), overlay, "<imported>/");
    if (s.size() > kMaxReason) s = s.substr(0, kMaxReason - 3) + "...";
    return s;
}

bool all_finite(const Image& image) {
    return std::all_of(image.rgba.begin(), image.rgba.end(), [](float v) { return std::isfinite(v); });
}

std::string folder_of(const std::string& preset) {
    const size_t slash = preset.rfind('/');
    if (slash == std::string::npos) return ".";
    std::string dir = preset.substr(0, slash);
    // At most two levels: a folder's summary gathers its sub-folders.
    const size_t first = dir.find('/');
    if (first != std::string::npos) {
        const size_t second = dir.find('/', first + 1);
        if (second != std::string::npos) dir.resize(second);
    }
    return dir;
}

// A consumer that draws on another driver than the sweep's Vulkan renders (Godot 4's web build:
// WebGL 2 in Chromium, on SwiftShader: Consumer::draws_on_swiftshader) and differs from them is
// judged again against Vulkan on its own driver: a shader's own knife-edge arithmetic (a sin-based
// hash, a loop past lavapipe's 65535 steps) comes out apart on two drivers, which is not the
// translation's doing. Both figures are reported.
// Vulkan on SwiftShader, for those judgements: found and started at its first use (a sweep
// whose every target agrees never lists the devices); none where it is not installed or the
// sweep already draws on it.
class SwiftShaderJudge {
public:
    explicit SwiftShaderJudge(const EngineOptions& sweep) : sweep_(sweep) {}
    bool available() {
        if (looked_) return !device_.empty();
        looked_ = true;
        if (auto found = vulkan_device_named("SwiftShader", sweep_.device); found.ok()) device_ = found.value();
        return !device_.empty();
    }
    Result<Image> render(SceneRenderRequest scene, const std::vector<TargetOutput>& spirv_outputs) {
        if (!renderer_) renderer_ = std::make_unique<TargetRenderer>(EngineOptions{device_, sweep_.validation});
        scene.target = TargetId::Spirv;
        scene.outputs = &spirv_outputs;
        auto images = renderer_->render_scene(scene);
        if (!images.ok()) return images.error();
        if (images.value().empty()) return make_error("no image", {}, 0, "corpus");
        return std::move(images.value().front());
    }

private:
    EngineOptions sweep_;
    bool looked_ = false;
    std::string device_;
    std::unique_ptr<TargetRenderer> renderer_;
};

std::string decibels(double psnr) { return fmt::format("{:.2f} dB", psnr); }

CorpusRow run_one(const CorpusRequest& request, const std::string& rel, const Cache& cache, TargetRenderer& renderer,
                  SwiftShaderJudge& swiftshader) {
    CorpusRow row = corpus_row_for(request, rel);
    auto skip_all = [&](const std::string& why) {
        for (auto& [name, r] : row.targets) r.reason = why;
    };

    SlangImportOptions options;
    options.root = request.root;
    options.unset_filter = request.smooth ? Filter::Linear : Filter::Nearest;
    options.source_width = request.source_width;
    options.source_height = request.source_height;
    auto imported = import_slangp(request.root + "/" + rel, options);
    if (!imported.ok()) {
        row.import_error = one_line(imported.error());
        skip_all("not imported");
        return row;
    }
    row.warnings = imported.value().warnings.size();
    // The preset's overlay, in a folder of its own that goes however the preset ends.
    auto work = TemporaryFolder::create("crtforge-corpus");
    auto library = [&]() -> Result<std::shared_ptr<TemplateLibrary>> {
        if (!work.ok()) return work.error();
        const std::string overlay = (work.value().path() / "overlay").string();
        if (auto s = write_imported_preset(imported.value(), overlay); !s.ok()) return s.error();
        return TemplateLibrary::load(overlay);
    }();
    if (!library.ok()) {
        row.import_error = one_line(library.error());
        skip_all("not imported");
        return row;
    }
    const TemplateLibrary& lib = *library.value();
    auto found = lib.lookup_preset(imported.value().name);
    if (!found.ok()) {
        row.import_error = one_line(found.error());
        skip_all("not imported");
        return row;
    }
    const Preset* preset = found.value();
    row.passes = preset->passes.size();

    // SPIR-V, pass by pass: every pass that compiles is still emitted for the targets. Vulkan alone
    // renders the SPIR-V as it is: it needs no readable names.
    const bool spirv_only = std::all_of(request.targets.begin(), request.targets.end(), [](TargetId t) { return t == TargetId::Spirv; });
    std::vector<CompiledVariant> passes(preset->passes.size());  // the scene renders them once all compiled
    std::vector<bool> compiled(preset->passes.size(), false);
    for (size_t i = 0; i < preset->passes.size(); ++i) {
        VariantOptions variant;
        variant.uniforms = request.uniforms;
        variant.local_names = !spirv_only;
        variant.specialize_baked = spirv_only;
        auto pass = compile_variant(lib, *preset, variant, cache, i);
        if (pass.ok()) {
            passes[i] = std::move(pass.value());
            compiled[i] = true;
            ++row.passes_spirv;
        } else if (row.spirv_error.empty()) {
            row.spirv_error = one_line(pass.error());
        }
    }

    auto luts = read_file_luts(*preset);
    const int w = request.source_width, h = request.source_height;
    SceneRenderRequest scene;
    scene.preset = preset;
    scene.source = [w, h](int frame) { return make_test_input("pixel_art", w, h, frame); };
    scene.width = request.display_width;
    scene.height = request.display_height;
    scene.frames = {request.frame};
    scene.frame_count_base = 1;  // RetroArch's Vulkan driver draws its first frame with FrameCount 1
    // RetroArch's display is 8-bit: values clamp to 0..1 and a NaN shows as 0, as on any UNORM target.
    scene.format = OutputFormat::Rgba8Unorm;
    if (luts.ok()) scene.file_luts = std::move(luts.value());
    scene.passes = &passes;

    std::optional<Image> vulkan;  // the judge of the other targets
    std::vector<TargetOutput> spirv_outputs;        // its passes, drawn again on SwiftShader where needed
    std::optional<Result<Image>> vulkan_swiftshader;  // that render, made at its first use
    for (TargetId t : request.targets) {
        CorpusTargetResult& r = row.targets[target_info(t).name];
        std::vector<TargetOutput> outputs;
        std::string first_failure, status;
        for (size_t i = 0; i < compiled.size(); ++i) {
            if (!compiled[i]) continue;
            auto emitted = emit_target(passes[i], t, cache);
            if (!emitted.ok()) {
                if (first_failure.empty()) first_failure = one_line(emitted.error()), status = "refused";
                continue;
            }
            bool accepted = true;
            for (const OutputFile& f : emitted.value().files) {
                if (!f.is_shader()) continue;
                auto consumed = renderer.compile(t, f);
                if (consumed.ok()) continue;
                accepted = false;
                if (first_failure.empty())
                    first_failure = "pass " + std::to_string(i) + " (" + preset->passes[i].alias + "), " + f.manifest_role() + ": " +
                                    one_line(consumed.error()), status = "compile";
                break;
            }
            if (accepted) ++r.passes_compiled;
            outputs.push_back(std::move(emitted.value()));
        }
        if (!row.spirv_error.empty()) {
            r.status = "compile";
            r.reason = "SPIR-V: " + row.spirv_error;
            continue;
        }
        if (!first_failure.empty()) {
            r.status = status;
            r.reason = first_failure;
            continue;
        }
        if (!luts.ok()) {
            r.status = "render";
            r.reason = one_line(luts.error());
            continue;
        }
        scene.target = t;
        scene.outputs = &outputs;
        auto images = renderer.render_scene(scene);
        if (!images.ok() || images.value().empty()) {
            r.status = "render";
            r.reason = images.ok() ? "no image" : one_line(images.error());
            continue;
        }
        Image& image = images.value().front();
        if (!all_finite(image)) {
            r.status = "render";
            r.reason = "the render has non-finite pixels (NaN or infinity)";
            continue;
        }
        if (t == TargetId::Spirv) {
            r.status = "agrees";
            r.psnr = 100;
            vulkan = std::move(image);
            spirv_outputs = std::move(outputs);
            continue;
        }
        if (!vulkan) {
            r.status = "differs";
            r.reason = "no Vulkan render to judge it against";
            continue;
        }
        auto metrics = compare_images(image, *vulkan);
        if (!metrics.ok()) {
            r.status = "differs";
            r.reason = one_line(metrics.error());
            continue;
        }
        r.psnr = metrics.value().psnr;
        r.status = r.psnr >= request.min_psnr ? "agrees" : "differs";
        if (r.status == "agrees") continue;
        r.reason = "PSNR " + std::to_string(r.psnr).substr(0, 5) + " dB against Vulkan (worst pixel at " +
                   std::to_string(metrics.value().worst_x) + "," + std::to_string(metrics.value().worst_y) + ")";
        if (!renderer.draws_on_swiftshader(t) || !swiftshader.available()) continue;
        if (!vulkan_swiftshader) vulkan_swiftshader = swiftshader.render(scene, spirv_outputs);
        if (!vulkan_swiftshader->ok()) {
            r.reason += "; Vulkan on SwiftShader, its driver, did not render: " + one_line(vulkan_swiftshader->error());
            continue;
        }
        auto same_driver = compare_images(image, vulkan_swiftshader->value());
        if (!same_driver.ok()) continue;
        const double lavapipe = r.psnr;
        if (same_driver.value().psnr < request.min_psnr) {
            r.reason += "; " + decibels(same_driver.value().psnr) + " against Vulkan on SwiftShader, its driver";
            continue;
        }
        r.status = "agrees";
        r.psnr = same_driver.value().psnr;
        r.reason = "agrees with Vulkan on SwiftShader, the driver it draws on (" + decibels(r.psnr) + "); " + decibels(lavapipe) +
                   " against Vulkan on " + (request.vulkan.device.empty() ? std::string("lavapipe") : request.vulkan.device) +
                   ": the shader's own arithmetic, which the two drivers compute apart";
    }

    if (!request.retroarch_dir.empty()) {
        const std::string path = request.retroarch_dir + "/" + rel + ".png";
        std::error_code ec;
        if (!fs::exists(path, ec)) {
            row.retroarch = "not run";
        } else if (!vulkan) {
            row.retroarch = "render";
        } else if (auto theirs = read_image(path); !theirs.ok()) {
            row.retroarch = "differs";
        } else if (auto m = compare_images(*vulkan, theirs.value()); !m.ok()) {
            row.retroarch = "differs";
        } else {
            row.retroarch_psnr = m.value().psnr;
            row.retroarch = row.retroarch_psnr >= request.min_psnr ? "agrees" : "differs";
        }
    }
    return row;
}

}  // namespace

Result<std::vector<std::string>> corpus_shard_presets(const CorpusRequest& request) {
    if (request.shard.count == 0 || request.shard.index < 1 || request.shard.index > request.shard.count)
        return make_error("shard index must be 1..count", {}, 0, "--shard");
    std::vector<std::string> mine;
    for (size_t i = 0; i < request.presets.size(); ++i)
        if (i % request.shard.count == request.shard.index - 1) mine.push_back(request.presets[i]);
    return mine;
}

CorpusReport empty_corpus_report(const CorpusRequest& request) {
    CorpusReport report;
    report.root = request.root;
    report.shard_index = request.shard.index;
    report.shard_count = request.shard.count;
    report.total_presets = request.presets.size();
    report.settings = request;
    for (TargetId t : request.targets) report.targets.push_back(target_info(t).name);
    return report;
}

CorpusRow corpus_row_for(const CorpusRequest& request, const std::string& preset) {
    CorpusRow row;
    row.preset = preset;
    row.folder = folder_of(preset);
    for (TargetId t : request.targets) row.targets[target_info(t).name] = {};
    return row;
}

Result<CorpusReport> run_corpus(const CorpusRequest& request, const Cache& cache, const CorpusProgress& progress) {
    auto shard = corpus_shard_presets(request);
    if (!shard.ok()) return shard.error();
    const std::vector<std::string>& mine = shard.value();
    CorpusReport report = empty_corpus_report(request);
    report.rows.resize(mine.size());
    std::atomic<size_t> next{0};
    size_t done = 0;
    std::mutex progress_mutex;
    auto worker = [&] {
        TargetRenderer renderer(request.vulkan);
        SwiftShaderJudge swiftshader(request.vulkan);
        for (size_t i = next++; i < mine.size(); i = next++) {
            report.rows[i] = run_one(request, mine[i], cache, renderer, swiftshader);
            std::lock_guard<std::mutex> lock(progress_mutex);
            ++done;
            if (progress) progress(done, mine.size(), report.rows[i]);
        }
    };
    const unsigned threads = std::max(1u, std::min<unsigned>(request.jobs, static_cast<unsigned>(std::max<size_t>(mine.size(), 1))));
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    return report;
}

}  // namespace crtforge
