// crtforge bench's files: bench.json (every figure), bench.md (a table) and bench.svg (error against
// cost, one point per timing, each preset's Pareto front joined): see crtforge/validate/bench.hpp.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/inert_text.hpp"
#include "crtforge/validate/bench.hpp"

namespace crtforge {

namespace {

using json = nlohmann::ordered_json;

constexpr double kPlotWidth = 900;
// Two compiles of one scene draw the same picture when their 8-bit frames agree this well (an
// optimiser's reassociation moves a value by an ulp, which can flip a rounding to 1/255).
constexpr double kSamePicturePsnr = 50;

// Costs and errors compare only at one display size: a blit's cost and the aliasing both change with it.
bool same_display(const SceneTiming& a, const SceneTiming& b) { return a.width == b.width && a.height == b.height; }

// The timings grouped by display size, in the order the sizes first appear.
std::vector<std::vector<SceneTiming>> by_display(const std::vector<SceneTiming>& timings) {
    std::vector<std::vector<SceneTiming>> groups;
    for (const SceneTiming& t : timings) {
        auto g = std::find_if(groups.begin(), groups.end(), [&](const auto& group) { return same_display(group.front(), t); });
        if (g == groups.end()) groups.push_back({t});
        else g->push_back(t);
    }
    return groups;
}

// Each preset's point tier with each of its other tiers (declared ones, "filtered",
// "filtered:<stage>"), measured at the same size with the same --uniforms variant, in the order
// they were timed (preset_tiers(): by the work they do).
std::vector<std::pair<const SceneTiming*, const SceneTiming*>> tier_pairs(const std::vector<SceneTiming>& timings) {
    std::vector<std::pair<const SceneTiming*, const SceneTiming*>> pairs;
    for (const SceneTiming& point : timings) {
        if (point.tier != "point" || !point.vs_supersampled) continue;
        for (const SceneTiming& other : timings)
            if (other.preset == point.preset && other.uniforms == point.uniforms && same_display(other, point) && !other.tier.empty() &&
                other.tier != "point" && other.vs_supersampled)
                pairs.emplace_back(&point, &other);
    }
    return pairs;
}

json cost_json(const ShaderCost& c) {
    return {{"instructions", c.instructions}, {"textureSamples", c.samples}, {"transcendentals", c.transcendentals}};
}

json metrics_json(const std::optional<ImageMetrics>& m) {
    if (!m) return nullptr;
    return {{"rmse", m->rmse}, {"psnr", m->psnr}, {"maxAbs", m->max_abs}, {"ssim", m->ssim}};
}

// Per preset and display size, the timings (its tiers and --uniforms variants) that no other timing
// of the same preset at that size beats on both cost and error against the supersampled reference; a preset timed once has
// no alternatives and no front. Across presets the errors do not compare: each is measured against
// its own preset's picture (a palette preset that matches its reference exactly at a blit's cost
// would otherwise "dominate" every CRT look).
std::vector<size_t> pareto_front(const std::vector<SceneTiming>& timings) {
    std::vector<size_t> front;
    for (size_t i = 0; i < timings.size(); ++i) {
        if (!timings[i].vs_supersampled) continue;
        bool dominated = false, alternatives = false;
        for (size_t j = 0; j < timings.size() && !dominated; ++j) {
            if (j == i || !timings[j].vs_supersampled || timings[j].preset != timings[i].preset || !same_display(timings[i], timings[j]))
                continue;
            alternatives = true;
            const double ci = timings[i].ratio(), cj = timings[j].ratio();
            const double ei = timings[i].vs_supersampled->rmse, ej = timings[j].vs_supersampled->rmse;
            dominated = cj <= ci && ej <= ei && (cj < ci || ej < ei);
        }
        if (alternatives && !dominated) front.push_back(i);
    }
    std::sort(front.begin(), front.end(), [&](size_t a, size_t b) {
        return std::make_pair(timings[a].preset, timings[a].ratio()) < std::make_pair(timings[b].preset, timings[b].ratio());
    });
    return front;
}

json stage_costs_json(const std::vector<StageCost>& costs) {
    json out = json::array();
    for (const StageCost& c : costs)
        out.push_back({{"pass", c.pass}, {"stage", c.stage}, {"form", c.form}, {"nsPerDraw", c.ns}, {"ratio", c.ratio()}});
    return out;
}


}  // namespace

std::string bench_json(const std::vector<SceneTiming>& timings) {
    json out = json::array();
    const std::vector<size_t> front = pareto_front(timings);
    for (size_t i = 0; i < timings.size(); ++i) {
        const SceneTiming& t = timings[i];
        json passes = json::array();
        for (const PassTiming& p : t.passes)
            passes.push_back({{"alias", p.alias}, {"input", {p.input_width, p.input_height}}, {"output", {p.width, p.height}},
                              {"format", p.format}, {"nsPerDraw", p.ns}, {"medianNsPerDraw", p.median_ns}, {"blitNs", p.blit_ns}, {"ratio", p.ratio()}, {"spread", p.spread},
                              {"shader", cost_json(p.cost)}});
        out.push_back({{"preset", t.preset},
                       {"tier", t.tier},
                       {"tierChanges", t.tier_changes},
                       {"uniforms", t.uniforms},
                       {"shader", cost_json(t.cost())},
                       {"device", t.device},
                       {"display", {t.width, t.height}},
                       {"frame", t.frame},
                       {"drawsPerTiming", t.draws},
                       {"rounds", t.rounds},
                       {"passes", passes},
                       {"sceneNs", t.total_ns()},
                       {"displayBlitNs", t.display_blit_ns},
                       {"ratio", t.ratio()},
                       {"errorVsPoint", metrics_json(t.vs_point)},
                       {"errorVsSupersampled", metrics_json(t.vs_supersampled)},
                       {"supersample", t.supersample},
                       {"errorRows", t.error_rows ? t.error_rows : t.height},
                       {"pointTies", t.point_ties},
                       {"stageCosts", stage_costs_json(t.stage_costs)},
                       {"retroarchCompileNs", t.retroarch_compile_ns > 0 ? json(t.retroarch_compile_ns) : json(nullptr)},
                       {"speedupVsRetroarchCompile", t.retroarch_compile_ns > 0 ? json(t.speedup_vs_retroarch()) : json(nullptr)},
                       {"frameVsRetroarchCompile", metrics_json(t.vs_retroarch_compile)},
                       {"pareto", std::find(front.begin(), front.end(), i) != front.end()}});
    }
    return out.dump(2) + "\n";
}

namespace {

std::string markdown_of_display(const std::vector<SceneTiming>& timings) {
    const std::vector<size_t> front = pareto_front(timings);
    std::string md = "| preset | display | passes | cost (x blit) | instructions / samples / transcendentals | RMSE vs point fp64 | "
                     "RMSE vs supersampled fp64 | SSIM vs supersampled | Pareto |\n"
                     "|---|---|---:|---:|---:|---:|---:|---:|:---:|\n";
    for (size_t i = 0; i < timings.size(); ++i) {
        const SceneTiming& t = timings[i];
        auto num = [](const std::optional<ImageMetrics>& m, bool ssim) {
            if (!m) return std::string("-");
            return ssim ? fmt::format("{:.4f}", m->ssim) : fmt::format("{:.5f}", m->rmse);
        };
        const ShaderCost c = t.cost();
        md += fmt::format("| {} | {}x{} | {} | {:.2f} | {} / {} / {} | {} | {} | {} | {} |\n", t.label(), t.width, t.height, t.passes.size(),
                          t.ratio(), c.instructions, c.samples, c.transcendentals,
                          num(t.vs_point, false), num(t.vs_supersampled, false), num(t.vs_supersampled, true),
                          std::find(front.begin(), front.end(), i) != front.end() ? "yes" : "");
    }
    if (auto banded = std::find_if(timings.begin(), timings.end(), [](const SceneTiming& t) { return t.error_rows > 0; }); banded != timings.end())
        md += fmt::format("\nErrors measured on {} of the {} rows (evenly spaced bands of 64 rows).\n", banded->error_rows, banded->height);
    std::string tied;
    for (const SceneTiming& t : timings)
        if (t.point_ties > 0) tied += fmt::format("{}{} ({})", tied.empty() ? "" : ", ", t.label(), t.point_ties);
    if (!tied.empty())
        md += "\nPixels whose point sample sits exactly on a discontinuity (the point reference flips under a jitter of 1/16384 px), "
              "each judged against the nearest of the reference and its renders jittered along the diagonals: " + tied + ".\n";
    if (std::any_of(timings.begin(), timings.end(), [](const SceneTiming& t) { return !t.stage_costs.empty(); })) {
        md += "\n| preset | pass | stage (form) | adds (us per draw) | adds (x blit) |\n|---|---|---|---:|---:|\n";
        for (const SceneTiming& t : timings)
            for (const StageCost& c : t.stage_costs)
                md += fmt::format("| {} | {} | {} ({}) | {:.1f} | {:.2f} |\n", t.label(), c.pass, c.stage, c.form, c.ns / 1000, c.ratio());
    }
    const std::vector<TierPick> picks = pick_tiers(timings);
    if (!picks.empty()) {
        md += fmt::format("\n| preset | tier to pick at {}x{} | why |\n|---|---|---|\n", timings.front().width, timings.front().height);
        for (const TierPick& p : picks) md += fmt::format("| {} | {} | {} |\n", p.preset, p.tier, p.why);
    }
    return md;
}

}  // namespace

namespace {

// --versus-retroarch: per scene, RetroArch's compile against each other variant, then the means.
std::string versus_retroarch_markdown(const std::vector<SceneTiming>& timings) {
    std::string md = "| preset | display | passes | RetroArch's compile (us per frame) | crtforge (us per frame) | speed-up | "
                     "same picture (PSNR on 8 bits) |\n|---|---|---:|---:|---:|---:|---:|\n";
    std::vector<double> speedups;
    std::string slower, different;
    for (const SceneTiming& t : timings) {
        if (t.retroarch_compile_ns <= 0) continue;
        const double x = t.speedup_vs_retroarch();
        speedups.push_back(x);
        const double psnr = t.vs_retroarch_compile ? t.vs_retroarch_compile->psnr : 0;
        md += fmt::format("| {} | {}x{} | {} | {:.1f} | {:.1f} | {:.2f}x | {:.1f} dB |\n", t.label(), t.width, t.height, t.passes.size(),
                          t.retroarch_compile_ns / 1000, t.total_ns() / 1000, x, psnr);
        if (x < 1) slower += fmt::format("{}{} ({:.2f}x)", slower.empty() ? "" : ", ", t.label(), x);
        if (psnr < kSamePicturePsnr) different += fmt::format("{}{} ({:.1f} dB)", different.empty() ? "" : ", ", t.label(), psnr);
    }
    double sum = 0, log_sum = 0;
    for (double x : speedups) sum += x, log_sum += std::log(x);
    const double lowest = *std::min_element(speedups.begin(), speedups.end());
    md += fmt::format("\nSpeed-up over {} scenes: mean {:.3f}x, geometric mean {:.3f}x, lowest {:.2f}x; slower than RetroArch's compile: {}.\n",
                      speedups.size(), sum / double(speedups.size()), std::exp(log_sum / double(speedups.size())), lowest,
                      slower.empty() ? "none" : slower);
    if (!different.empty()) md += fmt::format("Pictures that differ (below {:.0f} dB): {}.\n", kSamePicturePsnr, different);
    return md;
}

}  // namespace

std::string bench_markdown(const std::vector<SceneTiming>& timings) {
    const auto groups = by_display(timings);
    std::string md;
    if (groups.size() < 2) md = markdown_of_display(timings);
    else
        for (const auto& group : groups)
            md += fmt::format("{}### {}x{}\n\n{}", md.empty() ? "" : "\n", group.front().width, group.front().height, markdown_of_display(group));
    if (std::any_of(timings.begin(), timings.end(), [](const SceneTiming& t) { return t.retroarch_compile_ns > 0; }))
        md += "\n### Against RetroArch's compile (glslang alone, parameters as uniforms)\n\n" + versus_retroarch_markdown(timings);
    return md;
}

std::vector<TierPick> pick_tiers(const std::vector<SceneTiming>& timings) {
    // Per preset, variant and display size: the first tier, in the order of the work they do
    // (preset_tiers(): the cheaper declared tiers, point, each filtered stage alone, filtered, the
    // supersampled declared tiers; the bench times them in that order), whose error against the
    // supersampled reference is within a tenth of the best tier's; a tier before point only where
    // it also measured cheaper than point (it exists to be cheaper).
    std::vector<TierPick> picks;
    const auto pairs = tier_pairs(timings);
    for (size_t i = 0; i < pairs.size(); ++i) {
        const SceneTiming* point = pairs[i].first;
        if (i > 0 && pairs[i - 1].first == point) continue;  // one pick per preset, variant and size
        std::vector<const SceneTiming*> order;  // as timed: the order of the work they do
        for (const SceneTiming& t : timings)
            if (&t == point || std::any_of(pairs.begin(), pairs.end(), [&](const auto& pair) { return pair.first == point && pair.second == &t; }))
                order.push_back(&t);
        double best = point->vs_supersampled->rmse;
        for (const SceneTiming* t : order) best = std::min(best, t->vs_supersampled->rmse);
        const SceneTiming* chosen = point;
        bool before_point = true;
        for (const SceneTiming* t : order) {
            before_point = before_point && t != point;
            if (t->vs_supersampled->rmse <= 1.1 * best && (!before_point || t->ratio() < point->ratio())) {
                chosen = t;
                break;
            }
        }
        const double ep = point->vs_supersampled->rmse;
        const std::string variant = point->uniforms.empty() || point->uniforms == "default" ? "" : " uniforms=" + point->uniforms;
        if (chosen == point) {
            std::string why = fmt::format("RMSE vs supersampled {:.5f} point; filtering gains under a tenth; cost {:.2f}x blit", ep, point->ratio());
            for (const SceneTiming* t : order)
                if (t != point && t->tier.rfind("filtered", 0) != 0)  // the declared ones, cheaper or not
                    why += fmt::format("; {} RMSE {:.5f} at {:.2f}x", t->tier, t->vs_supersampled->rmse, t->ratio());
            picks.push_back({point->preset + variant, point->width, point->height, "point", why});
            continue;
        }
        const double ef = chosen->vs_supersampled->rmse;
        const double gain = 100 * (1 - ef / std::max(ep, 1e-12));
        picks.push_back({point->preset + variant, point->width, point->height, chosen->tier,
                         fmt::format("RMSE vs supersampled {:.5f} {}, {:.5f} point ({:.0f}% {}); cost {:.2f}x vs {:.2f}x blit", ef, chosen->tier,
                                     ep, std::abs(gain), gain >= 0 ? "less aliasing" : "more error", chosen->ratio(), point->ratio())});
    }
    return picks;
}

namespace {

// A colour per preset, by the preset's place among the panel's presets sorted by name: 20
// categorical colours far enough apart to tell on white (past 20 they repeat, with the legend).
const char* preset_colour(size_t index) {
    static const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2",
                                    "#7f7f7f", "#bcbd22", "#17becf", "#393b79", "#ad494a", "#637939", "#e7ba52",
                                    "#7b4173", "#3182bd", "#31a354", "#e6550d", "#756bb1", "#636363"};
    return colours[index % (sizeof colours / sizeof colours[0])];
}

// One display size's plot, `top` pixels down the picture; returns its height.
double svg_panel(const std::vector<SceneTiming>& timings, double top, std::string& out) {
    // Cost on x (ratio to a blit) and error against the supersampled reference on y, both log: the
    // costs span a blit to tens of blits (a multi-pass scene), the errors decades.
    constexpr double W = kPlotWidth, H = 560, L = 70, R = 30, T = 50, B = 50;
    double min_cost = 1e9, max_cost = 0, min_err = 1e9, max_err = 0;
    for (const SceneTiming& t : timings) {
        if (t.ratio() > 0) min_cost = std::min(min_cost, t.ratio()), max_cost = std::max(max_cost, t.ratio());
        if (t.vs_supersampled) {
            min_err = std::min(min_err, std::max(t.vs_supersampled->rmse, 1e-6));
            max_err = std::max(max_err, t.vs_supersampled->rmse);
        }
    }
    if (max_err <= 0) min_err = 1e-4, max_err = 1e-1;
    if (max_cost <= 0) min_cost = max_cost = 1;
    const double lo = std::floor(std::log10(min_err)), hi = std::max(lo + 1, std::ceil(std::log10(max_err)));
    // x from the 1-2-5 step below the cheapest to the one above the dearest.
    auto nice_below = [](double v) {
        const double d = std::pow(10.0, std::floor(std::log10(v)));
        return v >= 5 * d ? 5 * d : v >= 2 * d ? 2 * d : d;
    };
    auto nice_above = [](double v) {
        const double d = std::pow(10.0, std::floor(std::log10(v)));
        return v <= d ? d : v <= 2 * d ? 2 * d : v <= 5 * d ? 5 * d : 10 * d;
    };
    const double xmin = nice_below(min_cost * 0.95), xmax = nice_above(max_cost * 1.05);
    const double lx0 = std::log10(xmin), lx1 = std::max(lx0 + 0.3, std::log10(xmax));
    auto X = [&](double c) { return L + (W - L - R) * (std::log10(std::max(c, xmin)) - lx0) / (lx1 - lx0); };
    auto Y = [&](double e) { return T + (H - T - B) * (hi - std::log10(std::max(e, 1e-6))) / (hi - lo); };

    std::vector<std::string> presets;
    for (const SceneTiming& t : timings) presets.push_back(t.preset);
    std::sort(presets.begin(), presets.end());
    presets.erase(std::unique(presets.begin(), presets.end()), presets.end());
    auto colour = [&](const std::string& preset) {
        return preset_colour(static_cast<size_t>(std::lower_bound(presets.begin(), presets.end(), preset) - presets.begin()));
    };

    std::string body;
    for (double d = std::pow(10.0, std::floor(lx0)); d <= xmax * 1.0001; d *= 10)
        for (double m : {1.0, 2.0, 5.0}) {
            const double c = d * m;
            if (c < xmin * 0.9999 || c > xmax * 1.0001) continue;
            body += fmt::format("<line x1=\"{0:.1f}\" x2=\"{0:.1f}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#ddd\"/><text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
                                X(c), T, H - B, H - B + 16, c);
        }
    for (int d = static_cast<int>(lo); d <= hi; ++d)
        body += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#ddd\"/><text x=\"{3}\" y=\"{4}\" text-anchor=\"end\">1e{5}</text>\n",
                            L, W - R, Y(std::pow(10.0, d)), L - 6, Y(std::pow(10.0, d)) + 4, d);
    body += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">GPU time per frame, as a ratio to a blit of the same display (log)</text>\n",
                        (L + W - R) / 2, H - 12);
    body += fmt::format("<text x=\"16\" y=\"{0}\" transform=\"rotate(-90 16 {0})\" text-anchor=\"middle\">RMSE against the supersampled fp64 reference</text>\n",
                        (T + H - B) / 2);
    const std::vector<size_t> front = pareto_front(timings);
    // Each preset's front joined in its colour, cheapest first (the front is sorted by preset, then cost).
    for (size_t k = 0; k < front.size();) {
        const std::string& preset = timings[front[k]].preset;
        std::string path;
        for (; k < front.size() && timings[front[k]].preset == preset; ++k)
            path += fmt::format("{}{:.1f},{:.1f}", path.empty() ? "M" : " L", X(timings[front[k]].ratio()), Y(timings[front[k]].vs_supersampled->rmse));
        body += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n", path, colour(preset));
    }
    // A preset's tiers joined, point to filtered: what filtering buys and costs.
    for (const auto& [point, filtered] : tier_pairs(timings))
        body += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\" stroke-dasharray=\"4 3\"/>\n",
                            X(point->ratio()), Y(point->vs_supersampled->rmse), X(filtered->ratio()), Y(filtered->vs_supersampled->rmse),
                            colour(point->preset));

    // Points first (the front's last, so none of it is hidden), then labels: the front's first,
    // each at the first free spot around its point (right, left, then lines above and below,
    // inside the plot). A label with no free spot becomes a number, named in a list under the plot.
    std::vector<size_t> order;
    for (size_t i = 0; i < timings.size(); ++i)
        if (std::find(front.begin(), front.end(), i) == front.end()) order.push_back(i);
    order.insert(order.end(), front.begin(), front.end());
    struct Box { double x0, x1, y0, y1; };
    std::vector<Box> placed;
    auto overlaps = [&](const Box& b) {
        return std::any_of(placed.begin(), placed.end(), [&](const Box& o) { return b.x0 < o.x1 && o.x0 < b.x1 && b.y0 < o.y1 && o.y0 < b.y1; });
    };
    for (size_t i : order) {
        if (!timings[i].vs_supersampled) continue;
        const double x = X(timings[i].ratio()), y = Y(timings[i].vs_supersampled->rmse);
        // A point on its preset's front is ringed in black.
        const bool on_front = std::find(front.begin(), front.end(), i) != front.end();
        body += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"{}\"{}/>\n", x, y, colour(timings[i].preset),
                            on_front ? " stroke=\"#000\" stroke-width=\"1.5\"" : "");
        placed.push_back(Box{x - 4, x + 4, y - 4, y + 4});
    }
    std::vector<size_t> label_order(front.begin(), front.end());
    for (size_t i : order)
        if (std::find(front.begin(), front.end(), i) == front.end()) label_order.push_back(i);
    std::vector<std::string> unplaced;
    for (size_t i : label_order) {
        const SceneTiming& t = timings[i];
        if (!t.vs_supersampled) continue;
        const double x = X(t.ratio()), y = Y(t.vs_supersampled->rmse);
        const double width = 6.9 * static_cast<double>(t.label().size());
        bool done = false;
        for (int line = 0; line <= 6 && !done; ++line) {
            const double dy = 13.0 * ((line + 1) / 2) * (line % 2 ? -1 : 1);
            for (const bool right : {true, false}) {
                const double tx = right ? x + 7 : x - 7;
                const Box box{right ? tx : tx - width, right ? tx + width : tx, y + dy - 6, y + dy + 6};
                if (box.x0 < L || box.x1 > W - R || box.y0 < T || box.y1 > H - B || overlaps(box)) continue;
                placed.push_back(box);
                if (dy != 0)
                    body += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#999\" stroke-width=\"0.5\"/>\n",
                                        x, y, tx, y + dy);
                body += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"{}\">{}</text>\n", tx, y + dy + 4,
                                    right ? "start" : "end", html_escape(t.label()));
                done = true;
                break;
            }
        }
        if (done) continue;
        unplaced.push_back(t.label());
        const std::string number = std::to_string(unplaced.size());
        const Box box{x + 4, x + 4 + 7.0 * static_cast<double>(number.size()), y - 12, y};
        if (!overlaps(box)) placed.push_back(box);
        body += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"10\" fill=\"#555\">{}</text>\n", x + 4, y - 3, number);
    }
    // The numbered points' names, in columns under the plot.
    constexpr int kColumns = 3;
    const int rows = static_cast<int>((unplaced.size() + kColumns - 1) / kColumns);
    for (size_t k = 0; k < unplaced.size(); ++k)
        body += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\">{}: {}</text>\n", L + (W - L - R) / kColumns * static_cast<double>(k % kColumns),
                            H + 14.0 * static_cast<double>(k / kColumns), k + 1, html_escape(unplaced[k]));
    // The legend: each preset's colour, in columns under the numbered names.
    constexpr int kLegendColumns = 4;
    const double legend_top = H + 14.0 * rows + (rows ? 10 : 4);
    for (size_t k = 0; k < presets.size(); ++k) {
        const double lx = L + (W - L - R) / kLegendColumns * static_cast<double>(k % kLegendColumns);
        const double ly = legend_top + 16.0 * static_cast<double>(k / kLegendColumns);
        body += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"12\" height=\"12\" fill=\"{}\"/><text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\">{}</text>\n",
                            lx, ly, preset_colour(k), lx + 16, ly + 10, html_escape(presets[k]));
    }
    const int legend_rows = static_cast<int>((presets.size() + kLegendColumns - 1) / kLegendColumns);
    const double height = legend_top + 16.0 * legend_rows + 4;
    out += fmt::format("<g transform=\"translate(0 {})\">\n", top);
    out += fmt::format("<text x=\"{}\" y=\"18\" font-size=\"14\">crtforge bench: error against cost{}</text>\n", L,
                       timings.empty() ? std::string() : fmt::format(" ({}x{}, {})", timings.front().width, timings.front().height,
                                                                     html_escape(timings.front().device)));
    out += fmt::format("<text x=\"{}\" y=\"36\">colour: preset (legend below); line, ringed: its Pareto front; dashed: point tier to each other tier; error 0 at the bottom</text>\n", L);
    out += body + "</g>\n";
    return height;
}

}  // namespace

std::string bench_svg(const std::vector<SceneTiming>& timings) {
    // One plot per display size, stacked.
    std::string panels;
    double top = 0;
    for (const auto& group : by_display(timings)) top += svg_panel(group, top, panels) + 10;
    if (panels.empty()) top = svg_panel({}, 0, panels) + 10;
    return fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"12\">\n"
                       "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
                       kPlotWidth, top - 10) +
           panels + "</svg>\n";
}

}  // namespace crtforge
