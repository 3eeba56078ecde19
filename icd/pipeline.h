// VkPipeline and VkPipelineCache. Graphics pipelines need the render path (rast/ + shader/), which is not wired
// in yet: creation fails with a message instead of pretending.
#pragma once
#include <vector>

#include "object.h"

namespace tilevk::icd {

struct Pipeline : NonDispatchableObject {
    using Handle = VkPipeline;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PIPELINE;
    Pipeline() : NonDispatchableObject(kType) {}
};

struct PipelineCache : NonDispatchableObject {
    using Handle = VkPipelineCache;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PIPELINE_CACHE;
    PipelineCache() : NonDispatchableObject(kType) {}
};

}  // namespace tilevk::icd
