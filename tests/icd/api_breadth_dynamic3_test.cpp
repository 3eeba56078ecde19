// VK_EXT_vertex_input_dynamic_state and VK_EXT_extended_dynamic_state3 (suite ApiDynamicState3): each runs on tilevk
// and lavapipe with the extensions and features enabled and the validation layer on; the images are compared byte
// for byte and checked against what the states say must be written. The cts group dynamic.vertex_input_eds3.*
// covers the states over whole scenes.
#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

class ApiDynamicState3 : public ApiBreadth {};

// Both extensions with every feature tilevk reports (validation checks each command against its feature).
struct Features3 {
    VkPhysicalDeviceExtendedDynamicState2FeaturesEXT eds2{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_2_FEATURES_EXT};
    VkPhysicalDeviceVertexInputDynamicStateFeaturesEXT vi{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VERTEX_INPUT_DYNAMIC_STATE_FEATURES_EXT, &eds2};
    VkPhysicalDeviceExtendedDynamicState3FeaturesEXT eds3{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_3_FEATURES_EXT, &vi};
    Features3() {
        vi.vertexInputDynamicState = VK_TRUE;
        eds2.extendedDynamicState2 = eds2.extendedDynamicState2LogicOp = VK_TRUE;  // the logic op itself
        eds3.extendedDynamicState3PolygonMode = eds3.extendedDynamicState3LogicOpEnable = VK_TRUE;
        eds3.extendedDynamicState3ColorBlendEnable = eds3.extendedDynamicState3ColorBlendEquation = VK_TRUE;
        eds3.extendedDynamicState3ColorWriteMask = VK_TRUE;
    }
};
const std::vector<const char*> kExtensions = {VK_EXT_EXTENDED_DYNAMIC_STATE_2_EXTENSION_NAME,
                                              VK_EXT_VERTEX_INPUT_DYNAMIC_STATE_EXTENSION_NAME,
                                              VK_EXT_EXTENDED_DYNAMIC_STATE_3_EXTENSION_NAME};

template <class F>
F proc(Kit& k, const char* name) {
    F f = reinterpret_cast<F>(vkGetDeviceProcAddr(k.d, name));
    EXPECT_NE(f, nullptr) << name;
    return f;
}

VkVertexInputBindingDescription2EXT binding2(uint32_t binding, uint32_t stride, VkVertexInputRate rate) {
    return {VK_STRUCTURE_TYPE_VERTEX_INPUT_BINDING_DESCRIPTION_2_EXT, nullptr, binding, stride, rate, 1};
}
VkVertexInputAttributeDescription2EXT attribute2(uint32_t location, uint32_t binding, VkFormat f, uint32_t offset) {
    return {VK_STRUCTURE_TYPE_VERTEX_INPUT_ATTRIBUTE_DESCRIPTION_2_EXT, nullptr, location, binding, f, offset};
}

// vkCmdSetVertexInputEXT on a pipeline made without vertex input: three draws with three layouts (the plain
// Vertex; colour read as R8G8B8A8_UNORM from the float bits; stride 64, every other vertex, colour from an
// instance-rate binding), a static pipeline between them drawing with its own layout. A driver that ignored the
// dynamic layout would draw the first and last triangles from no attributes at all.
TEST_F(ApiDynamicState3, VertexInputAcrossBindsAndLayouts) {
    Features3 f;
    auto dev = device_pair(kExtensions, &f.eds3);
    ASSERT_TRUE(dev->ok());
    const Bytes b = both_on(dev->tilevk, dev->lavapipe, [](Kit& k) {
        auto set_input = proc<PFN_vkCmdSetVertexInputEXT>(k, "vkCmdSetVertexInputEXT");
        Target t = target(k);
        Pipe dyn;
        dyn.rp = t.rp;
        dyn.bindings = {};
        dyn.attrs = {};
        dyn.dynamic = {VK_DYNAMIC_STATE_VERTEX_INPUT_EXT};
        VkPipeline pd = k.pipeline(dyn);
        Pipe fixed;
        fixed.rp = t.rp;
        VkPipeline pf = k.pipeline(fixed);
        Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        EXPECT_EQ(k.run([&](VkCommandBuffer c) {
            begin_pass(c, t.rp, t.fb, 32, 32, {clear_color(0, 0, 0.25f, 1)});
            const VkDeviceSize zero = 0;
            const VkBuffer bufs[2] = {vb.buffer, vb.buffer};
            const VkDeviceSize offsets[2] = {0, 0};
            vkCmdBindVertexBuffers(c, 0, 2, bufs, offsets);
            set_input(c, 0, nullptr, 0, nullptr);  // replaced before the draw
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pd);
            const VkVertexInputBindingDescription2EXT plain = binding2(0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX);
            const VkVertexInputAttributeDescription2EXT a1[2] = {
                attribute2(0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0),
                attribute2(1, 0, VK_FORMAT_R8G8B8A8_UNORM, 16 + 4)};  // colour.g's float bits as four bytes
            set_input(c, 1, &plain, 2, a1);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pf);
            vkCmdBindVertexBuffers(c, 0, 1, &vb.buffer, &zero);
            vkCmdDraw(c, 3, 1, 3, 0);
            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pd);
            // Vertices 0, 2, 4 (stride 64); colour of instance 0 from binding 1 (the first vertex's colour).
            const VkVertexInputBindingDescription2EXT b2[2] = {
                binding2(1, sizeof(Vertex), VK_VERTEX_INPUT_RATE_INSTANCE),
                binding2(0, 2 * sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX)};
            const VkVertexInputAttributeDescription2EXT a2[2] = {attribute2(1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, 16),
                                                                 attribute2(0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0)};
            vkCmdBindVertexBuffers(c, 0, 2, bufs, offsets);
            set_input(c, 2, b2, 2, a2);
            vkCmdDraw(c, 3, 1, 0, 0);
            vkCmdEndRenderPass(c);
        }),
                  VK_SUCCESS);
        return k.read(t.image.image, 32, 32, 4);
    });
    ASSERT_EQ(b.size(), 32u * 32 * 4);
    size_t drawn = 0;
    for (uint32_t i = 0; i < 32 * 32; ++i) drawn += std::memcmp(b.data() + i * 4, "\x00\x00\x40\xff", 4) != 0;
    EXPECT_GT(drawn, 300u);  // three triangles over much of the target, not the clear
}

