// Programs already built from the same inputs, so that pipelines sharing shaders (the usual case: many pipelines,
// few modules) skip SPIR-V validation, legalization and translation, which cost far more than everything else in
// pipeline creation. A Program is immutable and thread-safe, so one can serve every pipeline that asks for it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string_view>
#include <vector>

#include "shader/program.h"

namespace tilevk::shader {

class ProgramCache {
  public:
    // capacity: programs kept; the least recently used one goes when a new one does not fit.
    explicit ProgramCache(size_t capacity = 256) : capacity_(capacity) {}

    // Program::create(spirv, stage, entry, spec), or the program an earlier call with identical inputs (every
    // SPIR-V word, the stage, the entry point name and every specialization constant) returned. Failures are not
    // kept: each call that fails builds again and reports its own error. *hit (if given) says which happened; a hit
    // reports create_ms as the lookup's own time. Thread-safe; programs are built outside the lock.
    Result get_or_create(std::span<const uint32_t> spirv, Stage stage, std::string_view entry,
                         const SpecConstants& spec, bool* hit = nullptr);

    size_t size() const;

  private:
    struct Entry {
        uint64_t hash;
        std::vector<uint32_t> key;  // the whole input, compared word for word on a hash match
        std::shared_ptr<const Program> program;
        uint64_t last_use;
    };
    size_t capacity_;
    mutable std::mutex mutex_;
    std::vector<Entry> entries_;
    uint64_t clock_ = 0;
};

}  // namespace tilevk::shader
