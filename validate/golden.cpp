#include "crtforge/validate/golden.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/runtime/image_io.hpp"
#include "crtforge/reference/reference_renderer.hpp"
#include "crtforge/runtime/test_inputs.hpp"
#include "crtforge/uniforms.hpp"
#include "crtforge/files.hpp"

namespace crtforge {

using json = nlohmann::ordered_json;

namespace {

// fp32 on the GPU against fp64 on the CPU: on lavapipe and Mesa GL every render agrees to RMSE
// <= 0.0003 and max |d| <= 0.0005 (the half-float output and 16-bit golden steps), so RMSE may be
// at most 0.004 (about 1/255): ten times that floor, still small enough to catch a wrong constant
// such as a luma weight. Where the math is discontinuous — floor() in masks and cell quantising,
// the bezel edge, texel steps — another driver's rounding can put a sample on the other side of an
// edge and flip a whole pixel, so up to 0.5% of pixels may differ by more than 0.05 rather than
// bounding the max error. A 5% scanline-period error or a swapped mask channel fails by far
// (tests/validate_test.cpp).
Tolerance default_tolerance() {
    return {0.004, 0.05, 0.005, 0.99,
            "fp32 GPU vs fp64 reference: RMSE <= 0.004 (lavapipe/Mesa measure <= 0.0003); discontinuities "
            "(floor in masks, bezel edge, texel steps) may flip up to 0.5% of pixels by more than 0.05; luma SSIM >= 0.99"};
}

}  // namespace

GoldenEntry make_golden_entry(const std::string& preset, const std::string& input, int w, int h, int input_width,
                              int input_height, int frame) {
    GoldenEntry e;
    e.preset = preset;
    e.input = input;
    e.width = w;
    e.height = h;
    e.input_width = input_width;
    e.input_height = input_height;
    e.frame = frame;
    e.id = fmt::format("{}.{}.{}x{}.f{}", preset, input, w, h, frame);
    e.tolerance = default_tolerance();
    return e;
}

Result<Image> golden_input(const GoldenEntry& entry) {
    return make_test_input(entry.input, entry.input_width, entry.input_height);
}

Result<Image> render_golden_reference(const TemplateLibrary& library, const GoldenEntry& entry) {
    const Preset* preset = library.find_preset(entry.preset);
    if (!preset) return make_error("golden '" + entry.id + "' names unknown preset '" + entry.preset + "'");
    auto variant = make_variant(library, *preset, {});
    if (!variant.ok()) return variant.error();
    auto input = golden_input(entry);
    if (!input.ok()) return input.error();
    ReferenceJob job;
    job.variant = &variant.value();
    job.input = std::move(input.value());
    job.filter = preset->filter == Filter::Nearest ? SamplerFilter::Nearest : SamplerFilter::Linear;
    job.width = entry.width;
    job.height = entry.height;
    job.time = FrameInfo::time_of_frame(entry.frame);
    auto image = render_reference(job);
    if (!image.ok()) return image;
    for (float& v : image.value().rgba) v = std::clamp(v, 0.0f, 1.0f);
    return image;
}

Result<std::vector<GoldenEntry>> load_golden_manifest(const std::string& dir) {
    const std::string path = dir + "/manifest.json";
    auto text = read_text_file(path);
    if (!text.ok()) return make_error("no golden manifest (run 'crtforge golden update')", path);
    json j = json::parse(text.value(), nullptr, false);
    if (j.is_discarded() || !j.contains("goldens")) return make_error("not a golden manifest", path);
    std::vector<GoldenEntry> out;
    try {
        for (const auto& g : j["goldens"]) {
            GoldenEntry e = make_golden_entry(g.at("preset"), g.at("input"), g.at("width"), g.at("height"),
                                              g.at("inputWidth"), g.at("inputHeight"), g.at("frame"));
            const auto& t = g.at("tolerance");
            e.tolerance = {t.at("maxRmse"), t.at("outlierThreshold"), t.at("maxOutlierFraction"), t.at("minSsim"), t.at("why")};
            if (g.at("id") != e.id) return make_error("golden id '" + g.at("id").get<std::string>() + "' does not match its fields", path);
            out.push_back(std::move(e));
        }
    } catch (const std::exception& ex) {
        return make_error(std::string("malformed golden manifest: ") + ex.what(), path);
    }
    return out;
}

Result<GoldenUpdate> update_goldens(const TemplateLibrary& library, const std::string& dir, const std::string& filter) {
    auto planned = golden_plan(library, dir);
    if (!planned.ok()) return planned.error();
    const auto& plan = planned.value();
    // Render everything first: a failure must not leave a half-updated golden set.
    std::vector<std::pair<const GoldenEntry*, Image>> images;
    for (const GoldenEntry& e : plan) {
        if (!filter.empty() && e.id.find(filter) == std::string::npos) continue;
        auto image = render_golden_reference(library, e);
        if (!image.ok()) return image.error();
        images.emplace_back(&e, std::move(image.value()));
    }
    for (const auto& [entry, image] : images)
        if (auto s = write_png(dir + "/" + entry->file(), image, 16); !s.ok()) return s.error();
    json manifest;
    manifest["note"] = "Reference images from the CPU double-precision renderer (runtime/reference). "
                       "Regenerate only with: crtforge golden update";
    manifest["goldens"] = json::array();
    for (const GoldenEntry& e : plan) {
        manifest["goldens"].push_back(json{
            {"id", e.id}, {"file", e.file()}, {"preset", e.preset}, {"input", e.input},
            {"width", e.width}, {"height", e.height}, {"inputWidth", e.input_width}, {"inputHeight", e.input_height},
            {"frame", e.frame},
            {"tolerance", {{"maxRmse", e.tolerance.max_rmse}, {"outlierThreshold", e.tolerance.outlier_threshold},
                           {"maxOutlierFraction", e.tolerance.max_outlier_fraction}, {"minSsim", e.tolerance.min_ssim},
                           {"why", e.tolerance.why}}}});
    }
    if (auto s = write_file_atomic(dir + "/manifest.json", manifest.dump(2) + "\n"); !s.ok()) return s.error();
    return GoldenUpdate{images.size(), plan.size()};
}

Result<Verdict> judge(const Image& render, const Image& golden, const Tolerance& t) {
    Image clamped = render;
    for (float& v : clamped.rgba) v = std::clamp(v, 0.0f, 1.0f);
    auto metrics = compare_images(clamped, golden);
    if (!metrics.ok()) return metrics.error();
    Verdict v;
    v.metrics = metrics.value();
    size_t outliers = 0;
    for (size_t i = 0; i < golden.rgba.size(); i += 4) {
        double worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, static_cast<double>(std::abs(clamped.rgba[i + c] - golden.rgba[i + c])));
        if (worst > t.outlier_threshold) ++outliers;
    }
    v.outlier_fraction = golden.rgba.empty() ? 0.0 : static_cast<double>(outliers) / (golden.rgba.size() / 4);
    std::vector<std::string> failures;
    if (v.metrics.rmse > t.max_rmse) failures.push_back(fmt::format("RMSE {:.4f} > {}", v.metrics.rmse, t.max_rmse));
    if (v.outlier_fraction > t.max_outlier_fraction)
        failures.push_back(fmt::format("{:.2f}% of pixels off by > {} (allowed {:.2f}%)", 100 * v.outlier_fraction,
                                       t.outlier_threshold, 100 * t.max_outlier_fraction));
    if (v.metrics.ssim < t.min_ssim) failures.push_back(fmt::format("SSIM {:.4f} < {}", v.metrics.ssim, t.min_ssim));
    v.passed = failures.empty();
    for (const auto& f : failures) v.reason += (v.reason.empty() ? "" : "; ") + f;
    return v;
}

}  // namespace crtforge
