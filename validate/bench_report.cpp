// crtforge bench's files: bench.json (every figure), bench.md (a table) and bench.svg (error against
// cost, one point per preset, the Pareto front joined): see crtforge/validate/bench.hpp.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "crtforge/validate/bench.hpp"

namespace crtforge {

namespace {

using json = nlohmann::ordered_json;

// Each preset's point tier with each of its other tiers ("filtered", "filtered:<stage>"), measured
// with the same --uniforms variant.
std::vector<std::pair<const SceneTiming*, const SceneTiming*>> tier_pairs(const std::vector<SceneTiming>& timings) {
    std::vector<std::pair<const SceneTiming*, const SceneTiming*>> pairs;
    for (const SceneTiming& point : timings) {
        if (point.tier != "point" || !point.vs_supersampled) continue;
        for (const SceneTiming& filtered : timings)
            if (filtered.preset == point.preset && filtered.uniforms == point.uniforms && filtered.tier.rfind("filtered", 0) == 0 &&
                filtered.vs_supersampled)
                pairs.emplace_back(&point, &filtered);
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

// The presets no other preset beats on both cost and error (against the supersampled reference).
std::vector<size_t> pareto_front(const std::vector<SceneTiming>& timings) {
    std::vector<size_t> front;
    for (size_t i = 0; i < timings.size(); ++i) {
        if (!timings[i].vs_supersampled) continue;
        bool dominated = false;
        for (size_t j = 0; j < timings.size() && !dominated; ++j) {
            if (j == i || !timings[j].vs_supersampled) continue;
            const double ci = timings[i].ratio(), cj = timings[j].ratio();
            const double ei = timings[i].vs_supersampled->rmse, ej = timings[j].vs_supersampled->rmse;
            dominated = cj <= ci && ej <= ei && (cj < ci || ej < ei);
        }
        if (!dominated) front.push_back(i);
    }
    std::sort(front.begin(), front.end(), [&](size_t a, size_t b) { return timings[a].ratio() < timings[b].ratio(); });
    return front;
}

std::string xml_escape(const std::string& s) {
    std::string out;
    for (char c : s) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
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
                              {"format", p.format}, {"nsPerDraw", p.ns}, {"blitNs", p.blit_ns}, {"ratio", p.ratio()}, {"spread", p.spread},
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
                       {"passes", passes},
                       {"sceneNs", t.total_ns()},
                       {"displayBlitNs", t.display_blit_ns},
                       {"ratio", t.ratio()},
                       {"errorVsPoint", metrics_json(t.vs_point)},
                       {"errorVsSupersampled", metrics_json(t.vs_supersampled)},
                       {"supersample", t.supersample},
                       {"pareto", std::find(front.begin(), front.end(), i) != front.end()}});
    }
    return out.dump(2) + "\n";
}

std::string bench_markdown(const std::vector<SceneTiming>& timings) {
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
    const std::vector<TierPick> picks = pick_tiers(timings);
    if (!picks.empty()) {
        md += fmt::format("\n| preset | tier to pick at {}x{} | why |\n|---|---|---|\n", timings.front().width, timings.front().height);
        for (const TierPick& p : picks) md += fmt::format("| {} | {} | {} |\n", p.preset, p.tier, p.why);
    }
    return md;
}

std::vector<TierPick> pick_tiers(const std::vector<SceneTiming>& timings) {
    // Per preset: the point tier unless another lowers the aliasing error by at least a tenth; of
    // those, the one doing the least work (the partial tiers come before "filtered") whose error is
    // within a tenth of the best tier's.
    std::vector<TierPick> picks;
    const auto pairs = tier_pairs(timings);
    for (size_t i = 0; i < pairs.size(); ++i) {
        const SceneTiming* point = pairs[i].first;
        if (i > 0 && pairs[i - 1].first == point) continue;  // one pick per preset and variant
        double best = point->vs_supersampled->rmse;
        for (const auto& [p, t] : pairs)
            if (p == point) best = std::min(best, t->vs_supersampled->rmse);
        const SceneTiming* chosen = nullptr;
        for (const auto& [p, t] : pairs)
            if (p == point && !chosen && t->vs_supersampled->rmse <= 0.9 * point->vs_supersampled->rmse &&
                t->vs_supersampled->rmse <= 1.1 * best)
                chosen = t;
        const double ep = point->vs_supersampled->rmse;
        const std::string variant = point->uniforms.empty() || point->uniforms == "default" ? "" : " uniforms=" + point->uniforms;
        if (!chosen) {
            picks.push_back({point->preset + variant, "point", fmt::format("RMSE vs supersampled {:.5f} point; filtering gains under a tenth; cost {:.2f}x blit", ep, point->ratio())});
            continue;
        }
        const double ef = chosen->vs_supersampled->rmse;
        picks.push_back({point->preset + variant, chosen->tier,
                         fmt::format("RMSE vs supersampled {:.5f} {}, {:.5f} point ({:.0f}% less aliasing); cost {:.2f}x vs {:.2f}x blit", ef,
                                     chosen->tier, ep, 100 * (1 - ef / std::max(ep, 1e-12)), chosen->ratio(), point->ratio())});
    }
    return picks;
}

std::string bench_svg(const std::vector<SceneTiming>& timings) {
    // Cost on x (ratio to a blit, linear), error against the supersampled reference on y (log).
    constexpr double W = 760, H = 500, L = 70, R = 30, T = 50, B = 50;
    double max_cost = 1, min_err = 1e9, max_err = 0;
    for (const SceneTiming& t : timings) {
        max_cost = std::max(max_cost, t.ratio());
        if (t.vs_supersampled) {
            min_err = std::min(min_err, std::max(t.vs_supersampled->rmse, 1e-6));
            max_err = std::max(max_err, t.vs_supersampled->rmse);
        }
    }
    if (max_err <= 0) min_err = 1e-4, max_err = 1e-1;
    const double lo = std::floor(std::log10(min_err)), hi = std::max(lo + 1, std::ceil(std::log10(max_err)));
    // About eight x ticks of 1, 2, 5, 10, ... blits.
    double step = 1;
    while (max_cost / step > 8) step = step == 1 ? 2 : step == 2 ? 5 : step * 2;
    const double xmax = step * std::ceil((max_cost + 0.25) / step);
    auto X = [&](double c) { return L + (W - L - R) * c / xmax; };
    auto Y = [&](double e) { return T + (H - T - B) * (hi - std::log10(std::max(e, 1e-6))) / (hi - lo); };
    std::string s = fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"12\">\n"
                                "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n", W, H);
    s += fmt::format("<text x=\"{}\" y=\"18\" font-size=\"14\">crtforge bench: error against cost{}</text>\n", L,
                     timings.empty() ? std::string() : fmt::format(" ({}x{}, {})", timings.front().width, timings.front().height,
                                                                   xml_escape(timings.front().device)));
    for (double c = 0; c <= xmax + 1e-9; c += step)
        s += fmt::format("<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#ddd\"/><text x=\"{0}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
                         X(c), T, H - B, H - B + 16, c);
    for (int d = static_cast<int>(lo); d <= hi; ++d)
        s += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#ddd\"/><text x=\"{3}\" y=\"{4}\" text-anchor=\"end\">1e{5}</text>\n",
                         L, W - R, Y(std::pow(10.0, d)), L - 6, Y(std::pow(10.0, d)) + 4, d);
    s += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">GPU time per frame, as a ratio to a blit of the same display</text>\n",
                     (L + W - R) / 2, H - 12);
    s += fmt::format("<text x=\"16\" y=\"{0}\" transform=\"rotate(-90 16 {0})\" text-anchor=\"middle\">RMSE against the supersampled fp64 reference</text>\n",
                     (T + H - B) / 2);
    const std::vector<size_t> front = pareto_front(timings);
    std::string path;
    for (size_t i : front)
        path += fmt::format("{}{:.1f},{:.1f}", path.empty() ? "M" : " L", X(timings[i].ratio()), Y(timings[i].vs_supersampled->rmse));
    if (!path.empty()) s += "<path d=\"" + path + "\" fill=\"none\" stroke=\"#d33\" stroke-width=\"1.5\"/>\n";
    // A preset's tiers joined, point to filtered: what filtering buys and costs.
    for (const auto& [point, filtered] : tier_pairs(timings))
        s += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#36c\" stroke-dasharray=\"4 3\"/>\n",
                         X(point->ratio()), Y(point->vs_supersampled->rmse), X(filtered->ratio()), Y(filtered->vs_supersampled->rmse));
    // The front's points last, so a point of it is never hidden under another.
    std::vector<size_t> order;
    for (size_t i = 0; i < timings.size(); ++i)
        if (std::find(front.begin(), front.end(), i) == front.end()) order.push_back(i);
    order.insert(order.end(), front.begin(), front.end());
    // Labels that would overlap an earlier one (two tiers at one error, say) move to the nearest
    // free line above or below.
    struct Box { double x0, x1, y0, y1; };
    std::vector<Box> placed;
    for (size_t i : order) {
        const SceneTiming& t = timings[i];
        if (!t.vs_supersampled) continue;
        const bool on_front = std::find(front.begin(), front.end(), i) != front.end();
        const double x = X(t.ratio()), y = Y(t.vs_supersampled->rmse);
        const bool right = x > W - R - 120;  // labels near the right edge go to the point's left
        const double width = 7.2 * static_cast<double>(t.label().size()), tx = right ? x - 6 : x + 6;
        Box box{right ? tx - width : tx, right ? tx : tx + width, y - 15, y - 3};
        auto overlaps = [&](const Box& b) {
            return std::any_of(placed.begin(), placed.end(), [&](const Box& o) { return b.x0 < o.x1 && o.x0 < b.x1 && b.y0 < o.y1 && o.y0 < b.y1; });
        };
        // Nearest free line: 0, up 1, down 1, up 2, ... (13 px each); as it was when none is free.
        const Box home = box;
        for (int k = 1; k <= 12 && overlaps(box); ++k) {
            const double shift = 13.0 * ((k + 1) / 2) * (k % 2 ? -1 : 1);
            box = Box{home.x0, home.x1, home.y0 + shift, home.y1 + shift};
        }
        if (overlaps(box)) box = home;
        placed.push_back(box);
        s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"{}\"/><text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"{}\">{}</text>\n",
                         x, y, on_front ? "#d33" : "#36c", tx, box.y1 - 1, right ? "end" : "start", xml_escape(t.label()));
    }
    s += fmt::format("<text x=\"{}\" y=\"36\" fill=\"#d33\">red: Pareto front (nothing both cheaper and closer); dashed: point tier to filtered tier; error 0 at the bottom</text>\n", L);
    return s + "</svg>\n";
}

}  // namespace crtforge
