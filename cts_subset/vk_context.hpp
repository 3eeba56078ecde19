// The runner's Vulkan side: one instance, and a "device context" per side (ours and the reference).
// Both sides may live on the same physical device (lavapipe vs lavapipe) as two separate VkDevices.
#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace tilevk::cts {

class ValidationLog;

// Any failing Vulkan call becomes this error; its text is the reason a case fails.
struct VkError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
void vk_check(VkResult r, const char* what);

struct DeviceContext {
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties props{};
    VkPhysicalDeviceFeatures features{};
    VkPhysicalDeviceMemoryProperties memory{};
    std::string name;
    // The device extensions of kSubsetExtensions (vk_context.cpp) the device offers, all enabled, and their
    // feature structs with every reported feature enabled.
    std::vector<std::string> extensions;
    VkPhysicalDeviceIndexTypeUint8FeaturesEXT index_type_uint8{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_INDEX_TYPE_UINT8_FEATURES_EXT};
    VkPhysicalDevicePrimitiveTopologyListRestartFeaturesEXT list_restart{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PRIMITIVE_TOPOLOGY_LIST_RESTART_FEATURES_EXT};
    VkPhysicalDeviceDepthClipControlFeaturesEXT depth_clip_control{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_CONTROL_FEATURES_EXT};
    VkPhysicalDeviceExtendedDynamicStateFeaturesEXT extended_dynamic_state{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_FEATURES_EXT};
    VkPhysicalDeviceExtendedDynamicState2FeaturesEXT extended_dynamic_state2{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_2_FEATURES_EXT};
    VkPhysicalDeviceColorWriteEnableFeaturesEXT color_write_enable{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_COLOR_WRITE_ENABLE_FEATURES_EXT};
    VkPhysicalDeviceMultiDrawFeaturesEXT multi_draw{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTI_DRAW_FEATURES_EXT};
    VkPhysicalDeviceConditionalRenderingFeaturesEXT conditional_rendering{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_CONDITIONAL_RENDERING_FEATURES_EXT};
    VkPhysicalDeviceProvokingVertexFeaturesEXT provoking_vertex{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_FEATURES_EXT};
    VkPhysicalDeviceDepthClipEnableFeaturesEXT depth_clip_enable{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_ENABLE_FEATURES_EXT};
    VkPhysicalDeviceLineRasterizationFeaturesEXT line_rasterization{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT};
    VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomic_float{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
    VkPhysicalDeviceShaderAtomicFloat2FeaturesEXT atomic_float2{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_2_FEATURES_EXT};
    // VK_KHR_shader_atomic_int64's features (on a Vulkan 1.2+ instance enabled through Vulkan 1.2's struct and
    // copied here).
    VkPhysicalDeviceShaderAtomicInt64Features atomic_int64{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_INT64_FEATURES};
    VkPhysicalDeviceCustomBorderColorFeaturesEXT custom_border_color{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_CUSTOM_BORDER_COLOR_FEATURES_EXT};
    VkPhysicalDevice4444FormatsFeaturesEXT formats_4444{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_4444_FORMATS_FEATURES_EXT};
    VkPhysicalDeviceVertexInputDynamicStateFeaturesEXT vertex_input_dynamic_state{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VERTEX_INPUT_DYNAMIC_STATE_FEATURES_EXT};
    VkPhysicalDeviceExtendedDynamicState3FeaturesEXT extended_dynamic_state3{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_3_FEATURES_EXT};
    VkPhysicalDeviceNonSeamlessCubeMapFeaturesEXT non_seamless_cube_map{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_NON_SEAMLESS_CUBE_MAP_FEATURES_EXT};
    VkPhysicalDeviceRobustness2FeaturesEXT robustness2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT};
    bool has_extension(const char* name) const;
    // Extended dynamic state commands of the device (null when its extension is not enabled).
    struct DynamicStateCommands {
        PFN_vkCmdSetCullModeEXT cull_mode = nullptr;
        PFN_vkCmdSetFrontFaceEXT front_face = nullptr;
        PFN_vkCmdSetPrimitiveTopologyEXT topology = nullptr;
        PFN_vkCmdSetViewportWithCountEXT viewport_with_count = nullptr;
        PFN_vkCmdSetScissorWithCountEXT scissor_with_count = nullptr;
        PFN_vkCmdBindVertexBuffers2EXT bind_vertex_buffers2 = nullptr;
        PFN_vkCmdSetDepthTestEnableEXT depth_test = nullptr;
        PFN_vkCmdSetDepthWriteEnableEXT depth_write = nullptr;
        PFN_vkCmdSetDepthCompareOpEXT depth_compare = nullptr;
        PFN_vkCmdSetDepthBoundsTestEnableEXT depth_bounds_test = nullptr;
        PFN_vkCmdSetStencilTestEnableEXT stencil_test = nullptr;
        PFN_vkCmdSetStencilOpEXT stencil_op = nullptr;
        PFN_vkCmdSetRasterizerDiscardEnableEXT rasterizer_discard = nullptr;
        PFN_vkCmdSetDepthBiasEnableEXT depth_bias = nullptr;
        PFN_vkCmdSetPrimitiveRestartEnableEXT primitive_restart = nullptr;
        PFN_vkCmdSetLogicOpEXT logic_op = nullptr;
        PFN_vkCmdSetColorWriteEnableEXT color_write_enable = nullptr;
        PFN_vkCmdDrawMultiEXT draw_multi = nullptr;
        PFN_vkCmdDrawMultiIndexedEXT draw_multi_indexed = nullptr;
        PFN_vkCmdBeginConditionalRenderingEXT begin_conditional = nullptr;
        PFN_vkCmdEndConditionalRenderingEXT end_conditional = nullptr;
        PFN_vkCmdSetVertexInputEXT vertex_input = nullptr;
        // Extended dynamic state 3 (the members Draw::dynamic3 sets).
        PFN_vkCmdSetPolygonModeEXT polygon_mode = nullptr;
        PFN_vkCmdSetDepthClampEnableEXT depth_clamp = nullptr;
        PFN_vkCmdSetDepthClipEnableEXT depth_clip = nullptr;
        PFN_vkCmdSetDepthClipNegativeOneToOneEXT negative_one_to_one = nullptr;
        PFN_vkCmdSetLogicOpEnableEXT logic_op_enable = nullptr;
        PFN_vkCmdSetSampleMaskEXT sample_mask = nullptr;
        PFN_vkCmdSetAlphaToCoverageEnableEXT alpha_to_coverage = nullptr;
        PFN_vkCmdSetLineRasterizationModeEXT line_mode = nullptr;
        PFN_vkCmdSetLineStippleEnableEXT line_stipple = nullptr;
        PFN_vkCmdSetProvokingVertexModeEXT provoking_vertex = nullptr;
        PFN_vkCmdSetColorBlendEnableEXT blend_enable = nullptr;
        PFN_vkCmdSetColorBlendEquationEXT blend_equation = nullptr;
        PFN_vkCmdSetColorWriteMaskEXT write_mask = nullptr;
    } cmd;

    // The index of a memory type allowed by `bits` that has all of `flags`; throws if there is none.
    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const;
};

class Instance {
  public:
    // With a log, VK_LAYER_KHRONOS_validation is enabled and a debug-utils messenger feeds the log (also during
    // vkCreateInstance/vkDestroyInstance).
    explicit Instance(ValidationLog* validation = nullptr);
    ~Instance();
    Instance(const Instance&) = delete;
    Instance& operator=(const Instance&) = delete;

    std::vector<std::string> device_names() const;
    // Opens a logical device on the first physical device whose name contains `substring` (or starts with it when
    // `prefix`); returns false with a reason if none matches or creation fails.
    bool open(const std::string& substring, bool prefix, DeviceContext& out, std::string& reason) const;
    static void close(DeviceContext& ctx);

  private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    std::vector<VkPhysicalDevice> physicals_;
};

}  // namespace tilevk::cts
