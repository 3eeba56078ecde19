#include "compute_vk.h"

#include <chrono>
#include <cstring>
#include <functional>
#include <stdexcept>

#include "frame_timing.h"
#include "glsl.hpp"

namespace tilevk::bench {
namespace {

using cts::vk_check;

constexpr uint32_t kSaxpyN = 1u << 20, kHistN = 1u << 20, kHistPerInvocation = 16, kMat = 512;

// Every input is a small integer or half, so each product and sum is exact in float: the result bytes do not
// depend on whether a driver fuses a * x + y (the two drivers' hashes must agree).
const char* kSaxpy =
    "#version 450\nlayout(local_size_x=64) in;\n"
    "layout(push_constant) uniform P { float a; };\n"
    "layout(std430, binding=0) readonly buffer X { float x[]; };\n"
    "layout(std430, binding=1) readonly buffer Y { float y[]; };\n"
    "layout(std430, binding=2) writeonly buffer Z { float z[]; };\n"
    "void main() { uint i = gl_GlobalInvocationID.x; z[i] = a * x[i] + y[i]; }\n";
// 256 bins per workgroup in shared memory, added into the result once per workgroup.
const char* kHistogram =
    "#version 450\nlayout(local_size_x=256) in;\n"
    "shared uint bins[256];\n"
    "layout(std430, binding=0) readonly buffer D { uint d[]; };\n"
    "layout(std430, binding=1) buffer H { uint h[256]; };\n"
    "void main() { uint l = gl_LocalInvocationIndex, base = gl_WorkGroupID.x * 256u * 16u;\n"
    "  bins[l] = 0u; barrier();\n"
    "  for (uint k = 0u; k < 16u; ++k) atomicAdd(bins[d[base + k * 256u + l] & 255u], 1u);\n"
    "  barrier(); atomicAdd(h[l], bins[l]); }\n";
const char* kMatmul =
    "#version 450\nlayout(local_size_x=16, local_size_y=16) in;\n"
    "shared float ta[16][16];\nshared float tb[16][16];\n"
    "layout(std430, binding=0) readonly buffer A { float a[]; };\n"
    "layout(std430, binding=1) readonly buffer B { float b[]; };\n"
    "layout(std430, binding=2) writeonly buffer C { float c[]; };\n"
    "void main() { uint row = gl_GlobalInvocationID.y, col = gl_GlobalInvocationID.x;\n"
    "  uint ly = gl_LocalInvocationID.y, lx = gl_LocalInvocationID.x; float acc = 0.0;\n"
    "  for (uint t = 0u; t < 512u; t += 16u) {\n"
    "    ta[ly][lx] = a[row * 512u + t + lx]; tb[ly][lx] = b[(t + ly) * 512u + col];\n"
    "    barrier();\n"
    "    for (uint k = 0u; k < 16u; ++k) acc += ta[ly][k] * tb[k][lx];\n"
    "    barrier();\n"
    "  }\n"
    "  c[row * 512u + col] = acc; }\n";

struct Kernel {
    const char* name;
    const char* description;
    uint32_t width, height;  // the problem size the table shows
    const char* glsl;
    uint32_t groups[2];
    std::vector<std::vector<uint32_t>> (*inputs)();  // the input buffers' words; the result buffer follows them
    uint32_t result_words;
    bool reset_result;  // the kernel accumulates into the result: vkCmdFillBuffer(0) first, every frame
    float push;
};

uint32_t fbits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

const Kernel kKernels[] = {
    {"compute_saxpy",
     "SAXPY z = a x + y over 1M floats, 64 invocations per workgroup",
     kSaxpyN,
     1,
     kSaxpy,
     {kSaxpyN / 64, 1},
     [] {
         std::vector<uint32_t> x(kSaxpyN), y(kSaxpyN);
         for (uint32_t i = 0; i < kSaxpyN; ++i) {
             x[i] = fbits(float(i % 1024) * 0.5f);
             y[i] = fbits(float(i % 7));
         }
         return std::vector<std::vector<uint32_t>>{x, y};
     },
     kSaxpyN,
     false,
     2.5f},
    {"compute_histogram256",
     "256-bin histogram of 1M values: shared-memory bins per workgroup of 256, atomic adds into the result",
     kHistN,
     1,
     kHistogram,
     {kHistN / 256 / kHistPerInvocation, 1},
     [] {
         std::vector<uint32_t> d(kHistN);
         uint32_t s = 12345;
         for (uint32_t& v : d) {
             s = s * 1664525u + 1013904223u;
             v = (s >> 8) ^ (s >> 17);  // skewed bins
         }
         return std::vector<std::vector<uint32_t>>{d};
     },
     256,
     true,
     0.0f},
    {"compute_matmul512",
     "512x512 float matrix product, 16x16 tiles in shared memory",
     kMat,
     kMat,
     kMatmul,
     {kMat / 16, kMat / 16},
     [] {
         std::vector<uint32_t> a(kMat * kMat), b(kMat * kMat);
         for (uint32_t i = 0; i < kMat * kMat; ++i) {
             a[i] = fbits(float(int(i * 7 % 9) - 4));
             b[i] = fbits(float(int(i * 5 % 11) - 5));
         }
         return std::vector<std::vector<uint32_t>>{a, b};
     },
     kMat* kMat,
     false,
     0.0f},
};

const Kernel& kernel(const std::string& name) {
    for (const Kernel& k : kKernels)
        if (name == k.name) return k;
    throw std::runtime_error("unknown compute scene '" + name + "'");
}

}  // namespace

std::vector<std::string> compute_scene_names() {
    std::vector<std::string> out;
    for (const Kernel& k : kKernels) out.emplace_back(k.name);
    return out;
}
bool is_compute_scene(const std::string& name) {
    for (const Kernel& k : kKernels)
        if (name == k.name) return true;
    return false;
}
std::string compute_scene_description(const std::string& name) {
    return kernel(name).description;
}
void compute_scene_size(const std::string& name, uint32_t& width, uint32_t& height) {
    width = kernel(name).width;
    height = kernel(name).height;
}

struct ComputeOnDevice::Impl {
    const cts::DeviceContext* c = nullptr;
    const Kernel* k = nullptr;
    std::vector<std::function<void()>> undo;  // destroyed in reverse order
    struct Buf {
        VkBuffer buffer;
        void* mapped;
        VkDeviceSize size;
    };
    std::vector<Buf> buffers;  // inputs, then the result
    VkDescriptorSetLayout dsl = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkCommandBuffer cb = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    double cold_ms = 0, record_ms = 0;

