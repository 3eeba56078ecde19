#include "vk_context.hpp"

#include <cstring>
#include <type_traits>

#include "glsl.hpp"
#include "validation.hpp"
#include "vk_names.hpp"

namespace tilevk::cts {

void vk_check(VkResult r, const char* what) {
    if (r != VK_SUCCESS)
        throw VkError(std::string(what) + " returned " + result_name(r) + " (" + std::to_string(r) + ")");
}

namespace {

// Device extensions cases may use, enabled on every device that offers them (requirements.cpp asks for them).
const char* const kSubsetExtensions[] = {VK_KHR_MAINTENANCE_1_EXTENSION_NAME,
                                         VK_EXT_INDEX_TYPE_UINT8_EXTENSION_NAME,
                                         VK_EXT_PRIMITIVE_TOPOLOGY_LIST_RESTART_EXTENSION_NAME,
                                         VK_EXT_DEPTH_CLIP_CONTROL_EXTENSION_NAME,
                                         VK_EXT_EXTENDED_DYNAMIC_STATE_EXTENSION_NAME,
                                         VK_EXT_EXTENDED_DYNAMIC_STATE_2_EXTENSION_NAME,
                                         VK_KHR_DEVICE_GROUP_EXTENSION_NAME,
                                         VK_KHR_SAMPLER_MIRROR_CLAMP_TO_EDGE_EXTENSION_NAME,
                                         VK_KHR_STORAGE_BUFFER_STORAGE_CLASS_EXTENSION_NAME,
                                         VK_KHR_16BIT_STORAGE_EXTENSION_NAME,
                                         VK_KHR_8BIT_STORAGE_EXTENSION_NAME,
                                         VK_KHR_SHADER_FLOAT16_INT8_EXTENSION_NAME,
                                         VK_EXT_COLOR_WRITE_ENABLE_EXTENSION_NAME,
                                         VK_EXT_MULTI_DRAW_EXTENSION_NAME,
                                         VK_KHR_SHADER_DRAW_PARAMETERS_EXTENSION_NAME,
                                         VK_EXT_PROVOKING_VERTEX_EXTENSION_NAME,
                                         VK_EXT_DEPTH_CLIP_ENABLE_EXTENSION_NAME,
                                         VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME,
                                         VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME,
                                         VK_EXT_SHADER_ATOMIC_FLOAT_2_EXTENSION_NAME,
                                         VK_KHR_SHADER_ATOMIC_INT64_EXTENSION_NAME,
                                         VK_EXT_CUSTOM_BORDER_COLOR_EXTENSION_NAME,
                                         VK_EXT_SAMPLER_FILTER_MINMAX_EXTENSION_NAME,
                                         VK_EXT_4444_FORMATS_EXTENSION_NAME,
                                         VK_EXT_VERTEX_INPUT_DYNAMIC_STATE_EXTENSION_NAME,
                                         VK_EXT_EXTENDED_DYNAMIC_STATE_3_EXTENSION_NAME,
                                         VK_EXT_CONDITIONAL_RENDERING_EXTENSION_NAME,
                                         VK_EXT_NON_SEAMLESS_CUBE_MAP_EXTENSION_NAME,
                                         VK_EXT_ROBUSTNESS_2_EXTENSION_NAME};

}  // namespace

static void load_dynamic_state_commands(DeviceContext& c) {
    auto get = [&c](auto& fn, const char* name) {
        fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(vkGetDeviceProcAddr(c.device, name));
    };
    DeviceContext::DynamicStateCommands& d = c.cmd;
    if (c.extended_dynamic_state.extendedDynamicState) {
        get(d.cull_mode, "vkCmdSetCullModeEXT");
        get(d.front_face, "vkCmdSetFrontFaceEXT");
        get(d.topology, "vkCmdSetPrimitiveTopologyEXT");
        get(d.viewport_with_count, "vkCmdSetViewportWithCountEXT");
        get(d.scissor_with_count, "vkCmdSetScissorWithCountEXT");
        get(d.bind_vertex_buffers2, "vkCmdBindVertexBuffers2EXT");
        get(d.depth_test, "vkCmdSetDepthTestEnableEXT");
        get(d.depth_write, "vkCmdSetDepthWriteEnableEXT");
        get(d.depth_compare, "vkCmdSetDepthCompareOpEXT");
        get(d.depth_bounds_test, "vkCmdSetDepthBoundsTestEnableEXT");
        get(d.stencil_test, "vkCmdSetStencilTestEnableEXT");
        get(d.stencil_op, "vkCmdSetStencilOpEXT");
    }
    if (c.extended_dynamic_state2.extendedDynamicState2) {
        get(d.rasterizer_discard, "vkCmdSetRasterizerDiscardEnableEXT");
        get(d.depth_bias, "vkCmdSetDepthBiasEnableEXT");
        get(d.primitive_restart, "vkCmdSetPrimitiveRestartEnableEXT");
    }
    if (c.extended_dynamic_state2.extendedDynamicState2LogicOp) get(d.logic_op, "vkCmdSetLogicOpEXT");
    if (c.color_write_enable.colorWriteEnable) get(d.color_write_enable, "vkCmdSetColorWriteEnableEXT");
    if (c.vertex_input_dynamic_state.vertexInputDynamicState) get(d.vertex_input, "vkCmdSetVertexInputEXT");
    // Extended dynamic state 3: each command whose feature the device reports (Draw::dynamic3 needs them all).
    const VkPhysicalDeviceExtendedDynamicState3FeaturesEXT& f3 = c.extended_dynamic_state3;
    if (f3.extendedDynamicState3PolygonMode) get(d.polygon_mode, "vkCmdSetPolygonModeEXT");
    if (f3.extendedDynamicState3DepthClampEnable) get(d.depth_clamp, "vkCmdSetDepthClampEnableEXT");
    if (f3.extendedDynamicState3DepthClipEnable) get(d.depth_clip, "vkCmdSetDepthClipEnableEXT");
    if (f3.extendedDynamicState3DepthClipNegativeOneToOne)
        get(d.negative_one_to_one, "vkCmdSetDepthClipNegativeOneToOneEXT");
    if (f3.extendedDynamicState3LogicOpEnable) get(d.logic_op_enable, "vkCmdSetLogicOpEnableEXT");
    if (f3.extendedDynamicState3SampleMask) get(d.sample_mask, "vkCmdSetSampleMaskEXT");
    if (f3.extendedDynamicState3AlphaToCoverageEnable) get(d.alpha_to_coverage, "vkCmdSetAlphaToCoverageEnableEXT");
    if (f3.extendedDynamicState3LineRasterizationMode) get(d.line_mode, "vkCmdSetLineRasterizationModeEXT");
    if (f3.extendedDynamicState3LineStippleEnable) get(d.line_stipple, "vkCmdSetLineStippleEnableEXT");
    if (f3.extendedDynamicState3ProvokingVertexMode) get(d.provoking_vertex, "vkCmdSetProvokingVertexModeEXT");
    if (f3.extendedDynamicState3ColorBlendEnable) get(d.blend_enable, "vkCmdSetColorBlendEnableEXT");
    if (f3.extendedDynamicState3ColorBlendEquation) get(d.blend_equation, "vkCmdSetColorBlendEquationEXT");
    if (f3.extendedDynamicState3ColorWriteMask) get(d.write_mask, "vkCmdSetColorWriteMaskEXT");
    if (c.multi_draw.multiDraw) {
        get(d.draw_multi, "vkCmdDrawMultiEXT");
        get(d.draw_multi_indexed, "vkCmdDrawMultiIndexedEXT");
    }
    if (c.conditional_rendering.conditionalRendering) {
        get(d.begin_conditional, "vkCmdBeginConditionalRenderingEXT");
        get(d.end_conditional, "vkCmdEndConditionalRenderingEXT");
    }
}

bool DeviceContext::has_extension(const char* n) const {
    for (const std::string& e : extensions)
        if (e == n) return true;
    return false;
}

uint32_t DeviceContext::memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const {
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if ((bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags) return i;
    }
    throw VkError("no memory type with flags " + std::to_string(flags) + " in bits " + std::to_string(bits));
}

Instance::Instance(ValidationLog* validation) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "tilevk-cts";
    app.apiVersion = VK_MAKE_API_VERSION(0, 1, spirv_target_vulkan_minor(), 0);  // the SPIR-V's environment
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    // get_physical_device_properties2: the feature structs of the device extensions are read through it;
    // device_group_creation, which VK_KHR_device_group (vkCmdDispatchBaseKHR) needs on a Vulkan 1.0 instance, when
    // the loader offers it.
    std::vector<const char*> exts = {VK_KHR_GET_PHYSICAL_DEVICE_PROPERTIES_2_EXTENSION_NAME};
    {
        uint32_t n = 0;
        vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
        std::vector<VkExtensionProperties> offered(n);
        vkEnumerateInstanceExtensionProperties(nullptr, &n, offered.data());
        for (const VkExtensionProperties& e : offered)
            if (std::strcmp(e.extensionName, VK_KHR_DEVICE_GROUP_CREATION_EXTENSION_NAME) == 0)
                exts.push_back(VK_KHR_DEVICE_GROUP_CREATION_EXTENSION_NAME);
    }
    VkDebugUtilsMessengerCreateInfoEXT mci = ValidationLog::messenger_info(validation);
    // The layer's default checks plus synchronization validation (off by default): missing or wrong barriers are
    // harness bugs that a CPU driver, which runs commands in order, would never show in an image.
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    if (validation) {
        features.pNext = &mci;  // messages of vkCreateInstance/vkDestroyInstance themselves
        ci.pNext = &features;
        ci.enabledLayerCount = 1;
        ci.ppEnabledLayerNames = &layer;
        exts.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        exts.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    }
    ci.enabledExtensionCount = uint32_t(exts.size());
    ci.ppEnabledExtensionNames = exts.data();
    vk_check(vkCreateInstance(&ci, nullptr, &instance_),
             validation ? "vkCreateInstance with VK_LAYER_KHRONOS_validation" : "vkCreateInstance");
    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create) {
            vkDestroyInstance(instance_, nullptr);
            throw VkError("vkCreateDebugUtilsMessengerEXT is not available");
        }
        VkResult r = create(instance_, &mci, nullptr, &messenger_);
        if (r != VK_SUCCESS) {
            vkDestroyInstance(instance_, nullptr);
            vk_check(r, "vkCreateDebugUtilsMessengerEXT");
        }
    }
    uint32_t n = 0;
    vk_check(vkEnumeratePhysicalDevices(instance_, &n, nullptr), "vkEnumeratePhysicalDevices");
    physicals_.resize(n);
    vk_check(vkEnumeratePhysicalDevices(instance_, &n, physicals_.data()), "vkEnumeratePhysicalDevices");
    physicals_.resize(n);
}

