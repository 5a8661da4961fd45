// run_corpus_in_workers(): batches of the shard's presets, each run by a child process whose rows
// come back through a pipe, a line of JSON each, and land in the row of their preset.
#include "crtforge/validate/corpus_workers.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <deque>
#include <map>

#include <fmt/format.h>

#include "crtforge/files.hpp"
#include "crtforge/runtime/gpu_watchdog.hpp"
#include "runtime/common/process_util.hpp"

namespace crtforge {

namespace {

constexpr int kRowsFd = 3;                     // the rows' descriptor in the worker
constexpr size_t kMaxRowLine = 4u << 20;       // rows hold short reasons: a longer line is not a row

// A worker running: its batch (indexes into the shard's presets), the rows it has written, and the
// part of a line not ended yet.
struct Worker {
    pid_t pid = -1;
    int fd = -1;
    std::vector<size_t> batch;
    size_t rows = 0;
    std::string pending;
    std::chrono::steady_clock::time_point since;  // its start or its last row
    bool timed_out = false;                       // stopped for writing no row in time
};

// The workers still running; on an early return every one is killed and reaped, so a failed sweep
// leaves no process behind.
struct Workers {
    std::vector<Worker> running;
    ~Workers() {
        for (Worker& w : running) {
            ::kill(w.pid, SIGKILL);
            ::close(w.fd);
            int status = 0;
            while (::waitpid(w.pid, &status, 0) < 0 && errno == EINTR) {
            }
        }
    }
};

Result<Worker> start_worker(const CorpusWorkers& workers, const std::vector<std::string>& presets, std::vector<size_t> batch,
                            const std::string& scratch) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return make_error(std::string("cannot make a pipe: ") + std::strerror(errno), {}, 0, "corpus");
    detail::SpawnSpec spec;
    spec.executable = workers.executable;
    spec.args = workers.arguments(presets, kRowsFd);
    spec.env = detail::child_environment({{"TMPDIR", scratch}});
    spec.output_fd = STDERR_FILENO;  // a worker's messages are the sweep's
    spec.extra_fd = std::make_pair(fds[1], kRowsFd);
    auto pid = detail::spawn(spec);
    ::close(fds[1]);
    if (!pid.ok()) {
        ::close(fds[0]);
        return pid.error();
    }
    Worker w;
    w.pid = pid.value();
    w.fd = fds[0];
    w.batch = std::move(batch);
    w.since = std::chrono::steady_clock::now();
    return w;
}

// The rows in what `w` wrote since: each complete line handed to `on_row`.
Status take_rows(Worker& w, const char* data, size_t size, const std::function<Status(const Worker&, const CorpusRow&)>& on_row) {
    w.pending.append(data, size);
    size_t start = 0;
    for (size_t nl; (nl = w.pending.find('\n', start)) != std::string::npos; start = nl + 1) {
        auto row = corpus_row_from_line(w.pending.substr(start, nl - start));
        if (!row.ok()) return row.error();
        if (auto s = on_row(w, row.value()); !s.ok()) return s;
        ++w.rows;
        w.since = std::chrono::steady_clock::now();
    }
    w.pending.erase(0, start);
    if (w.pending.size() > kMaxRowLine) return make_error("a corpus worker wrote a line too long to be a row", {}, 0, "corpus");
    return Ok{};
}

}  // namespace

