// A scene is the whole description of one conformance case's frame: a render target and a list of draws.
// Cases build scenes from tables; render.cpp turns a scene into identical Vulkan commands on each device.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tilevk::cts {

struct Vertex {
    float pos[4] = {0, 0, 0, 1};
    float color[4] = {1, 1, 1, 1};
    float uv[2] = {0, 0};
    float point_size = 1.0f;
};

enum class Interp { kSmooth, kFlat, kNoPerspective };
// kCount writes exactly 1/255 to every channel (one unorm8 increment under ONE,ONE blending);
// kFacing writes 1/255 to red for front faces and to green for back faces.
// kDiscard discards pixels whose x + y is odd (a checkerboard) and writes v_color elsewhere.
// kColorSum writes v_color + v_color: an fadd, which lavapipe's linear-shader analysis
// (lp_state_fs_analysis.c) refuses, so B8G8R8A8 frames with it isolate the linear mode's geometry.
// kConstant writes vec4(0.5, 0.25, 0.8, 0.75); kColorRgb1 vec4(v_color.rgb, 1.0).
enum class Frag { kColor, kTexture, kCount, kFacing, kDiscard, kColorSum, kConstant, kColorRgb1 };

// Occlusion queries around the draws (cases_query.cpp): none; one query per draw, begun and ended inside the
// render pass; or one query begun before the render pass and ended after it (spanning it). The results are copied
// into a buffer (vkCmdCopyQueryPoolResults, 64-bit values with availability) and read back as the plane "queries".
enum class QueryMode { kNone, kPerDraw, kAcrossPass };
enum class TexPattern { kChecker, kGradient };

struct TextureSpec {
    uint32_t width = 16, height = 16, mip_levels = 1;
    // More than 1: a VK_IMAGE_TYPE_3D image and VIEW_TYPE_3D view whose texels encode their coordinates (the pattern
    // is ignored; texture.3d.*, which bring their own sampler3D shaders), its depth halving per level too.
    uint32_t depth = 1;
    // one_d: a VK_IMAGE_TYPE_1D image of `layers` layers (height ignored), viewed as 1D or, with more than one
    // layer, 1D_ARRAY; its texels encode x, layer and level (texture.1d.*, with their own sampler1D shaders).
    bool one_d = false;
    uint32_t layers = 1;
    std::optional<VkSamplerAddressMode> wrap_w;  // addressModeW when it differs from `wrap`
    TexPattern pattern = TexPattern::kChecker;
    VkFilter mag = VK_FILTER_NEAREST, min = VK_FILTER_NEAREST;
    VkSamplerMipmapMode mip_mode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    VkSamplerAddressMode wrap = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    VkBorderColor border = VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK;
    float max_lod = 16.0f;
    // Cube textures (cases_texture_cube.cpp): a CUBE view when 6, a CUBE_ARRAY view of that many layers when a
    // larger multiple of 6 (square: width is the size); their format (R8G8B8A8_UNORM or D32_SFLOAT) and
    // depth comparison.
    uint32_t cube_layers = 0;
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    // VK_EXT_custom_border_color: `border` must be VK_BORDER_COLOR_{FLOAT,INT}_CUSTOM_EXT (texture.custom_border.*)
    std::optional<VkClearColorValue> custom_border;
    // samplerFilterMinmax (VK_EXT_sampler_filter_minmax; texture.minmax.*, on an R8_UNORM `format`)
    VkSamplerReductionMode reduction = VK_SAMPLER_REDUCTION_MODE_WEIGHTED_AVERAGE;
    float lod_bias = 0.0f;  // VkSamplerCreateInfo::mipLodBias, for every kind of texture (texture.lod_bias.*)
    // above 0: anisotropyEnable with this maxAnisotropy (feature samplerAnisotropy; texture.aniso.*)
    float max_anisotropy = 0.0f;
    bool compare = false;
    VkCompareOp compare_op = VK_COMPARE_OP_LESS;
    // VK_EXT_non_seamless_cube_map: the cube sampler made with VK_SAMPLER_CREATE_NON_SEAMLESS_CUBE_MAP_BIT_EXT
    bool non_seamless = false;
};