// Two attachments (ab_mrt.frag) with blend enables, equations and write masks per attachment and the logic op
// enable, all dynamic, on a pipeline made with other values; two frames on the same pipeline. Frame 0: attachment
// 0 adds (ONE, ONE) onto the clear, attachment 1 blends off, writing red and green only. Frame 1: the logic op
// (XOR, static) on both, attachment 0 writing red and alpha only; polygon mode LINE.
TEST_F(ApiDynamicState3, PerAttachmentBlendWriteMaskLogicOp) {
    Features3 f;
    VkPhysicalDeviceFeatures core{};
    core.logicOp = core.fillModeNonSolid = VK_TRUE;
    Device t(tilevk_->physical(), &core, kExtensions, &f.eds3), l(lavapipe_->physical(), &core, kExtensions, &f.eds3);
    ASSERT_TRUE(t.ok() && l.ok());
    const Bytes b = both_on(t, l, [](Kit& k) {
        auto enable = proc<PFN_vkCmdSetColorBlendEnableEXT>(k, "vkCmdSetColorBlendEnableEXT");
        auto equation = proc<PFN_vkCmdSetColorBlendEquationEXT>(k, "vkCmdSetColorBlendEquationEXT");
        auto mask = proc<PFN_vkCmdSetColorWriteMaskEXT>(k, "vkCmdSetColorWriteMaskEXT");
        auto logic = proc<PFN_vkCmdSetLogicOpEnableEXT>(k, "vkCmdSetLogicOpEnableEXT");
        auto polygon = proc<PFN_vkCmdSetPolygonModeEXT>(k, "vkCmdSetPolygonModeEXT");
        const VkFormat fmt = VK_FORMAT_R8G8B8A8_UNORM;
        Device::Image img[2] = {
            k.image(fmt, 32, 32, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT),
            k.image(fmt, 32, 32, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT)};
        static const VkAttachmentReference refs[2] = {{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                                      {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
        VkSubpassDescription sub = subpass(&refs[0]);
        sub.colorAttachmentCount = 2;
        const auto att = attachment(fmt, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE);
        VkRenderPass rp = k.render_pass({att, att}, {sub});
        VkFramebuffer fb = k.framebuffer(rp,
                                         {k.view(img[0].image, fmt, VK_IMAGE_ASPECT_COLOR_BIT),
                                          k.view(img[1].image, fmt, VK_IMAGE_ASPECT_COLOR_BIT)},
                                         32, 32);
        Pipe p;
        p.fs = SPV(ab_mrt_frag);
        p.rp = rp;
        p.color_count = 2;
        VkPipelineColorBlendAttachmentState other =
            blend_add(VK_BLEND_FACTOR_ZERO, VK_BLEND_FACTOR_SRC_ALPHA, VK_BLEND_FACTOR_ZERO, VK_BLEND_FACTOR_ONE);
        other.colorWriteMask = 0x4;
        p.blend = {other, other};
        p.dynamic = {VK_DYNAMIC_STATE_COLOR_BLEND_ENABLE_EXT, VK_DYNAMIC_STATE_COLOR_BLEND_EQUATION_EXT,
                     VK_DYNAMIC_STATE_COLOR_WRITE_MASK_EXT,   VK_DYNAMIC_STATE_LOGIC_OP_ENABLE_EXT,
                     VK_DYNAMIC_STATE_POLYGON_MODE_EXT,       VK_DYNAMIC_STATE_LOGIC_OP_EXT};
        VkPipeline pipe = k.pipeline(p);
        auto set_logic_op = proc<PFN_vkCmdSetLogicOpEXT>(k, "vkCmdSetLogicOpEXT");
        Device::Buffer vb = k.buffer_of(kBothTriangles, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        Bytes out;
        for (int frame = 0; frame < 2; ++frame) {
            EXPECT_EQ(k.run([&](VkCommandBuffer c) {
                begin_pass(c, rp, fb, 32, 32,
                           {clear_color(0.25f, 0.5f, 0.75f, 0.5f), clear_color(0.25f, 0.5f, 0.75f, 0.5f)});
                vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                bind_vertices(c, vb);
                const VkBool32 enables[2] = {frame == 0, VK_FALSE};
                enable(c, 0, 2, enables);
                const VkColorBlendEquationEXT add = {VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE, VK_BLEND_OP_ADD,
                                                     VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE, VK_BLEND_OP_ADD};
                equation(c, 0, 1, &add);
                const VkColorComponentFlags masks[2] = {frame == 0 ? 0xFu : 0x9u, frame == 0 ? 0x3u : 0xFu};
                mask(c, 0, 2, masks);
                logic(c, frame == 1);
                set_logic_op(c, VK_LOGIC_OP_XOR);
                polygon(c, frame == 1 ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL);
                vkCmdDraw(c, 6, 1, 0, 0);
                vkCmdEndRenderPass(c);
            }),
                      VK_SUCCESS);
            out = concat({out, k.read(img[0].image, 32, 32, 4), k.read(img[1].image, 32, 32, 4)});
        }
        return out;
    });
    ASSERT_EQ(b.size(), 4u * 32 * 32 * 4);
    // The clear (0.25, 0.5, 0.75, 0.5) as UNORM8 bytes.
    const uint8_t clear[4] = {64, 128, 191, 128};
    auto image = [&b](int frame, int a) { return b.data() + size_t(frame * 2 + a) * 32 * 32 * 4; };
    size_t wrong = 0, changed = 0;
    for (uint32_t i = 0; i < 32 * 32; ++i) {
        const uint8_t* a1 = image(0, 1) + i * 4;
        wrong += a1[2] != clear[2] || a1[3] != clear[3];  // frame 0, attachment 1: blue and alpha kept
        const uint8_t* a0 = image(1, 0) + i * 4;
        wrong += a0[1] != clear[1] || a0[2] != clear[2];  // frame 1, attachment 0: green and blue kept
        const uint8_t* f0 = image(0, 0) + i * 4;
        if (std::memcmp(f0, clear, 4) != 0) wrong += f0[0] < clear[0] || f0[1] < clear[1] || f0[2] < clear[2];
        changed += std::memcmp(f0, clear, 4) != 0;
    }
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(changed, 200u);  // the additive blend drew the two triangles
}

// What both extensions report: tilevk's extended dynamic state 3 members are lavapipe's but the three it names as
// not supported (icd/README.md), and dynamicPrimitiveTopologyUnrestricted is lavapipe's VK_TRUE.
TEST_F(ApiDynamicState3, ReportedAsLavapipeButThree) {
    auto query = [](VkPhysicalDevice pd) {
        Features3 f;
        VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f.eds3};
        vkGetPhysicalDeviceFeatures2(pd, &f2);
        VkPhysicalDeviceExtendedDynamicState3PropertiesEXT p{
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTENDED_DYNAMIC_STATE_3_PROPERTIES_EXT};
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &p};
        vkGetPhysicalDeviceProperties2(pd, &p2);
        return std::make_tuple(f.eds3, f.vi.vertexInputDynamicState, p.dynamicPrimitiveTopologyUnrestricted);
    };
    auto [t, tvi, tp] = query(tilevk_->physical());
    auto [l, lvi, lp] = query(lavapipe_->physical());
    EXPECT_EQ(tvi, VK_TRUE);
    EXPECT_EQ(tvi, lvi);
    EXPECT_EQ(tp, lp);
    EXPECT_EQ(t.extendedDynamicState3TessellationDomainOrigin, VK_FALSE);
    EXPECT_EQ(t.extendedDynamicState3RasterizationSamples, VK_FALSE);
    EXPECT_EQ(t.extendedDynamicState3AlphaToOneEnable, VK_FALSE);
    t.extendedDynamicState3AlphaToOneEnable = l.extendedDynamicState3AlphaToOneEnable;
    t.extendedDynamicState3TessellationDomainOrigin = l.extendedDynamicState3TessellationDomainOrigin;
    t.extendedDynamicState3RasterizationSamples = l.extendedDynamicState3RasterizationSamples;
    const size_t offset =
        offsetof(VkPhysicalDeviceExtendedDynamicState3FeaturesEXT, extendedDynamicState3TessellationDomainOrigin);
    EXPECT_EQ(std::memcmp(reinterpret_cast<const uint8_t*>(&t) + offset, reinterpret_cast<const uint8_t*>(&l) + offset,
                          sizeof t - offset),
              0);
}

}  // namespace
}  // namespace tilevk::test::breadth
