// VkShaderModule: the SPIR-V words, copied. shader/ validates and compiles them at pipeline creation.
#pragma once
#include <vector>

#include "object.h"

namespace tilevk::icd {

struct ShaderModule : NonDispatchableObject {
    using Handle = VkShaderModule;
    static constexpr VkObjectType kType = VK_OBJECT_TYPE_SHADER_MODULE;
    ShaderModule() : NonDispatchableObject(kType) {}
    std::vector<uint32_t> words;
};

}  // namespace tilevk::icd
