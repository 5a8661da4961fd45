#include "crtforge/cache.hpp"
#include "crtforge/version.hpp"

#include <link.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <xxhash.h>

#include "crtforge/files.hpp"

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

namespace {

// The GNU build-id note the linker puts in the executable: unique per build, read from memory.
int find_build_id(struct dl_phdr_info* info, size_t, void* out) {
    if (info->dlpi_name && info->dlpi_name[0]) return 0;  // the main program comes first, unnamed
    for (int i = 0; i < info->dlpi_phnum; ++i) {
        const ElfW(Phdr)& ph = info->dlpi_phdr[i];
        if (ph.p_type != PT_NOTE) continue;
        const char* p = reinterpret_cast<const char*>(info->dlpi_addr + ph.p_vaddr);
        const char* end = p + ph.p_memsz;
        while (p + sizeof(ElfW(Nhdr)) <= end) {
            const auto* note = reinterpret_cast<const ElfW(Nhdr)*>(p);
            const char* name = p + sizeof(ElfW(Nhdr));
            const char* desc = name + ((note->n_namesz + 3) & ~3u);
            if (note->n_type == NT_GNU_BUILD_ID && note->n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0) {
                auto* id = static_cast<std::string*>(out);
                for (unsigned k = 0; k < note->n_descsz; ++k) *id += fmt::format("{:02x}", static_cast<unsigned char>(desc[k]));
                return 1;
            }
            p = desc + ((note->n_descsz + 3) & ~3u);
        }
    }
    return 1;
}

}  // namespace

const std::string& Cache::build_id() {
    static const std::string id = [] {
        std::string found;
        dl_iterate_phdr(find_build_id, &found);
        if (!found.empty()) return found;
        // No build-id note (unusual linker settings): hash the executable instead.
        std::ifstream in("/proc/self/exe", std::ios::binary);
        if (!in) return std::string(CRTFORGE_VERSION);
        XXH3_state_t* state = XXH3_createState();
        XXH3_128bits_reset(state);
        std::vector<char> chunk(1 << 20);
        while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0)
            XXH3_128bits_update(state, chunk.data(), static_cast<size_t>(in.gcount()));
        const XXH128_hash_t h = XXH3_128bits_digest(state);
        XXH3_freeState(state);
        return fmt::format("{:016x}{:016x}", h.high64, h.low64);
    }();
    return id;
}

namespace {

// An entry: a header naming the format, the key and a checksum of the payload, then the payload.
// Any mismatch (truncation, a flipped bit, a same-length edit, another key's file) is a miss; the
// recompiled result then overwrites the entry, so a damaged cache heals itself.
constexpr std::string_view kEntryMagic = "crtforge-cache 2\n";

std::string checksum(std::string_view data) {
    const XXH128_hash_t h = XXH3_128bits(data.data(), data.size());
    return fmt::format("{:016x}{:016x}", h.high64, h.low64);
}

std::string entry_header(const std::string& key, std::string_view payload) {
    return std::string(kEntryMagic) + key + "\n" + checksum(payload) + "\n";
}

}  // namespace

std::optional<std::string> Cache::get(const std::string& kind, const std::string& key) const {
    if (!enabled()) return std::nullopt;
    const std::string path = dir_ + "/" + kind + "/" + key;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        ++misses_;
        return std::nullopt;
    }
    // Only a regular file of bounded size is read: a FIFO, a device or a huge file planted as an
    // entry is a rejected entry (then replaced by put), never a hang or an exhausted memory.
    auto read = read_text_file(path, kMaxDataFileBytes);
    if (!read.ok()) {
        ++rejected_;
        ++misses_;
        return std::nullopt;
    }
    const std::string& blob = read.value();
    const size_t header_size = kEntryMagic.size() + key.size() + 1 + 32 + 1;
    if (blob.size() < header_size || blob.compare(0, kEntryMagic.size(), kEntryMagic) != 0) {
        ++rejected_;
        ++misses_;
        return std::nullopt;
    }
    std::string payload = blob.substr(header_size);
    if (blob.compare(0, header_size, entry_header(key, payload)) != 0) {
        ++rejected_;
        ++misses_;
        return std::nullopt;
    }
    ++hits_;
    return payload;
}

void Cache::put(const std::string& kind, const std::string& key, std::string_view data) const {
    if (!enabled()) return;
    std::string blob = entry_header(key, data);
    blob += data;
    // A cache that cannot be written is only slower; never an error for the user.
    (void)write_file_atomic(dir_ + "/" + kind + "/" + key, blob);
}

}  // namespace crtforge
