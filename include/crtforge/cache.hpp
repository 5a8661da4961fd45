// A content-addressed cache: blobs stored under a hash of everything that determines them, so an
// unchanged variant is neither recompiled nor re-emitted. Writes are atomic (temp + rename). Every
// entry carries its key and a checksum of its payload, verified on read: an unreadable, truncated
// or edited entry is a miss (counted in rejected()), and the caller's put() heals it.
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <string_view>

namespace crtforge {

class Cache {
public:
    // An empty dir disables the cache.
    explicit Cache(std::string dir = {});
    Cache(const Cache& other) : dir_(other.dir_) {}
    static std::string default_dir();  // $CRTFORGE_CACHE, else $XDG_CACHE_HOME/crtforge, else ~/.cache/crtforge

    bool enabled() const { return !dir_.empty(); }
    const std::string& dir() const { return dir_; }

    // A stable 128-bit hex key of the given parts (order matters).
    static std::string key(std::initializer_list<std::string_view> parts);

    // A hash of the running executable, folded into every key: a rebuilt crtforge (changed
    // templates handling, emitters, compiler libraries) never reuses another build's entries.
    static const std::string& build_id();

    std::optional<std::string> get(const std::string& kind, const std::string& key) const;
    void put(const std::string& kind, const std::string& key, std::string_view data) const;

    unsigned hits() const { return hits_; }
    unsigned misses() const { return misses_; }
    unsigned rejected() const { return rejected_; }  // entries found but damaged (also misses)

private:
    std::string dir_;
    // Safe to share between the export's worker threads.
    mutable std::atomic<unsigned> hits_{0}, misses_{0}, rejected_{0};
};

}  // namespace crtforge
