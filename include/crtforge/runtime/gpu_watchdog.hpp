// A bound on how long crtforge waits for the GPU. Lavapipe stops every shader invocation after
// 65535 loop iterations, but SwiftShader (validate's second driver, --device swiftshader) and a
// real GPU run a loop as written: an imported shader whose loop never ends (or runs for hours)
// would hang the run with no output. A wait on the device says every so often that it is still
// waiting, and at the limit the run stops with one line naming the draw. The device cannot be
// torn down while it draws, so that stop skips destructors (exit_after_cleanup: staging folders
// and temporary files go, nothing half-written stays).
#pragma once

#include <chrono>
#include <string>

namespace crtforge {

inline constexpr double kDefaultGpuTimeoutSeconds = 300;
// The exit code of a run stopped at the limit (a corpus worker so stopped is not a failed sweep:
// the preset it was on gets a "timeout" row).
inline constexpr int kExitGpuTimeout = 3;
// Seconds one submission of GPU work may take; 0 waits for ever. Process-wide (--gpu-timeout).
void set_gpu_timeout(double seconds);
double gpu_timeout();

// While it lives, names the work the calling thread has the GPU doing ("crt-royale.slangp: pass 3
// 'blur', frame 0"), for the lines the wait prints. Nested labels restore the outer one.
class GpuWorkLabel {
public:
    explicit GpuWorkLabel(std::string what);
    ~GpuWorkLabel();
    GpuWorkLabel(const GpuWorkLabel&) = delete;
    GpuWorkLabel& operator=(const GpuWorkLabel&) = delete;

private:
    std::string previous_;
};

// One wait on the device: call still_waiting() each time a bounded wait (a fence, a query) times
// out. It prints a progress line after 10 s and then every 30 s, and at the limit stops the
// process (kExitGpuTimeout) with an error line naming the labelled work.
class GpuWait {
public:
    GpuWait();
    void still_waiting();

private:
    std::chrono::steady_clock::time_point start_;
    double next_progress_ = 10;
};

// How long one bounded wait inside a GpuWait should last, in nanoseconds.
inline constexpr unsigned long long kGpuWaitSliceNs = 1'000'000'000ull;

}  // namespace crtforge