    ~Impl() {
        if (c) vkQueueWaitIdle(c->queue);
        for (auto it = undo.rbegin(); it != undo.rend(); ++it) (*it)();
    }
    VkDevice dev() const { return c->device; }
    Buf buffer(const std::vector<uint32_t>& words, VkDeviceSize size);
    void descriptors();
    void record();
};

// A host-visible, coherent, mapped storage buffer (both drivers keep memory on the CPU: no staging copies).
ComputeOnDevice::Impl::Buf ComputeOnDevice::Impl::buffer(const std::vector<uint32_t>& words, VkDeviceSize size) {
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = size;
    ci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    Buf b{VK_NULL_HANDLE, nullptr, size};
    vk_check(vkCreateBuffer(dev(), &ci, nullptr, &b.buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev(), b.buffer, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex =
        c->memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    VkDeviceMemory mem;
    if (VkResult r = vkAllocateMemory(dev(), &ai, nullptr, &mem); r != VK_SUCCESS) {
        vkDestroyBuffer(dev(), b.buffer, nullptr);
        vk_check(r, "vkAllocateMemory");
    }
    undo.push_back([d = dev(), mem] { vkFreeMemory(d, mem, nullptr); });
    undo.push_back([d = dev(), buf = b.buffer] { vkDestroyBuffer(d, buf, nullptr); });
    vk_check(vkBindBufferMemory(dev(), b.buffer, mem, 0), "vkBindBufferMemory");
    vk_check(vkMapMemory(dev(), mem, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
    std::memset(b.mapped, 0, size);
    if (!words.empty()) std::memcpy(b.mapped, words.data(), words.size() * 4);
    return b;
}

void ComputeOnDevice::Impl::descriptors() {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (uint32_t i = 0; i < buffers.size(); ++i)
        bindings.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = uint32_t(bindings.size());
    lci.pBindings = bindings.data();
    vk_check(vkCreateDescriptorSetLayout(dev(), &lci, nullptr, &dsl), "vkCreateDescriptorSetLayout");
    undo.push_back([d = dev(), l = dsl] { vkDestroyDescriptorSetLayout(d, l, nullptr); });
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, 4};
    VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pci.setLayoutCount = 1;
    pci.pSetLayouts = &dsl;
    pci.pushConstantRangeCount = 1;
    pci.pPushConstantRanges = &range;
    vk_check(vkCreatePipelineLayout(dev(), &pci, nullptr, &layout), "vkCreatePipelineLayout");
    undo.push_back([d = dev(), l = layout] { vkDestroyPipelineLayout(d, l, nullptr); });
    VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, uint32_t(buffers.size())};
    VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpci.maxSets = 1;
    dpci.poolSizeCount = 1;
    dpci.pPoolSizes = &ps;
    VkDescriptorPool pool;
    vk_check(vkCreateDescriptorPool(dev(), &dpci, nullptr, &pool), "vkCreateDescriptorPool");
    undo.push_back([d = dev(), pool] { vkDestroyDescriptorPool(d, pool, nullptr); });
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &dsl;
    vk_check(vkAllocateDescriptorSets(dev(), &ai, &set), "vkAllocateDescriptorSets");
    std::vector<VkDescriptorBufferInfo> infos;
    for (const Buf& b : buffers) infos.push_back({b.buffer, 0, VK_WHOLE_SIZE});
    std::vector<VkWriteDescriptorSet> writes;
    for (uint32_t i = 0; i < buffers.size(); ++i) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = set;
        w.dstBinding = i;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        w.pBufferInfo = &infos[i];
        writes.push_back(w);
    }
    vkUpdateDescriptorSets(dev(), uint32_t(writes.size()), writes.data(), 0, nullptr);
}

// The frame's commands: the result reset (accumulating kernels), the dispatch, the result made visible to the host.
void ComputeOnDevice::Impl::record() {
    vk_check(vkResetCommandBuffer(cb, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(cb, &bi), "vkBeginCommandBuffer");
    if (k->reset_result) {
        vkCmdFillBuffer(cb, buffers.back().buffer, 0, VK_WHOLE_SIZE, 0);
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
        vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &mb, 0,
                             nullptr, 0, nullptr);
    }
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cb, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 4, &k->push);
    vkCmdDispatch(cb, k->groups[0], k->groups[1], 1);
    VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                         nullptr, 0, nullptr);
    vk_check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
}

