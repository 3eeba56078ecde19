// ProgramCache: a small least-recently-used table of built programs keyed by their exact inputs.
#include "shader/program_cache.h"

#include <algorithm>
#include <chrono>
#include <cstring>

namespace tilevk::shader {

namespace {

// The inputs as one word sequence: stage, entry point length and bytes, specialization constants (count, then id,
// word count and words of each), then the SPIR-V. Two calls get the same program exactly when these are equal.
std::vector<uint32_t> make_key(std::span<const uint32_t> spirv, Stage stage, std::string_view entry,
                               const SpecConstants& spec) {
    std::vector<uint32_t> key;
    key.reserve(spirv.size() + 8 + entry.size() / 4 + spec.size() * 4);
    key.push_back(static_cast<uint32_t>(stage));
    key.push_back(static_cast<uint32_t>(entry.size()));
    for (size_t i = 0; i < entry.size(); i += 4) {
        uint32_t w = 0;
        std::memcpy(&w, entry.data() + i, std::min<size_t>(4, entry.size() - i));
        key.push_back(w);
    }
    key.push_back(static_cast<uint32_t>(spec.size()));
    for (const SpecConstant& c : spec) {
        key.push_back(c.id);
        key.push_back(static_cast<uint32_t>(c.words.size()));
        key.insert(key.end(), c.words.begin(), c.words.end());
    }
    key.insert(key.end(), spirv.begin(), spirv.end());
    return key;
}

uint64_t hash_words(const std::vector<uint32_t>& words) {
    uint64_t h = 0xCBF29CE484222325ull;  // FNV-1a over 32-bit words, then a final mix
    for (uint32_t w : words) h = (h ^ w) * 0x100000001B3ull;
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDull;
    return h ^ (h >> 33);
}

}  // namespace

Result ProgramCache::get_or_create(std::span<const uint32_t> spirv, Stage stage, std::string_view entry,
                                   const SpecConstants& spec, bool* hit) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<uint32_t> key = make_key(spirv, stage, entry, spec);
    const uint64_t hash = hash_words(key);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (Entry& e : entries_)
            if (e.hash == hash && e.key == key) {
                e.last_use = ++clock_;
                if (hit) *hit = true;
                Result r;
                r.program = e.program;
                r.create_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                return r;
            }
    }
    if (hit) *hit = false;
    Result r = Program::create(spirv, stage, entry, spec);
    if (!r || capacity_ == 0) return r;
    std::lock_guard<std::mutex> lock(mutex_);
    for (const Entry& e : entries_)
        if (e.hash == hash && e.key == key) return r;  // built meanwhile by another thread: keep the first
    if (entries_.size() >= capacity_) {
        auto oldest = std::min_element(entries_.begin(), entries_.end(),
                                       [](const Entry& a, const Entry& b) { return a.last_use < b.last_use; });
        entries_.erase(oldest);
    }
    entries_.push_back({hash, std::move(key), r.program, ++clock_});
    return r;
}

size_t ProgramCache::size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return entries_.size();
}

}  // namespace tilevk::shader
