#include "crtforge/cache.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <xxhash.h>

#include "generator/file_io.hpp"

namespace crtforge {

Cache::Cache(std::string dir) : dir_(std::move(dir)) {}

std::string Cache::default_dir() {
    if (const char* env = std::getenv("CRTFORGE_CACHE"); env && *env) return env;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/crtforge";
    if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/crtforge";
    return {};
}

std::string Cache::key(std::initializer_list<std::string_view> parts) {
    XXH3_state_t* state = XXH3_createState();
    XXH3_128bits_reset(state);
    for (std::string_view part : parts) {
        // Length-prefix each part so ("ab","c") and ("a","bc") differ.
        const uint64_t size = part.size();
        XXH3_128bits_update(state, &size, sizeof size);
        XXH3_128bits_update(state, part.data(), part.size());
    }
    XXH128_hash_t h = XXH3_128bits_digest(state);
    XXH3_freeState(state);
    return fmt::format("{:016x}{:016x}", h.high64, h.low64);
}

std::optional<std::string> Cache::get(const std::string& kind, const std::string& key) const {
    if (!enabled()) return std::nullopt;
    std::ifstream in(dir_ + "/" + kind + "/" + key, std::ios::binary);
    if (!in) {
        ++misses_;
        return std::nullopt;
    }
    std::ostringstream data;
    data << in.rdbuf();
    std::string blob = data.str();
    // Entries end with their own key: a truncated or foreign file is a miss, not a wrong answer.
    if (blob.size() < key.size() || blob.compare(blob.size() - key.size(), key.size(), key) != 0) {
        ++misses_;
        return std::nullopt;
    }
    blob.resize(blob.size() - key.size());
    ++hits_;
    return blob;
}

void Cache::put(const std::string& kind, const std::string& key, std::string_view data) const {
    if (!enabled()) return;
    std::string blob(data);
    blob += key;
    // A cache that cannot be written is only slower; never an error for the user.
    (void)detail::write_file_atomic(dir_ + "/" + kind + "/" + key, blob);
}

}  // namespace crtforge