Result<CorpusReport> run_corpus_in_workers(const CorpusRequest& request, const CorpusWorkers& workers, const CorpusProgress& progress) {
    auto shard = corpus_shard_presets(request);
    if (!shard.ok()) return shard.error();
    const std::vector<std::string>& mine = shard.value();
    CorpusReport report = empty_corpus_report(request);
    report.rows.resize(mine.size());
    std::map<std::string, size_t> slot;
    for (size_t i = 0; i < mine.size(); ++i) slot.emplace(mine[i], i);
    std::vector<bool> have(mine.size(), false);

    const size_t per = std::max<size_t>(1, workers.presets_per_process);
    std::deque<std::vector<size_t>> batches;
    for (size_t i = 0; i < mine.size(); i += per) {
        std::vector<size_t> batch;
        for (size_t k = i; k < std::min(mine.size(), i + per); ++k) batch.push_back(k);
        batches.push_back(std::move(batch));
    }
    size_t done = 0;
    auto on_row = [&](const Worker& w, const CorpusRow& row) -> Status {
        auto it = slot.find(row.preset);
        if (it == slot.end() || have[it->second] || std::find(w.batch.begin(), w.batch.end(), it->second) == w.batch.end())
            return make_error("a corpus worker wrote a row for '" + row.preset + "', not one of its presets or one it already wrote", {}, 0,
                              "corpus");
        have[it->second] = true;
        report.rows[it->second] = row;
        ++done;
        if (progress) progress(done, mine.size(), row);
        return Ok{};
    };
    // What a worker's end means for its batch: nothing left, an error, or presets to run again.
    auto ended = [&](const Worker& w, int status) -> Status {
        std::vector<size_t> unfinished;
        for (size_t i : w.batch)
            if (!have[i]) unfinished.push_back(i);
        // A draw past --gpu-timeout ends its worker with its own code, as a crash would: the preset
        // it was on gets a row saying so, and the sweep goes on.
        const bool gpu_stopped = WIFEXITED(status) && WEXITSTATUS(status) == kExitGpuTimeout;
        if (WIFEXITED(status) && WEXITSTATUS(status) != 0 && !gpu_stopped)
            return make_error(fmt::format("a corpus worker failed ({}) on {} presets from '{}'", detail::describe_status(status), w.batch.size(),
                                          mine[w.batch.front()]),
                              {}, 0, "corpus");
        if (unfinished.empty()) return Ok{};
        if (WIFEXITED(status) && !gpu_stopped) return make_error("a corpus worker ended without a row for '" + mine[unfinished.front()] + "'", {}, 0, "corpus");
        if (w.batch.size() == 1) {  // this preset kills its worker, or runs past the limit: say so in its row
            CorpusRow row = corpus_row_for(request, mine[w.batch.front()]);
            for (auto& [name, r] : row.targets) {
                r.status = w.timed_out || gpu_stopped ? "timeout" : "crashed";
                r.reason = w.timed_out     ? fmt::format("no result within {:g} s (--preset-timeout): stopped", workers.preset_timeout_s)
                           : gpu_stopped ? fmt::format("a draw ran past {:g} s on the GPU (--gpu-timeout): stopped", gpu_timeout())
                                         : "the worker process running this preset died: " + detail::describe_status(status);
            }
            return on_row(w, row);
        }
        // Which of the presets in flight killed it is not known: each unfinished one runs alone.
        for (auto it = unfinished.rbegin(); it != unfinished.rend(); ++it) batches.push_front({*it});
        return Ok{};
    };

    // The workers' temporary folders go in one of the sweep's, removed at its end: a worker killed by
    // a signal cannot remove its own. (Declared before `live`: the workers end first.)
    auto scratch = TemporaryFolder::create("crtforge-sweep");
    if (!scratch.ok()) return scratch.error();
    Workers live;
    const size_t threads = std::max(1u, request.jobs);
    char buffer[1 << 16];
    while (!batches.empty() || !live.running.empty()) {
        // The next batch starts once the newest worker has fewer presets left than threads: its last
        // presets and the next worker's start-up overlap instead of leaving cores idle.
        const Worker* newest = live.running.empty() ? nullptr : &live.running.back();
        if (!batches.empty() && live.running.size() < 2 && (!newest || newest->batch.size() - newest->rows < threads)) {
            std::vector<std::string> names;
            for (size_t i : batches.front()) names.push_back(mine[i]);
            auto w = start_worker(workers, names, std::move(batches.front()), scratch.value().path().string());
            batches.pop_front();
            if (!w.ok()) return w.error();
            live.running.push_back(std::move(w.value()));
            continue;
        }
        // A worker past its time is stopped; its pipe then closes and it ends as one killed.
        int wait_ms = -1;
        if (workers.preset_timeout_s > 0) {
            const auto now = std::chrono::steady_clock::now();
            const auto limit = std::chrono::duration<double>(workers.preset_timeout_s);
            for (Worker& w : live.running) {
                const double left = std::chrono::duration<double>(w.since + limit - now).count();
                if (left <= 0 && !w.timed_out) {
                    ::kill(w.pid, SIGKILL);
                    w.timed_out = true;
                }
                const int ms = left <= 0 ? 1000 : static_cast<int>(std::min(left * 1000.0 + 1.0, 3600e3));
                wait_ms = wait_ms < 0 ? ms : std::min(wait_ms, ms);
            }
        }
        std::vector<pollfd> fds;
        for (const Worker& w : live.running) fds.push_back({w.fd, POLLIN, 0});
        if (::poll(fds.data(), fds.size(), wait_ms) < 0) {
            if (errno == EINTR) continue;
            return make_error(std::string("cannot wait for the corpus workers: ") + std::strerror(errno), {}, 0, "corpus");
        }
        for (size_t k = fds.size(); k-- > 0;) {
            if (!fds[k].revents) continue;
            Worker& w = live.running[k];
            const ssize_t n = ::read(w.fd, buffer, sizeof buffer);
            if (n < 0 && errno == EINTR) continue;
            if (n > 0) {
                if (auto s = take_rows(w, buffer, static_cast<size_t>(n), on_row); !s.ok()) return s.error();
                continue;
            }
            // The pipe closed: the worker has ended (or closed it and will).
            int status = 0;
            while (::waitpid(w.pid, &status, 0) < 0) {
                if (errno != EINTR) return make_error(std::string("cannot wait for a corpus worker: ") + std::strerror(errno), {}, 0, "corpus");
            }
            ::close(w.fd);
            const Worker gone = std::move(w);
            live.running.erase(live.running.begin() + static_cast<std::ptrdiff_t>(k));
            if (!gone.pending.empty() && WIFEXITED(status)) return make_error("a corpus worker's last row is cut short", {}, 0, "corpus");
            if (auto s = ended(gone, status); !s.ok()) return s.error();
        }
    }
    return report;
}

}  // namespace crtforge
