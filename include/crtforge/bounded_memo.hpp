// A process-wide memo of values by key, shared by worker threads and bounded by a size the caller
// measures (bytes of a SPIR-V module, pixels of a picture): once the sizes pass the bound the
// oldest entries go first, so a run over thousands of presets (crtforge corpus) keeps a steady
// footprint however many distinct values it meets. A worker about to compute a value claims its
// key first: two workers meeting the same key at once (neighbouring presets of one family) then
// compute it once, the second waiting for the first.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>

namespace crtforge {

template <typename Value>
class BoundedMemo {
public:
    BoundedMemo(size_t bound, std::function<size_t(const Value&)> size_of) : bound_(bound), size_of_(std::move(size_of)) {}

    std::optional<Value> find(const std::string& key) const {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = values_.find(key);
        if (it == values_.end()) return std::nullopt;
        return it->second;
    }

    void put(const std::string& key, const Value& value) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!values_.emplace(key, value).second) return;
        order_.push_back(key);
        total_ += size_of_(value);
        while (total_ > bound_ && order_.size() > 1) {
            auto oldest = values_.find(order_.front());
            total_ -= size_of_(oldest->second);
            values_.erase(oldest);
            order_.pop_front();
        }
    }

    // While a Claim on a key lives, another claim of that key waits; look in the memo again once
    // it is granted (the holder put the value there, unless it failed: then compute it yourself).
    class [[nodiscard]] Claim {
    public:
        Claim(const BoundedMemo& memo, std::string key) : memo_(&memo), key_(std::move(key)) {
            std::unique_lock<std::mutex> lock(memo_->mutex_);
            memo_->released_.wait(lock, [&] { return !memo_->claimed_.count(key_); });
            memo_->claimed_.insert(key_);
        }
        Claim(const Claim&) = delete;
        Claim& operator=(const Claim&) = delete;
        ~Claim() {
            {
                std::lock_guard<std::mutex> lock(memo_->mutex_);
                memo_->claimed_.erase(key_);
            }
            memo_->released_.notify_all();
        }

    private:
        const BoundedMemo* memo_;
        std::string key_;
    };

    Claim claim(const std::string& key) const { return Claim(*this, key); }

private:
    const size_t bound_;
    const std::function<size_t(const Value&)> size_of_;
    mutable std::mutex mutex_;
    std::map<std::string, Value> values_;
    std::deque<std::string> order_;  // keys, oldest first
    size_t total_ = 0;
    mutable std::set<std::string> claimed_;
    mutable std::condition_variable released_;
};

}  // namespace crtforge
