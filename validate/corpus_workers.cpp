// run_corpus_in_workers(): batches of the shard's presets, each run by a child process whose rows
// come back through a pipe, a line of JSON each, and land in the row of their preset.
#include "crtforge/validate/corpus_workers.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <deque>
#include <map>

#include <fmt/format.h>

#include "runtime/common/process_util.hpp"

namespace crtforge {

namespace {

constexpr int kRowsFd = 3;                     // the rows' descriptor in the worker
constexpr size_t kMaxRowLine = 4u << 20;       // rows hold short reasons: a longer line is not a row

struct WorkerEnd {
    int status = 0;                      // waitpid's
    std::vector<CorpusRow> rows;         // in the order written
};

// Starts a worker for `presets` and reads its rows until it closes the pipe; `on_row` sees each as it
// arrives (the progress bar), before the worker has ended.
Result<WorkerEnd> run_worker(const CorpusWorkers& workers, const std::vector<std::string>& presets,
                             const std::function<Status(const CorpusRow&)>& on_row) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return make_error(std::string("cannot make a pipe: ") + std::strerror(errno), {}, 0, "corpus");
    detail::SpawnSpec spec;
    spec.executable = workers.executable;
    spec.args = workers.arguments(presets, kRowsFd);
    spec.env = detail::child_environment({});
    spec.output_fd = STDERR_FILENO;  // a worker's messages are the sweep's
    spec.extra_fd = std::make_pair(fds[1], kRowsFd);
    auto pid = detail::spawn(spec);
    ::close(fds[1]);
    if (!pid.ok()) {
        ::close(fds[0]);
        return pid.error();
    }
    WorkerEnd end;
    Status failed = Ok{};
    std::string pending;
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        pending.append(buffer, static_cast<size_t>(n));
        size_t start = 0;
        for (size_t nl; failed.ok() && (nl = pending.find('\n', start)) != std::string::npos; start = nl + 1) {
            auto row = corpus_row_from_line(pending.substr(start, nl - start));
            if (!row.ok()) failed = row.error();
            else if (failed = on_row(row.value()); failed.ok()) end.rows.push_back(std::move(row.value()));
        }
        pending.erase(0, start);
        if (failed.ok() && pending.size() > kMaxRowLine) failed = make_error("a corpus worker wrote a line too long to be a row", {}, 0, "corpus");
        if (!failed.ok()) {
            ::kill(pid.value(), SIGKILL);  // its rows can no longer be trusted
            break;
        }
    }
    ::close(fds[0]);
    while (::waitpid(pid.value(), &end.status, 0) < 0) {
        if (errno != EINTR) return make_error(std::string("cannot wait for a corpus worker: ") + std::strerror(errno), {}, 0, "corpus");
    }
    if (!failed.ok()) return failed.error();
    if (!pending.empty() && WIFEXITED(end.status)) return make_error("a corpus worker's last row is cut short", {}, 0, "corpus");
    return end;
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
    while (!batches.empty()) {
        const std::vector<size_t> batch = std::move(batches.front());
        batches.pop_front();
        std::vector<std::string> names;
        for (size_t i : batch) names.push_back(mine[i]);
        auto on_row = [&](const CorpusRow& row) -> Status {
            auto it = slot.find(row.preset);
            if (it == slot.end() || have[it->second] || std::find(batch.begin(), batch.end(), it->second) == batch.end())
                return make_error("a corpus worker wrote a row for '" + row.preset + "', not one of its presets or one it already wrote", {}, 0, "corpus");
            have[it->second] = true;
            report.rows[it->second] = row;
            ++done;
            if (progress) progress(done, mine.size(), row);
            return Ok{};
        };
        auto end = run_worker(workers, names, on_row);
        if (!end.ok()) return end.error();
        std::vector<size_t> unfinished;
        for (size_t i : batch)
            if (!have[i]) unfinished.push_back(i);
        const int status = end.value().status;
        if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
            return make_error(fmt::format("a corpus worker failed ({}) on {} presets from '{}'", detail::describe_status(status), batch.size(),
                                          mine[batch.front()]),
                              {}, 0, "corpus");
        if (unfinished.empty()) continue;
        if (WIFEXITED(status))
            return make_error("a corpus worker ended without a row for '" + mine[unfinished.front()] + "'", {}, 0, "corpus");
        if (batch.size() == 1) {  // this preset kills its worker: say so in its row
            CorpusRow row = corpus_row_for(request, mine[batch.front()]);
            for (auto& [name, r] : row.targets) {
                r.status = "crashed";
                r.reason = "the worker process running this preset died: " + detail::describe_status(status);
            }
            if (auto s = on_row(row); !s.ok()) return s.error();
            continue;
        }
        // Which of the presets in flight killed it is not known: each unfinished one runs alone.
        for (auto it = unfinished.rbegin(); it != unfinished.rend(); ++it) batches.push_front({*it});
    }
    return report;
}

}  // namespace crtforge