struct Draw {
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    std::vector<Vertex> vertices;
    VkCullModeFlags cull = VK_CULL_MODE_NONE;
    VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    VkPolygonMode polygon_mode = VK_POLYGON_MODE_FILL;
    float line_width = 1.0f;
    Interp interp = Interp::kSmooth;
    Frag frag = Frag::kColor;
    std::optional<TextureSpec> texture;
    // Colour output.
    VkPipelineColorBlendAttachmentState blend = {VK_FALSE,
                                                 VK_BLEND_FACTOR_ONE,
                                                 VK_BLEND_FACTOR_ZERO,
                                                 VK_BLEND_OP_ADD,
                                                 VK_BLEND_FACTOR_ONE,
                                                 VK_BLEND_FACTOR_ZERO,
                                                 VK_BLEND_OP_ADD,
                                                 0xF};
    float blend_constants[4] = {0, 0, 0, 0};
    // Logic op (feature logicOp; it replaces blending) when set.
    std::optional<VkLogicOp> logic_op;
    // Depth and stencil.
    bool depth_test = false, depth_write = false;
    VkCompareOp depth_op = VK_COMPARE_OP_LESS;
    bool depth_clamp = false;
    bool depth_bias = false;
    float bias_constant = 0, bias_slope = 0, bias_clamp = 0;
    bool stencil_test = false;
    VkStencilOpState stencil_front = {}, stencil_back = {};
    // Multisample state (the sample count comes from the target).
    uint32_t sample_mask = 0xFFFFFFFFu;
    bool alpha_to_coverage = false;
    bool alpha_to_one = false;  // feature alphaToOne
    float min_sample_shading = -1.0f;  // >= 0: sampleShadingEnable with this minSampleShading (sampleRateShading)
    // Viewport and scissor; unset means the whole target. negative_one_to_one: clip-space depth in [-w, w]
    // (VK_EXT_depth_clip_control); viewport_count > 1 repeats the viewport and scissor (feature multiViewport;
    // every primitive still uses viewport 0).
    bool negative_one_to_one = false;
    // Rasterization extensions (cases_raster_ext.cpp), each chained to the rasterization state when set:
    // VK_EXT_provoking_vertex (LAST_VERTEX), VK_EXT_depth_clip_enable (depthClipEnable) and
    // VK_EXT_line_rasterization (lineRasterizationMode, stippledLineEnable off).
    bool provoking_last = false;
    std::optional<bool> depth_clip_enable;
    std::optional<VkLineRasterizationModeEXT> line_mode;
    uint32_t viewport_count = 1;
    // Everything extended dynamic state 1 and 2 can set is set with vkCmdSet* before the draw instead, on a
    // pipeline created with other values (render.cpp dynamic_pipeline_state): the frame must not change.
    bool dynamic = false;
    // With `dynamic`: the vertex input (VK_EXT_vertex_input_dynamic_state) and every extended dynamic state 3 state
    // tilevk reports are set by vkCmdSet* too, the pipeline made with other values (another topology class, the
    // opposite enables, other blend equations and masks, sample mask 0); render_objects.cpp kDynamicStates3.
    bool dynamic3 = false;
    std::optional<VkViewport> viewport;
    std::optional<VkRect2D> scissor;
    // Free-form shaders (cases_random.cpp): when set, they replace the generated GLSL. The vertex inputs are
    // vertex_source's (locations 0-3); `push_constants` are one block of vec4s (VERTEX|FRAGMENT) and `uniforms` a
    // uniform buffer of vec4s at set 0, binding 1 (VERTEX|FRAGMENT).
    std::string vertex_glsl, fragment_glsl;
    // SPIR-V used as is instead of the compiled GLSL (tilevk-cts --fuzz feeds mutated modules through it).
    std::vector<uint32_t> vertex_spirv, fragment_spirv;
    std::vector<float> push_constants;  // at most 32 floats (maxPushConstantsSize 128)
    std::vector<float> uniforms;
    // Indexed draw (vkCmdDrawIndexed) when non-empty; indices refer to this draw's vertices. Restart values
    // (0xFF / 0xFFFF / 0xFFFFFFFF) are written by the case; restart on a list topology needs
    // VK_EXT_primitive_topology_list_restart, VK_INDEX_TYPE_UINT8_EXT needs VK_EXT_index_type_uint8.
    std::vector<uint32_t> indices;
    VkIndexType index_type = VK_INDEX_TYPE_UINT32;
    bool primitive_restart = false;
    uint32_t instances = 1;
    // Format of the colour attribute (location 1): R32G32B32A32_SFLOAT reads Vertex::color in place; any other
    // float/normalized format reads a second vertex binding packed from Vertex::color (render.cpp).
    VkFormat color_format = VK_FORMAT_R32G32B32A32_SFLOAT;
    // VK_EXT_color_write_enable: when set, attachment 0's enable; static (VkPipelineColorWriteCreateInfoEXT), or with
    // color_write_dynamic set by vkCmdSetColorWriteEnableEXT on a pipeline whose struct says the opposite.
    std::optional<VkBool32> color_write_enable;
    bool color_write_dynamic = false;
    // VK_EXT_multi_draw: when non-empty, one vkCmdDrawMultiEXT (or vkCmdDrawMultiIndexedEXT with `indices`) of
    // these entries {firstVertex or firstIndex, count, vertexOffset}, `instances` instances, the entries `stride`
    // bytes apart (render.cpp pads them); multi_vertex_offset: pVertexOffset.
    std::vector<std::array<int32_t, 3>> multi;
    std::optional<int32_t> multi_vertex_offset;
    // VK_EXT_conditional_rendering: when set, the draw (and clear_rect's clear) is recorded between
    // vkCmdBeginConditionalRenderingEXT and vkCmdEndConditionalRenderingEXT on a buffer holding this predicate at
    // offset 4 (its first word ~predicate, so a reader of the wrong word sees the opposite); condition_inverted:
    // VK_CONDITIONAL_RENDERING_INVERTED_BIT_EXT.
    std::optional<uint32_t> condition;
    bool condition_inverted = false;
    // When set, a vkCmdClearAttachments of colour attachment 0 over this rect (layer 0) to clear_rect_color, just
    // before the draw.
    std::optional<VkRect2D> clear_rect;
    std::array<float, 4> clear_rect_color = {0, 0, 0, 0};
};

