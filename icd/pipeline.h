// VkPipeline and VkPipelineCache. A graphics pipeline is its shader programs (shader/) and its fixed-function
// state translated once into rast::render::PipelineState; dynamic state is applied per draw (execute_draw.cpp).
// A compute pipeline is its compute program alone (execute_compute.cpp runs it).
#pragma once
#include <memory>
#include <vector>

#include "dynamic_state.h"
#include "object.h"
#include "rast/render/draw_state.h"

namespace tilevk::icd {

struct Pipeline : NonDispatchableObject {
    using Handle = VkPipeline;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PIPELINE;
    Pipeline() : NonDispatchableObject(kType) {}
    std::shared_ptr<const shader::Program> vertex, fragment;
    std::shared_ptr<const shader::Program> compute;    // compute pipelines: the only program
    rast::render::PipelineState state;                 // program pointers point at the two above
    DynamicMask dynamic = 0;                           // dynamic_bit(DynamicState::k*): from vkCmdSet*
    StaticValues statics;                              // static values that combine with dynamic ones
    double create_ms = 0;                              // wall time of vkCreateGraphicsPipelines for this pipeline
    uint32_t programs_built = 0, programs_cached = 0;  // shader programs built here / found in the device's cache
};

struct PipelineCache : NonDispatchableObject {
    using Handle = VkPipelineCache;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_PIPELINE_CACHE;
    PipelineCache() : NonDispatchableObject(kType) {}
};

}  // namespace tilevk::icd
