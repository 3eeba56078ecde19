// VkPipeline and VkPipelineCache. A graphics pipeline is its shader programs (shader/) and its fixed-function
// state translated once into rast::render::PipelineState; dynamic state is applied per draw (execute_draw.cpp).
#pragma once
#include <memory>
#include <vector>

#include "object.h"
#include "rast/render/draw_state.h"

namespace tilevk::icd {

// Bits of Pipeline::dynamic: which VkDynamicState values come from vkCmdSet* instead of the pipeline.
inline constexpr uint32_t dynamic_bit(VkDynamicState s) {
    return 1u << uint32_t(s);
}

struct Pipeline : NonDispatchableObject {
    using Handle = VkPipeline;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PIPELINE;
    Pipeline() : NonDispatchableObject(kType) {}
    std::shared_ptr<const shader::Program> vertex, fragment;
    rast::render::PipelineState state;                 // program pointers point at the two above
    uint32_t dynamic = 0;                              // dynamic_bit(VK_DYNAMIC_STATE_*)
    bool rasterizer_discard = false;                   // draws produce nothing
    double create_ms = 0;                              // wall time of vkCreateGraphicsPipelines for this pipeline
    uint32_t programs_built = 0, programs_cached = 0;  // shader programs built here / found in the device's cache
};

struct PipelineCache : NonDispatchableObject {
    using Handle = VkPipelineCache;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PIPELINE_CACHE;
    PipelineCache() : NonDispatchableObject(kType) {}
};

}  // namespace tilevk::icd