Instance::~Instance() {
    if (!instance_) return;
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    vkDestroyInstance(instance_, nullptr);
}

std::vector<std::string> Instance::device_names() const {
    std::vector<std::string> names;
    for (VkPhysicalDevice p : physicals_) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(p, &props);
        names.emplace_back(props.deviceName);
    }
    return names;
}

bool Instance::open(const std::string& substring, bool prefix, DeviceContext& out, std::string& reason) const {
    std::string seen;
    for (VkPhysicalDevice p : physicals_) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(p, &props);
        std::string name = props.deviceName;
        seen += (seen.empty() ? "" : ", ") + ("'" + name + "'");
        bool match = prefix ? name.rfind(substring, 0) == 0 : name.find(substring) != std::string::npos;
        if (!match) continue;
        out = DeviceContext{};
        out.physical = p;
        out.props = props;
        out.name = name;
        vkGetPhysicalDeviceFeatures(p, &out.features);
        vkGetPhysicalDeviceMemoryProperties(p, &out.memory);
        uint32_t nq = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(p, &nq, nullptr);
        std::vector<VkQueueFamilyProperties> qf(nq);
        vkGetPhysicalDeviceQueueFamilyProperties(p, &nq, qf.data());
        uint32_t family = UINT32_MAX;
        for (uint32_t i = 0; i < nq; ++i) {
            if (qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
                family = i;
                break;
            }
        }
        if (family == UINT32_MAX) {
            reason = "device '" + name + "' has no graphics queue family";
            return false;
        }
        float priority = 1.0f;
        VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qci.queueFamilyIndex = family;
        qci.queueCount = 1;
        qci.pQueuePriorities = &priority;
        // Enable every feature the device offers so that cases can ask for what they need.
        VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        dci.queueCreateInfoCount = 1;
        dci.pQueueCreateInfos = &qci;
        dci.pEnabledFeatures = &out.features;
        // The subset's device extensions that this device offers, with every feature their structs report.
        uint32_t next = 0;
        vkEnumerateDeviceExtensionProperties(p, nullptr, &next, nullptr);
        std::vector<VkExtensionProperties> offered(next);
        vkEnumerateDeviceExtensionProperties(p, nullptr, &next, offered.data());
        std::vector<const char*> enable;
        for (const char* want : kSubsetExtensions)
            for (const VkExtensionProperties& e : offered)
                if (std::strcmp(e.extensionName, want) == 0) {
                    enable.push_back(want);
                    out.extensions.emplace_back(want);
                }
        void* chain = nullptr;
        auto link = [&](auto& feature_struct, const char* ext) {
            if (!out.has_extension(ext)) return;
            feature_struct.pNext = chain;
            chain = &feature_struct;
        };
        link(out.index_type_uint8, VK_EXT_INDEX_TYPE_UINT8_EXTENSION_NAME);
        link(out.list_restart, VK_EXT_PRIMITIVE_TOPOLOGY_LIST_RESTART_EXTENSION_NAME);
        link(out.depth_clip_control, VK_EXT_DEPTH_CLIP_CONTROL_EXTENSION_NAME);
        link(out.extended_dynamic_state, VK_EXT_EXTENDED_DYNAMIC_STATE_EXTENSION_NAME);
        link(out.extended_dynamic_state2, VK_EXT_EXTENDED_DYNAMIC_STATE_2_EXTENSION_NAME);
        link(out.color_write_enable, VK_EXT_COLOR_WRITE_ENABLE_EXTENSION_NAME);
        link(out.multi_draw, VK_EXT_MULTI_DRAW_EXTENSION_NAME);
        link(out.provoking_vertex, VK_EXT_PROVOKING_VERTEX_EXTENSION_NAME);
        link(out.depth_clip_enable, VK_EXT_DEPTH_CLIP_ENABLE_EXTENSION_NAME);
        link(out.line_rasterization, VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME);
        link(out.atomic_float, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
        link(out.atomic_float2, VK_EXT_SHADER_ATOMIC_FLOAT_2_EXTENSION_NAME);
        link(out.custom_border_color, VK_EXT_CUSTOM_BORDER_COLOR_EXTENSION_NAME);
        link(out.formats_4444, VK_EXT_4444_FORMATS_EXTENSION_NAME);
        link(out.vertex_input_dynamic_state, VK_EXT_VERTEX_INPUT_DYNAMIC_STATE_EXTENSION_NAME);
        link(out.extended_dynamic_state3, VK_EXT_EXTENDED_DYNAMIC_STATE_3_EXTENSION_NAME);
        link(out.conditional_rendering, VK_EXT_CONDITIONAL_RENDERING_EXTENSION_NAME);
        link(out.non_seamless_cube_map, VK_EXT_NON_SEAMLESS_CUBE_MAP_EXTENSION_NAME);
        link(out.robustness2, VK_EXT_ROBUSTNESS_2_EXTENSION_NAME);
        // SPIR-V 1.6 (a Vulkan 1.3 instance): glslang writes LocalSizeId for spec-constant workgroup sizes, which
        // needs maintenance4 (core in 1.3, required of every 1.3 device).
        VkPhysicalDeviceMaintenance4Features maintenance4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES};
        if (spirv_target_vulkan_minor() >= 3) {
            maintenance4.pNext = chain;
            chain = &maintenance4;
        }
        // 8- and 16-bit types: shaderInt8 and the 8/16-bit storage features (types.int16.*, types.int8.*, ...)
        VkPhysicalDevice16BitStorageFeatures storage16{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_16BIT_STORAGE_FEATURES};
        VkPhysicalDevice8BitStorageFeatures storage8{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_8BIT_STORAGE_FEATURES};
        VkPhysicalDeviceShaderFloat16Int8Features int8{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES};
        link(storage16, VK_KHR_16BIT_STORAGE_EXTENSION_NAME);
        // On a Vulkan 1.2+ instance the validation layer reads Vulkan 1.2's features from this struct only (e.g.
        // samplerFilterMinmax, texture.minmax.*), and it must then replace the structs of extensions promoted to 1.2.
        VkPhysicalDeviceVulkan12Features core12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        if (spirv_target_vulkan_minor() >= 2) {
            core12.pNext = chain;
            chain = &core12;
        } else {
            link(storage8, VK_KHR_8BIT_STORAGE_EXTENSION_NAME);
            link(int8, VK_KHR_SHADER_FLOAT16_INT8_EXTENSION_NAME);
            link(out.atomic_int64, VK_KHR_SHADER_ATOMIC_INT64_EXTENSION_NAME);
        }
        if (chain != nullptr) {
            auto features2 = reinterpret_cast<PFN_vkGetPhysicalDeviceFeatures2KHR>(
                vkGetInstanceProcAddr(instance_, "vkGetPhysicalDeviceFeatures2KHR"));
            VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
            f2.pNext = chain;
            if (features2) features2(p, &f2);  // every reported feature is then enabled as reported
            // ... except the one that needs VK_EXT_transform_feedback, which the subset never enables
            out.provoking_vertex.transformFeedbackPreservesProvokingVertex = VK_FALSE;
        }
        if (spirv_target_vulkan_minor() >= 2 && out.has_extension(VK_KHR_SHADER_ATOMIC_INT64_EXTENSION_NAME)) {
            out.atomic_int64.shaderBufferInt64Atomics = core12.shaderBufferInt64Atomics;  // enabled through core12
            out.atomic_int64.shaderSharedInt64Atomics = core12.shaderSharedInt64Atomics;
        }
        dci.pNext = chain;
        dci.enabledExtensionCount = uint32_t(enable.size());
        dci.ppEnabledExtensionNames = enable.data();
        try {
            vk_check(vkCreateDevice(p, &dci, nullptr, &out.device), ("vkCreateDevice on '" + name + "'").c_str());
            out.index_type_uint8.pNext = out.list_restart.pNext = out.depth_clip_control.pNext = nullptr;
            out.extended_dynamic_state.pNext = out.extended_dynamic_state2.pNext = nullptr;
            out.color_write_enable.pNext = out.multi_draw.pNext = nullptr;
            out.provoking_vertex.pNext = out.depth_clip_enable.pNext = out.line_rasterization.pNext = nullptr;
            out.atomic_float.pNext = out.atomic_float2.pNext = out.atomic_int64.pNext = nullptr;
            out.custom_border_color.pNext = nullptr;
            out.formats_4444.pNext = nullptr;
            out.vertex_input_dynamic_state.pNext = out.extended_dynamic_state3.pNext = nullptr;
            out.conditional_rendering.pNext = out.robustness2.pNext = nullptr;
            load_dynamic_state_commands(out);
            out.queue_family = family;
            vkGetDeviceQueue(out.device, family, 0, &out.queue);
            VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
            pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
            pci.queueFamilyIndex = family;
            vk_check(vkCreateCommandPool(out.device, &pci, nullptr, &out.pool), "vkCreateCommandPool");
        } catch (const VkError& e) {
            reason = e.what();
            close(out);
            return false;
        }
        return true;
    }
    reason = "no Vulkan device named " + std::string(prefix ? "'" + substring + "...'" : "'*" + substring + "*'") +
             " (found: " + (seen.empty() ? "none" : seen) + ")";
    return false;
}

void Instance::close(DeviceContext& ctx) {
    if (ctx.device) {
        vkDeviceWaitIdle(ctx.device);
        if (ctx.pool) vkDestroyCommandPool(ctx.device, ctx.pool, nullptr);
        vkDestroyDevice(ctx.device, nullptr);
    }
    ctx.device = VK_NULL_HANDLE;
    ctx.pool = VK_NULL_HANDLE;
}

}  // namespace tilevk::cts
