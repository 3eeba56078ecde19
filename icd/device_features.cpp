#include "device_features.h"

#include <cstring>
#include <type_traits>
#include <vector>

#include "object.h"
#include "vk_names.h"

namespace tilevk::icd {
namespace {

constexpr size_t kHeader = sizeof(VkBaseOutStructure);  // sType + pNext, ahead of every feature struct's members

template <class T>
void init(T& s, VkStructureType t) {
    s = {};
    s.sType = t;
}

// The members of `s` after sType/pNext, copied from `from` (a struct of the same type); `size` is the struct's size.
void copy_body(VkBaseOutStructure* s, const void* from, size_t size) {
    std::memcpy(reinterpret_cast<char*>(s) + kHeader, static_cast<const char*>(from) + kHeader, size - kHeader);
}

// The Vulkan 1.1/1.2/1.3 structs themselves (the structs promoted into them go through core_structs.cpp).
template <class Core>
auto* core_struct(Core& core, VkStructureType t) {
    using Ptr = std::conditional_t<std::is_const_v<Core>, const void*, void*>;
    switch (t) {
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES:
            return Ptr(&core.v11);
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES:
            return Ptr(&core.v12);
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES:
            return Ptr(&core.v13);
        default:
            return Ptr(nullptr);
    }
}

// Extended dynamic state 3: each member whose state dynamic_state.cpp applies at the draw, as lavapipe 22.3.6 does.
// Not, though lavapipe reports them: TessellationDomainOrigin (tilevk has no tessellation), RasterizationSamples
// (a render pass instance takes its sample count from the first draw's pipeline) and AlphaToOneEnable (lavapipe
// 22.3.6 leaves the alpha of a single-sampled draw as the shader wrote it when alpha to one is set dynamically, but
// not when it is static; cts dynamic.vertex_input_eds3.feature.alpha_to_one.* at 1x showed it and the cause in
// llvmpipe is not yet known, so tilevk does not claim a rule it cannot state). LineStippleEnable: only VK_FALSE
// is valid (no stippled* feature), and a draw with VK_TRUE is refused by name. The rest are VK_FALSE in lavapipe too.
void add_dynamic_state3_features(VkPhysicalDeviceExtendedDynamicState3FeaturesEXT& f) {
    f.extendedDynamicState3PolygonMode = VK_TRUE;
    f.extendedDynamicState3DepthClampEnable = VK_TRUE;
    f.extendedDynamicState3DepthClipEnable = VK_TRUE;
    f.extendedDynamicState3LogicOpEnable = VK_TRUE;
    f.extendedDynamicState3SampleMask = VK_TRUE;
    f.extendedDynamicState3AlphaToCoverageEnable = VK_TRUE;
    f.extendedDynamicState3DepthClipNegativeOneToOne = VK_TRUE;
    f.extendedDynamicState3LineRasterizationMode = VK_TRUE;
    f.extendedDynamicState3LineStippleEnable = VK_TRUE;
    f.extendedDynamicState3ProvokingVertexMode = VK_TRUE;
    f.extendedDynamicState3ColorBlendEnable = VK_TRUE;
    f.extendedDynamicState3ColorBlendEquation = VK_TRUE;
    f.extendedDynamicState3ColorWriteMask = VK_TRUE;
}

// The feature structs of extensions that no core version took in (Features' own members).
void add_extension_features(Features& f) {
    f.index_type_uint8.indexTypeUint8 = VK_TRUE;  // rast/geometry fetch_index: 1-byte indices, restart 0xff
    // Restart on list topologies splits the draw into runs, as lavapipe's prim_restart_loop does for any topology.
    f.list_restart.primitiveTopologyListRestart = VK_TRUE;
    f.depth_clip_control.depthClipControl = VK_TRUE;  // rast/geometry clip_halfz = false: [-w, w], scale (f-n)/2
    // Extended dynamic state 1 and 2 (dynamic_state.cpp); no patch control points (no tessellation).
    f.extended_dynamic_state.extendedDynamicState = VK_TRUE;
    f.extended_dynamic_state2.extendedDynamicState2 = VK_TRUE;
    f.extended_dynamic_state2.extendedDynamicState2LogicOp = VK_TRUE;
    // vkCmdSetVertexInputEXT replaces the pipeline's bindings and attributes (dynamic_state.cpp apply_vertex_input).
    f.vertex_input_dynamic_state.vertexInputDynamicState = VK_TRUE;
    add_dynamic_state3_features(f.extended_dynamic_state3);
    // Instance-rate divisors (VkPipelineVertexInputDivisorStateCreateInfoEXT): element firstInstance + instance /
    // divisor (rast/geometry element_index), divisor 0 as lavapipe's UINT32_MAX (every instance reads firstInstance).
    f.vertex_attribute_divisor.vertexAttributeInstanceRateDivisor = VK_TRUE;
    f.vertex_attribute_divisor.vertexAttributeInstanceRateZeroDivisor = VK_TRUE;
    // Disabled attachments get write mask 0, static (VkPipelineColorWriteCreateInfoEXT) or per draw
    // (vkCmdSetColorWriteEnableEXT), as lavapipe's color_write_disables (dynamic_state.cpp disable_color_writes).
    f.color_write_enable.colorWriteEnable = VK_TRUE;
    // vkCmdDrawMulti[Indexed]EXT: entries as separate draws, instance-major as lavapipe (execute_draw.cpp).
    f.multi_draw.multiDraw = VK_TRUE;
    // PipelineState::flatshade_first: the last vertex orders decomposition, clipping and setup as in lavapipe. No
    // transform feedback in tilevk, so nothing to preserve (lavapipe, which has it, says VK_TRUE).
    f.provoking_vertex.provokingVertexLast = VK_TRUE;
    // PipelineState::depth_clip: z clipping on or off whatever depthClampEnable says (clip_z of the clip mask).
    f.depth_clip_enable.depthClipEnable = VK_TRUE;
    // rast/geometry setup_line's rectangular and Bresenham (diamond-exit) lines, as lp_setup_line.c; smooth and
    // stippled lines are refused at pipeline creation (pipeline.cpp translate_line_state).
    f.line_rasterization.rectangularLines = VK_TRUE;
    f.line_rasterization.bresenhamLines = VK_TRUE;
    // VK_BORDER_COLOR_*_CUSTOM_EXT: the colour's bits, clamped to the view's format and put in the channels it
    // stores as gallivm does (shader/texture_border.cpp format_border), so the sampler's format member is never needed.
    f.custom_border_color.customBorderColors = VK_TRUE;
    f.custom_border_color.customBorderColorWithoutFormat = VK_TRUE;
    // A4R4G4B4 / A4B4G4R4_UNORM_PACK16: rows of the format table like B4G4R4A4 (format/support.txt), drawn, blended,
    // sampled and blitted through the packed-UNORM codec as lavapipe (B4G4R4A4 / R4G4B4A4 in gallium's names).
    f.formats_4444.formatA4R4G4B4 = VK_TRUE;
    f.formats_4444.formatA4B4G4R4 = VK_TRUE;
    // Texel buffer views at any offset aligned to one texel (or, for three-component formats, one component): the
    // view's byte offset is added to the buffer's address as it is (buffer_view.cpp), as llvmpipe adds it.
    f.texel_buffer_alignment.texelBufferAlignment = VK_TRUE;
    // Border colours go through the view's component mapping after replacing the format's channels, as gallivm
    // (shader/texture_border.cpp), so the swizzle comes from the image;
    // VkSamplerBorderColorComponentMappingCreateInfoEXT is accepted and, as in lavapipe, not needed.
    f.border_color_swizzle.borderColorSwizzle = VK_TRUE;
    f.border_color_swizzle.borderColorSwizzleFromImage = VK_TRUE;
    // Draws, dispatches and vkCmdClearAttachments read the predicate as they execute (execute.cpp
    // condition_passes), as llvmpipe. Not inherited by secondary command buffers: lavapipe 22.3.6 reports
    // inheritedConditionalRendering VK_FALSE, so no secondary may run inside it (VUID-vkCmdExecuteCommands-
    // commandBuffer-00101) and tilevk has no reference to match.
    f.conditional_rendering.conditionalRendering = VK_TRUE;
    // VK_SAMPLER_CREATE_NON_SEAMLESS_CUBE_MAP_BIT_EXT: each face filtered alone, clamped to its edges as llvmpipe
    // (shader/texture_cube.cpp non_seamless_sample).
    f.non_seamless_cube_map.nonSeamlessCubeMap = VK_TRUE;
}

// The atomics beyond Vulkan 1.0's 32-bit integer ones.
void add_atomic_features(Features& f) {
    // 32-bit float Load / Store / Exchange / OpAtomicFAddEXT on storage buffers, Workgroup memory and R32_SFLOAT
    // storage images and texel buffers (shader/translate_atomic.cpp, exec_atomic.h), exactly lavapipe's answer
    // (lvp_device.c): no 64-bit float atomics, no sparse images.
    f.atomic_float.shaderBufferFloat32Atomics = VK_TRUE;
    f.atomic_float.shaderBufferFloat32AtomicAdd = VK_TRUE;
    f.atomic_float.shaderSharedFloat32Atomics = VK_TRUE;
    f.atomic_float.shaderSharedFloat32AtomicAdd = VK_TRUE;
    f.atomic_float.shaderImageFloat32Atomics = VK_TRUE;
    f.atomic_float.shaderImageFloat32AtomicAdd = VK_TRUE;
    // OpAtomicFMinEXT / FMaxEXT on the same 32-bit floats, as LLVM 15 computes them on x86 (docs/lavapipe-rules.md
    // "Float atomics"): lavapipe 22.3's three Float32AtomicMinMax members with LLVM >= 15 (lvp_device.c), no 16- or
    // 64-bit float and no sparse member.
    f.atomic_float2.shaderBufferFloat32AtomicMinMax = VK_TRUE;
    f.atomic_float2.shaderSharedFloat32AtomicMinMax = VK_TRUE;
    f.atomic_float2.shaderImageFloat32AtomicMinMax = VK_TRUE;
    // Every 64-bit integer OpAtomic* on storage buffers (through PhysicalStorageBuffer pointers too) and Workgroup
    // memory, interpreted on register pairs (shader/translate_atomic.cpp, exec_atomic.h kAtomicWide), as lavapipe
    // reports (lvp_device.c). No image form (VK_EXT_shader_image_atomic_int64 is not offered, as in lavapipe 22.3).
    f.core.v12.shaderBufferInt64Atomics = VK_TRUE;
    f.core.v12.shaderSharedInt64Atomics = VK_TRUE;
}

// The samplers' filtering features.
void add_sampler_features(Features& f) {
    // MIRROR_CLAMP_TO_EDGE: shader/texture.cpp folds the coordinate as gallivm (lp_build_sample_wrap_*: |x| then
    // CLAMP_TO_EDGE), nearest, linear and gathers (cts texture.wrap.mirror_clamp_to_edge_*,
    // texture.float_target.mip_linear_mirror_clamp_to_edge).
    f.core.v12.samplerMirrorClampToEdge = VK_TRUE;
    // VkSamplerReductionModeCreateInfo MIN / MAX: shader/texture_reduce.h in every linear filter step as gallivm's
    // lp_build_reduce_filter (ApiSamplerExt.FilterMinmax*, cts texture.minmax.*).
    f.core.v12.samplerFilterMinmax = VK_TRUE;
    // Anisotropic samplers on 2D and 2D-array views filter as llvmpipe's elliptical filter (shader/texture_aniso.cpp,
    // docs/lavapipe-rules.md §10 "Anisotropy"; cts texture.aniso.*); on 1D, 3D and cube views they filter without
    // anisotropy, said on stderr (icd/README.md "Known differences").
    f.core10.samplerAnisotropy = VK_TRUE;
}

// The features tilevk reports, a member a line with why it holds. A deliberate twin in shape of make_limits
// (physical_device.cpp): both are lists of "struct.member = value;" with different members and values. They stay
// code rather than one generated table because each value's reason (the code that makes it true, the test that
// checks it) is written next to it; the member names themselves come from the Vulkan headers.
Features make_supported() {
    Features f;
    VkPhysicalDeviceFeatures& c = f.core10;
    c.depthClamp = VK_TRUE;      // rast/fragment clamp_depth + no near/far clipping
    c.depthBiasClamp = VK_TRUE;  // rast/geometry depth bias with clamp
    c.independentBlend = VK_TRUE;
    // Indirect and indexed draws: execute_draw.cpp reads every record (drawCount, stride, firstInstance) and
    // rast/render fetches 32-bit index values as they are (tests/icd/api_breadth_draws_test.cpp
    // IndirectDrawsWithStride).
    c.fullDrawIndexUint32 = VK_TRUE;
    c.multiDrawIndirect = VK_TRUE;
    c.drawIndirectFirstInstance = VK_TRUE;
    c.largePoints = VK_TRUE;            // rast/geometry setup_point: sizes up to 255
    c.wideLines = VK_TRUE;              // rast/geometry setup_line: rectangular lines of any width
    c.occlusionQueryPrecise = VK_TRUE;  // exact sample counts (fragment_stage.cpp), as lavapipe's
    c.pipelineStatisticsQuery = VK_TRUE;  // all eleven counters as lavapipe counts them (execute_statistics.cpp)
    c.fillModeNonSolid = VK_TRUE;       // rast/render: draw's unfilled stage (edges / corners after culling)
    c.logicOp = VK_TRUE;                // rast/fragment logic_op8 on UNORM8 targets, as lavapipe's lp_build_logicop
    c.alphaToOne = VK_TRUE;             // rast/render: alpha 1.0 after alpha to coverage (lp_state_fs.c)
    // BC1-BC7 sampled (format/texel_bc.h, texel_bptc.cpp) and copied in blocks, every format the feature requires
    // (tests/icd/transfer_bc_test.cpp FormatQueries checks them against the spec's list and lavapipe).
    c.textureCompressionBC = VK_TRUE;
    // The SRC1 factors on attachment 0 blend with the fragment output of Location 0, Index 1 (shader/
    // kSecondColorOutput), converted as the first source; such draws take the reference fragment pipeline
    // (feature.dual_src_blend.*).
    c.dualSrcBlend = VK_TRUE;
    // rast/render shade_samples: one run per sample when lavapipe's min_samples > 1 (icd/pipeline.cpp
    // per_sample_shading), SampleId, SamplePosition, Sample and Centroid inputs; cts multisample.sample_shading.*.
    c.sampleRateShading = VK_TRUE;
    // ClipDistance and CullDistance written by the vertex shader: draw's user planes in rast/geometry clip.cpp and
    // its user_cull stage (cull_distance_keep); cts clipping.clip_distance.*, clipping.cull_distance.*. A fragment
    // shader may not read them (icd/pipeline.cpp refuses it).
    c.shaderClipDistance = VK_TRUE;
    c.shaderCullDistance = VK_TRUE;
    c.multiViewport = VK_TRUE;          // 16 viewports accepted; with no viewport-index output viewport 0 is used
    // shader/ bounds-checks every buffer access against the descriptor's range (loads 0, stores and atomics dropped,
    // atomics return 0) and rast/geometry fetches vertices past their buffer as (0,0,0,1) / (0,0,0,0), as lavapipe
    // (docs/lavapipe-rules.md §12 "Buffer bounds"; api_breadth ApiRobustBufferAccess).
    c.robustBufferAccess = VK_TRUE;
    // Buffer and image stores and atomics in vertex and fragment shaders: fragment side effects only from
    // live, covered lanes, after the depth test only with EarlyFragmentTests (lavapipe's depth modes);
    // api_breadth ApiStagesStores.
    c.vertexPipelineStoresAndAtomics = VK_TRUE;
    c.fragmentStoresAndAtomics = VK_TRUE;
    // Storage images of the 23 extended formats (format/support.txt), converted as lavapipe converts them
    // (api_breadth ApiStorageImage.EveryExtendedFormat*, cts compute.image.*).
    c.shaderStorageImageExtendedFormats = VK_TRUE;
    // Cube-array views sampled through samplerCubeArray[Shadow] as llvmpipe samples them (shader/texture_cube.cpp;
    // cts texture.cube.array_*, ShaderTextureCube tests).
    c.imageCubeArray = VK_TRUE;
    // Stores through images declared without a format take the view's format (shader/ never reads the type's
    // format), as lavapipe reports (PIPE_CAP_IMAGE_STORE_FORMATTED); reads without a format are not reported there
    // (no PIPE_CAP_IMAGE_LOAD_FORMATTED in llvmpipe) and not here (api_breadth ApiStorageImage.WriteWithoutFormat*).
    c.shaderStorageImageWriteWithoutFormat = VK_TRUE;
    // Uniform and storage buffer arrays at dynamically uniform indices: shader/ carries the element in a register
    // per lane, clamped to the array as robust indexing (api_breadth ApiDynamicIndexing). The sampled and storage
    // image forms stay VK_FALSE as in lavapipe 22.3.6, which has no reference for them.
    c.shaderUniformBufferArrayDynamicIndexing = VK_TRUE;
    c.shaderStorageBufferArrayDynamicIndexing = VK_TRUE;
    // 64-bit integers and doubles: two registers per scalar, interpreted with llvmpipe's semantics (IEEE doubles
    // under the same FTZ/DAZ, shifts masked, division by 0 and out-of-range conversions as lavapipe); programs using
    // them stay in the interpreter (shader/README.md "64-bit types"; cts types.*).
    c.shaderFloat64 = VK_TRUE;
    c.shaderInt64 = VK_TRUE;
    // 8- and 16-bit integers: one register per scalar holding the value zero-extended, wrapped, sign-extended and
    // shift counts masked as llvmpipe computes its i8/i16 LLVM types; 8/16-bit values (16-bit floats too, converted
    // as LLVM's fpext/fptrunc) at their byte offsets in storage and uniform buffers and push constants
    // (shader/README.md "8- and 16-bit types"; cts types.int16.*, types.int8.*, types.storage*). As lavapipe:
    // storageInputOutput16 VK_FALSE. shaderFloat16 (half arithmetic) is not reported: lavapipe reports it on F16C
    // hosts and computes half operations in LLVM's half type, which tilevk does not model.
    c.shaderInt16 = VK_TRUE;
    f.core.v11.storageBuffer16BitAccess = VK_TRUE;
    f.core.v11.uniformAndStorageBuffer16BitAccess = VK_TRUE;
    f.core.v11.storagePushConstant16 = VK_TRUE;
    f.core.v12.storageBuffer8BitAccess = VK_TRUE;
    f.core.v12.uniformAndStorageBuffer8BitAccess = VK_TRUE;
    f.core.v12.storagePushConstant8 = VK_TRUE;
    f.core.v12.shaderInt8 = VK_TRUE;

    add_extension_features(f);
    add_atomic_features(f);
    add_sampler_features(f);
    // BaseVertex, BaseInstance, DrawIndex (the record's number within an indirect call, as lavapipe's drawid).
    f.core.v11.shaderDrawParameters = VK_TRUE;
    // execute.cpp runs a multiview subpass once per view into its layers, ViewIndex given to the shaders; there is
    // no geometry or tessellation stage, so multiviewGeometryShader / multiviewTessellationShader stay VK_FALSE.
    f.core.v11.multiview = VK_TRUE;
    f.core.v12.drawIndirectCount = VK_TRUE;  // vkCmdDraw[Indexed]IndirectCount: the count read at execution
    f.core.v12.hostQueryReset = VK_TRUE;     // vkResetQueryPool: the reset vkCmdResetQueryPool does
    f.core.v12.timelineSemaphore = VK_TRUE;  // sync.cpp, queue_scheduler.h: wait-before-signal on the queue's worker
    // std430 uniform blocks: shader/ takes offsets and strides from the decorations (ApiSmallExtensions).
    f.core.v12.uniformBufferStandardLayout = VK_TRUE;
    f.core.v12.scalarBlockLayout = VK_TRUE;  // the same, with scalar alignment (ApiSmallExtensions.ScalarBlockLayout*)
    // framebuffer.cpp, command_buffer.cpp: the views of VkRenderPassAttachmentBeginInfo replace the framebuffer's.
    f.core.v12.imagelessFramebuffer = VK_TRUE;
    // Image layouts are not modelled (one layout for all; barriers move no bytes), so depth-only and stencil-only
    // layouts and the separate stencil layouts of render pass 2 are as good as any (ApiVulkan12).
    f.core.v12.separateDepthStencilLayouts = VK_TRUE;
    // OpGroupNonUniformBroadcast reads its id from a register per subgroup (exec_subgroup.h op_sg_broadcast), so a
    // dynamically uniform id (SPIR-V 1.5) works as a constant one does.
    f.core.v12.subgroupBroadcastDynamicId = VK_TRUE;
    // Subgroup operations take every type the device supports: 8- and 16-bit values are one register (a
    // zero-extended value, which Broadcast / BroadcastFirst / AllEqual move and compare as it is; the other
    // operations on them are refused by name, shader/translate_narrow.cpp); 64-bit values are two registers, which
    // the subgroup operations move word by word (shader/translate_subgroup.cpp).
    f.core.v12.shaderSubgroupExtendedTypes = VK_TRUE;
    // The Vulkan memory model's operands, scopes and semantics order nothing more than tilevk already does: a
    // workgroup runs on one thread, buffer atomics are sequentially consistent (shader/README.md "Compute").
    // Availability/visibility chains (optional) are not reported: no test tells them apart.
    f.core.v12.vulkanMemoryModel = VK_TRUE;
    f.core.v12.vulkanMemoryModelDeviceScope = VK_TRUE;
    // PhysicalStorageBuffer pointers are host addresses, read and written by the interpreter after a lookup in the
    // allocations made with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT (shader/translate_pointer.cpp, exec_pointer.h;
    // ApiBufferDeviceAddress). No capture/replay (addresses are wherever malloc puts them); one device per group.
    f.core.v12.bufferDeviceAddress = VK_TRUE;
    f.core.v13.privateData = VK_TRUE;  // private_data.cpp
    // Storage image loads and texel fetches outside the view give (0, 0, 0, 0), alpha 1 for formats without alpha,
    // stores outside do nothing (shader/texture.cpp, lavapipe's rules: docs/lavapipe-rules.md §9) — the spec's
    // texel replacement, with robustImageAccess enabled or not (ApiStorageImage.RobustImageAccessFeature).
    f.core.v13.robustImageAccess = VK_TRUE;
    // Inline uniform blocks: bytes inside the descriptor set, read as a uniform buffer (descriptor_pool.cpp,
    // execute_draw.cpp). Not after bind: descriptor indexing (which that needs) is not reported.
    f.core.v13.inlineUniformBlock = VK_TRUE;
    // OpTerminateInvocation ends the invocation as OpKill does; OpDemoteToHelperInvocation drops the pixel's writes
    // and keeps it running as a helper for its quad's derivatives (shader/translate_control.cpp, translate_ops.cpp).
    f.core.v13.shaderTerminateInvocation = VK_TRUE;
    f.core.v13.shaderDemoteToHelperInvocation = VK_TRUE;
    // shader/: Workgroup memory is zeroed before every workgroup, so null initializers hold (cp_zero_init.comp).
    f.core.v13.shaderZeroInitializeWorkgroupMemory = VK_TRUE;
    // One subgroup size, 8: required sizes and full subgroups are checked at pipeline creation (pipeline.cpp).
    f.core.v13.subgroupSizeControl = VK_TRUE;
    f.core.v13.computeFullSubgroups = VK_TRUE;
    // OpSDot/OpUDot/OpSUDot (+AccSat) on 32-bit vectors and packed 4x8-bit scalars (shader/translate_dot.cpp);
    // none is "accelerated" (every VkPhysicalDeviceShaderIntegerDotProductProperties member VK_FALSE).
    f.core.v13.shaderIntegerDotProduct = VK_TRUE;
    f.core.v13.synchronization2 = VK_TRUE;              // command_buffer2.cpp, vkQueueSubmit2: the 1.0 forms
    f.core.v13.pipelineCreationCacheControl = VK_TRUE;  // pipeline.cpp: FAIL_ON_PIPELINE_COMPILE_REQUIRED, EARLY_RETURN
    // dynamic_rendering.cpp: each vkCmdBeginRendering becomes a one-subpass render pass run as vkCmdBeginRenderPass.
    f.core.v13.dynamicRendering = VK_TRUE;
    // VK_KHR_maintenance4 (resources2.cpp, README "Extensions"): requirements of objects not yet made from the code
    // that answers for made ones; no pipeline layout is kept after use; LocalSizeId; wider vertex outputs.
    f.core.v13.maintenance4 = VK_TRUE;
    // VK_EXT_robustness2: per-word bounds of the exact range (robustBufferAccess above); a null descriptor is an empty
    // one, read as llvmpipe's format-NONE view (docs/lavapipe-rules.md "Null descriptors"; cts compute.robustness2.*).
    f.robustness2.robustBufferAccess2 = VK_TRUE;
    f.robustness2.robustImageAccess2 = VK_TRUE;
    f.robustness2.nullDescriptor = VK_TRUE;
    return f;
}

}  // namespace

Features::Features() {
    init(index_type_uint8, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_INDEX_TYPE_UINT8_FEATURES_EXT);
    init(list_restart, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PRIMITIVE_TOPOLOGY_LIST_RESTART_FEATURES_EXT);
    init(depth_clip_control, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_CONTROL_FEATURES_EXT);
    init(extended_dynamic_state, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_FEATURES_EXT);
    init(extended_dynamic_state2, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_2_FEATURES_EXT);
    init(vertex_attribute_divisor, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VERTEX_ATTRIBUTE_DIVISOR_FEATURES_EXT);
    init(color_write_enable, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_COLOR_WRITE_ENABLE_FEATURES_EXT);
    init(multi_draw, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTI_DRAW_FEATURES_EXT);
    init(provoking_vertex, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROVOKING_VERTEX_FEATURES_EXT);
    init(depth_clip_enable, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DEPTH_CLIP_ENABLE_FEATURES_EXT);
    init(line_rasterization, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT);
    init(atomic_float, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT);
    init(atomic_float2, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_2_FEATURES_EXT);
    init(custom_border_color, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_CUSTOM_BORDER_COLOR_FEATURES_EXT);
    init(formats_4444, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_4444_FORMATS_FEATURES_EXT);
    init(texel_buffer_alignment, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TEXEL_BUFFER_ALIGNMENT_FEATURES_EXT);
    init(border_color_swizzle, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BORDER_COLOR_SWIZZLE_FEATURES_EXT);
    init(vertex_input_dynamic_state, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VERTEX_INPUT_DYNAMIC_STATE_FEATURES_EXT);
    init(extended_dynamic_state3, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_3_FEATURES_EXT);
    init(conditional_rendering, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_CONDITIONAL_RENDERING_FEATURES_EXT);
    init(non_seamless_cube_map, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_NON_SEAMLESS_CUBE_MAP_FEATURES_EXT);
    init(robustness2, VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT);
}

VkBaseOutStructure* Features::extension_struct(VkStructureType t) {
    VkBaseOutStructure* all[] = {reinterpret_cast<VkBaseOutStructure*>(&index_type_uint8),
                                 reinterpret_cast<VkBaseOutStructure*>(&list_restart),
                                 reinterpret_cast<VkBaseOutStructure*>(&depth_clip_control),
                                 reinterpret_cast<VkBaseOutStructure*>(&extended_dynamic_state),
                                 reinterpret_cast<VkBaseOutStructure*>(&extended_dynamic_state2),
                                 reinterpret_cast<VkBaseOutStructure*>(&vertex_attribute_divisor),
                                 reinterpret_cast<VkBaseOutStructure*>(&color_write_enable),
                                 reinterpret_cast<VkBaseOutStructure*>(&multi_draw),
                                 reinterpret_cast<VkBaseOutStructure*>(&provoking_vertex),
                                 reinterpret_cast<VkBaseOutStructure*>(&depth_clip_enable),
                                 reinterpret_cast<VkBaseOutStructure*>(&line_rasterization),
                                 reinterpret_cast<VkBaseOutStructure*>(&atomic_float),
                                 reinterpret_cast<VkBaseOutStructure*>(&atomic_float2),
                                 reinterpret_cast<VkBaseOutStructure*>(&custom_border_color),
                                 reinterpret_cast<VkBaseOutStructure*>(&formats_4444),
                                 reinterpret_cast<VkBaseOutStructure*>(&texel_buffer_alignment),
                                 reinterpret_cast<VkBaseOutStructure*>(&border_color_swizzle),
                                 reinterpret_cast<VkBaseOutStructure*>(&vertex_input_dynamic_state),
                                 reinterpret_cast<VkBaseOutStructure*>(&extended_dynamic_state3),
                                 reinterpret_cast<VkBaseOutStructure*>(&conditional_rendering),
                                 reinterpret_cast<VkBaseOutStructure*>(&non_seamless_cube_map),
                                 reinterpret_cast<VkBaseOutStructure*>(&robustness2)};
    for (VkBaseOutStructure* s : all)
        if (s->sType == t) return s;
    return nullptr;
}

const VkBaseOutStructure* Features::extension_struct(VkStructureType t) const {
    return const_cast<Features*>(this)->extension_struct(t);
}

const Features& supported_features() {
    static const Features kSupported = make_supported();
    return kSupported;
}

void write_feature_struct(const Features& from, VkBaseOutStructure* s) {
    if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2) {
        reinterpret_cast<VkPhysicalDeviceFeatures2*>(s)->features = from.core10;
        return;
    }
    const FeatureStruct* fs = find_feature_struct(s->sType);
    if (fs == nullptr) return;  // not a feature struct vk.xml knows: skipped
    if (const void* core = core_struct(from.core, s->sType)) {
        copy_body(s, core, fs->size);
    } else if (read_core_features(from.core, s)) {
        // a struct promoted into Vulkan 1.1-1.3: filled from the Vulkan1x struct
    } else if (const VkBaseOutStructure* ext = from.extension_struct(s->sType)) {
        copy_body(s, ext, fs->size);
    } else {
        for (uint32_t m = 0; m < fs->count; ++m) {
            const VkBool32 no = VK_FALSE;
            std::memcpy(reinterpret_cast<char*>(s) + fs->offsets[m], &no, sizeof no);
        }
    }
}

