// A line on stderr every so often while one long piece of work runs without progress of its own
// (a reference render of many samples, a golden update of a long sequence): a command that takes
// minutes is never silent, so a user (or CI) can tell it from a hang.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace crtforge::cli {

class Heartbeat {
public:
    explicit Heartbeat(std::string what, std::chrono::seconds period = std::chrono::seconds(15))
        : what_(std::move(what)), period_(period), thread_([this] { run(); }) {}
    ~Heartbeat() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        thread_.join();
    }
    Heartbeat(const Heartbeat&) = delete;
    Heartbeat& operator=(const Heartbeat&) = delete;

private:
    void run() {
        const auto start = std::chrono::steady_clock::now();
        std::unique_lock<std::mutex> lock(mutex_);
        while (!wake_.wait_for(lock, period_, [this] { return stop_; })) {
            const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now() - start).count();
            std::fprintf(stderr, "crtforge: %s: still working, %lld s so far\n", what_.c_str(), static_cast<long long>(seconds));
            std::fflush(stderr);
        }
    }

    std::string what_;
    std::chrono::seconds period_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false;
    std::thread thread_;  // last: started once the members it reads exist
};

}  // namespace crtforge::cli
