// The corpus sweep in worker processes: the shard's presets in batches of neighbours (presets that
// share passes stay together), each batch run by a child process of this program that hands its
// rows back as lines of JSON. A fresh process per batch gives back all the memory the Vulkan driver
// keeps for the life of a process (lavapipe's JIT holds ~90 MB per Mega Bezel preset, so the whole
// library in one process outgrows 24 GB), and a preset that kills its worker (a driver crash, the
// OOM killer) gets a "crashed" row instead of ending the sweep.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "crtforge/validate/corpus.hpp"

namespace crtforge {

struct CorpusWorkers {
    std::string executable;  // the worker program, an absolute path
    // The worker's arguments (argv[1..]) for these presets (relative to the request's root); the
    // worker writes one corpus_row_line() per preset, each ended by '\n', to descriptor `rows_fd`.
    std::function<std::vector<std::string>(const std::vector<std::string>& presets, int rows_fd)> arguments;
    size_t presets_per_process = 50;
    // A worker that writes no row for this long is stopped (0: never): its preset in flight gets a
    // "timeout" row (alone in a worker; in a batch, the unfinished presets run again one by one).
    double preset_timeout_s = 0;
};

// The same report as run_corpus() (rows in the same order, the same bytes), run by workers. A
// worker that exits with a code, or writes a row that is malformed or not one of its presets, ends
// the run with an error; one killed by a signal has its unfinished presets run again, each in a
// worker of its own, and the one that kills that worker gets a "crashed" row naming the signal.
Result<CorpusReport> run_corpus_in_workers(const CorpusRequest& request, const CorpusWorkers& workers,
                                           const CorpusProgress& progress = {});

}  // namespace crtforge