ComputeOnDevice::ComputeOnDevice(const cts::DeviceContext& ctx, const std::string& name)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.c = &ctx;
    m.k = &kernel(name);
    for (const std::vector<uint32_t>& words : m.k->inputs()) m.buffers.push_back(m.buffer(words, words.size() * 4));
    m.buffers.push_back(m.buffer({}, VkDeviceSize(m.k->result_words) * 4));
    m.descriptors();
    const std::vector<uint32_t>& spirv = cts::compile_glsl(cts::Stage::kCompute, m.k->glsl);
    const auto t0 = Clock::now();
    VkShaderModuleCreateInfo smci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    smci.codeSize = spirv.size() * 4;
    smci.pCode = spirv.data();
    VkShaderModule module;
    vk_check(vkCreateShaderModule(m.dev(), &smci, nullptr, &module), "vkCreateShaderModule");
    m.undo.push_back([d = m.dev(), module] { vkDestroyShaderModule(d, module, nullptr); });
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = module;
    ci.stage.pName = "main";
    ci.layout = m.layout;
    vk_check(vkCreateComputePipelines(m.dev(), VK_NULL_HANDLE, 1, &ci, nullptr, &m.pipeline),
             "vkCreateComputePipelines");
    m.cold_ms = ms_since(t0);
    m.undo.push_back([d = m.dev(), p = m.pipeline] { vkDestroyPipeline(d, p, nullptr); });
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = ctx.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    vk_check(vkAllocateCommandBuffers(m.dev(), &ai, &m.cb), "vkAllocateCommandBuffers");
    m.undo.push_back([d = m.dev(), p = ctx.pool, cb = m.cb] { vkFreeCommandBuffers(d, p, 1, &cb); });
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vk_check(vkCreateFence(m.dev(), &fi, nullptr, &m.fence), "vkCreateFence");
    m.undo.push_back([d = m.dev(), f = m.fence] { vkDestroyFence(d, f, nullptr); });
}

ComputeOnDevice::~ComputeOnDevice() = default;

double ComputeOnDevice::cold_pipeline_ms() const {
    return impl_->cold_ms;
}
double ComputeOnDevice::last_record_ms() const {
    return impl_->record_ms;
}

double ComputeOnDevice::frame() {
    Impl& m = *impl_;
    return timed_frame(
        m.dev(), m.c->queue, m.cb, m.fence, [&m] { m.record(); }, &m.record_ms);
}

const uint8_t* ComputeOnDevice::image_bytes() const {
    return static_cast<const uint8_t*>(impl_->buffers.back().mapped);
}

uint64_t ComputeOnDevice::image_hash() {
    const Impl::Buf& r = impl_->buffers.back();
    const auto* bytes = static_cast<const uint8_t*>(r.mapped);
    uint64_t h = 1469598103934665603ull;
    for (VkDeviceSize i = 0; i < r.size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    return h;
}

}  // namespace tilevk::bench
