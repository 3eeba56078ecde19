// VkSampler: the create info, kept for the shader path's texture sampling.
#pragma once
#include "object.h"
#include "shader/program.h"

namespace tilevk::icd {

struct Sampler : NonDispatchableObject {
    using Handle = VkSampler;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_SAMPLER;
    Sampler() : NonDispatchableObject(kType) {}
    VkSamplerCreateInfo info{};  // pNext cleared: tilevk knows no sampler extension structs
    shader::SamplerState state;  // as shader/ samples with it, translated once (render_state.h sampler_state_of)
};

}  // namespace tilevk::icd
