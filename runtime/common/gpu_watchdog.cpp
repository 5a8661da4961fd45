#include "crtforge/runtime/gpu_watchdog.hpp"

#include <atomic>
#include <cstdio>

#include <fmt/format.h>

#include "crtforge/exit_cleanup.hpp"

namespace crtforge {

namespace {

std::atomic<double> g_timeout{kDefaultGpuTimeoutSeconds};
thread_local std::string t_work;

}  // namespace

void set_gpu_timeout(double seconds) { g_timeout = seconds; }
double gpu_timeout() { return g_timeout; }

GpuWorkLabel::GpuWorkLabel(std::string what) : previous_(std::move(t_work)) { t_work = std::move(what); }
GpuWorkLabel::~GpuWorkLabel() { t_work = std::move(previous_); }

GpuWait::GpuWait() : start_(std::chrono::steady_clock::now()) {}

void GpuWait::still_waiting() {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double limit = gpu_timeout();
    const std::string what = t_work.empty() ? "a GPU draw" : t_work;
    if (limit > 0 && elapsed >= limit)
        exit_after_cleanup(fmt::format("crtforge: error: {}: the GPU has not finished it in {:g} s (--gpu-timeout): a shader loop "
                                       "that runs too long or never ends? (a slower device may need a larger --gpu-timeout)",
                                       what, limit),
                           kExitGpuTimeout);
    if (elapsed < next_progress_) return;
    next_progress_ += 30;
    std::fprintf(stderr, "crtforge: %s: still drawing on the GPU, %.0f s so far%s\n", what.c_str(), elapsed,
                 limit > 0 ? fmt::format(" (stopped at {:g} s: --gpu-timeout)", limit).c_str() : "");
    std::fflush(stderr);
}

}  // namespace crtforge