namespace {

VkBool32 member(const void* s, size_t offset) {
    VkBool32 v;
    std::memcpy(&v, static_cast<const char*>(s) + offset, sizeof v);
    return v;
}

// The first member `requested` sets that `supported` does not, or -1.
int first_unsupported(const FeatureStruct& fs, const void* requested, const void* supported) {
    for (uint32_t m = 0; m < fs.count; ++m)
        if (member(requested, fs.offsets[m]) && !member(supported, fs.offsets[m])) return int(m);
    return -1;
}

VkResult check_features10(const VkPhysicalDeviceFeatures& want, VkPhysicalDeviceFeatures* enabled) {
    const FeatureStruct& fs = features10();
    const int bad = first_unsupported(fs, &want, &supported_features().core10);
    if (bad >= 0) {
        return fail(VK_ERROR_FEATURE_NOT_PRESENT,
                    "vkCreateDevice: VkPhysicalDeviceFeatures::%s is not supported by tilevk", fs.members[bad]);
    }
    auto* out = reinterpret_cast<VkBool32*>(enabled);
    const auto* in = reinterpret_cast<const VkBool32*>(&want);
    for (size_t i = 0; i < sizeof want / sizeof(VkBool32); ++i) out[i] |= in[i];
    return VK_SUCCESS;
}

// OR-s the VkBool32 members of `s` into the same struct inside `enabled`.
void merge(const FeatureStruct& fs, const VkBaseInStructure* s, Features* enabled) {
    void* target = core_struct(enabled->core, s->sType);
    if (target == nullptr) target = enabled->extension_struct(s->sType);
    if (target == nullptr) {
        merge_core_features(reinterpret_cast<const VkBaseOutStructure*>(s), &enabled->core);
        return;  // promoted structs are merged into the Vulkan1x struct; unknown ones have nothing set
    }
    for (uint32_t m = 0; m < fs.count; ++m) {
        const VkBool32 v = member(target, fs.offsets[m]) | member(s, fs.offsets[m]);
        std::memcpy(static_cast<char*>(target) + fs.offsets[m], &v, sizeof v);
    }
}

}  // namespace