struct Target {
    uint32_t width = 64, height = 64;
    VkFormat color = VK_FORMAT_R8G8B8A8_UNORM;  // VK_FORMAT_UNDEFINED: depth-only
    VkFormat depth = VK_FORMAT_UNDEFINED;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;  // > 1: the colour is resolved before read-back
    float clear_color[4] = {0, 0, 0, 0};
    float clear_depth = 1.0f;
    uint32_t clear_stencil = 0;
};

struct Plane;
struct DeviceContext;

struct Scene {
    Target target;
    std::vector<Draw> draws;
    QueryMode queries = QueryMode::kNone;
    // Non-zero: the queries are pipeline-statistics queries counting these (cases_statistics.cpp), each result
    // one 64-bit value per bit in bit order, then the availability word.
    VkQueryPipelineStatisticFlags statistics = 0;
    // A case without draws (transfer commands, e.g. cases_blit.cpp) runs its own commands instead: `run` records,
    // submits and reads back on one device; `unsupported` names what the device lacks (empty: supported).
    std::function<std::vector<Plane>(const DeviceContext&)> run;
    std::function<std::string(const DeviceContext&)> unsupported;
};

// One read-back plane: colour, depth or stencil, tightly packed rows.
struct Plane {
    std::string name;  // "color", "depth", "stencil"
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0, texel_bytes = 0;
    std::vector<uint8_t> data;
};

}  // namespace tilevk::cts
