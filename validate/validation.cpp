// Enumerates preset x target x check in a fixed order, keeps this shard's share, runs the checks.
#include "crtforge/validation.hpp"

#include <algorithm>
#include <cstdio>

#include "crtforge/exporter.hpp"

namespace crtforge {

size_t ValidationReport::failed() const {
    return static_cast<size_t>(std::count_if(checks.begin(), checks.end(), [](const CheckResult& c) { return !c.passed; }));
}

Result<Shard> Shard::parse(const std::string& text) {
    Shard s;
    unsigned i = 0, n = 0;
    char slash = 0;
    int consumed = 0;
    if (std::sscanf(text.c_str(), "%u%c%u%n", &i, &slash, &n, &consumed) != 3 || slash != '/' ||
        consumed != static_cast<int>(text.size()) || n == 0 || i == 0 || i > n)
        return make_error("'" + text + "' is not a shard: expected i/n with 1 <= i <= n, e.g. 2/4", {}, 0, "--shard");
    s.index = i;
    s.count = n;
    return s;
}

Result<ValidationReport> run_validation(const TemplateLibrary& library, const ValidateRequest& request,
                                        const Cache& cache, const ProgressFn& progress) {
    std::vector<const Preset*> presets;
    for (const auto& p : library.presets())
        if (request.presets.empty() || std::find(request.presets.begin(), request.presets.end(), p.name) != request.presets.end())
            presets.push_back(&p);
    for (const auto& name : request.presets)
        if (!library.find_preset(name)) return make_error("unknown preset '" + name + "'", {}, 0, "--preset");
    std::vector<TargetId> targets = request.targets;
    if (targets.empty())
        for (const auto& t : all_targets()) targets.push_back(t.id);

    // A shard takes every count-th (preset, target) pair, so work spreads evenly and the shards'
    // reports concatenate back into the full, ordered report.
    struct Job { const Preset* preset; TargetId target; };
    std::vector<Job> jobs;
    size_t index = 0;
    for (const Preset* p : presets)
        for (TargetId t : targets)
            if (index++ % request.shard.count == request.shard.index - 1) jobs.push_back({p, t});

    ValidationReport report;
    const size_t total = jobs.size() * 2;
    const Preset* compiled_for = nullptr;
    std::optional<CompiledVariant> compiled;
    for (const Job& job : jobs) {
        if (compiled_for != job.preset) {
            auto c = compile_variant(library, *job.preset, request.options, cache);
            if (!c.ok()) {
                // The generator itself failed: every check of this preset fails with that reason.
                for (ShaderStage stage : {ShaderStage::Vertex, ShaderStage::Fragment}) {
                    report.checks.push_back({job.preset->name, target_info(job.target).name,
                                             std::string("compile:") + shader_stage_name(stage), false, c.error().str()});
                    if (progress) progress(report.checks.size(), total, report.checks.back());
                }
                continue;
            }
            compiled = std::move(c.value());
            compiled_for = job.preset;
        }
        auto out = emit_target(*compiled, job.target, cache);
        for (ShaderStage stage : {ShaderStage::Vertex, ShaderStage::Fragment}) {
            CheckResult r{job.preset->name, target_info(job.target).name,
                          std::string("compile:") + shader_stage_name(stage), false, {}};
            if (!out.ok()) {
                r.message = out.error().str();
            } else {
                for (const OutputFile& f : out.value().files) {
                    if (f.stage != stage) continue;
                    auto consumed = consume_output(job.target, f);
                    r.passed = consumed.ok();
                    if (!consumed.ok()) r.message = consumed.error().str();
                }
            }
            report.checks.push_back(std::move(r));
            if (progress) progress(report.checks.size(), total, report.checks.back());
        }
    }
    return report;
}

}  // namespace crtforge