VkResult enable_features(const VkDeviceCreateInfo& ci, Features* enabled) {
    *enabled = Features{};
    if (ci.pEnabledFeatures != nullptr) {
        if (VkResult r = check_features10(*ci.pEnabledFeatures, &enabled->core10); r != VK_SUCCESS) return r;
    }
    const Features& supported = supported_features();
    std::vector<unsigned char> answer;
    for (auto* s = static_cast<const VkBaseInStructure*>(ci.pNext); s != nullptr; s = s->pNext) {
        if (s->sType == VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2) {
            const auto& f2 = *reinterpret_cast<const VkPhysicalDeviceFeatures2*>(s);
            if (VkResult r = check_features10(f2.features, &enabled->core10); r != VK_SUCCESS) return r;
            continue;
        }
        const FeatureStruct* fs = find_feature_struct(s->sType);
        if (fs == nullptr) continue;  // not a feature struct: what it asks for is checked where it is used
        // tilevk's answer for this struct, written exactly as vkGetPhysicalDeviceFeatures2 would write it.
        answer.assign(fs->size, 0);
        auto* mine = reinterpret_cast<VkBaseOutStructure*>(answer.data());
        mine->sType = s->sType;
        write_feature_struct(supported, mine);
        const int bad = first_unsupported(*fs, s, mine);
        if (bad >= 0) {
            return fail(VK_ERROR_FEATURE_NOT_PRESENT, "vkCreateDevice: %s::%s is not supported by tilevk", fs->name,
                        fs->members[bad]);
        }
        merge(*fs, s, enabled);
    }
    return VK_SUCCESS;
}

}  // namespace tilevk::icd
