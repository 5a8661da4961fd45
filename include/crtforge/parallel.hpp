// Work items 0..count-1 spread over `threads` threads (the calling one among them), each taking the
// next free item: items are independent and write only their own slot of a result, so the result
// does not depend on which thread ran what.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace crtforge {

template <typename Work>
void parallel_for(size_t count, unsigned threads, Work&& work) {
    std::atomic<size_t> next{0};
    auto worker = [&] {
        for (size_t i = next++; i < count; i = next++) work(i);
    };
    const unsigned n = static_cast<unsigned>(std::max<size_t>(1, std::min<size_t>(threads, count)));
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < n; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
}

// The machine's threads (1 where it cannot tell).
inline unsigned hardware_threads() { return std::max(1u, std::thread::hardware_concurrency()); }

}  // namespace crtforge
