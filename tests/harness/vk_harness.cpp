#include "vk_harness.h"

#include <cstdio>
#include <cstring>
#include <iterator>

#include "vk_pipeline.h"

namespace tilevk::test {
namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT type,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    // Only warnings and errors count; informational messages (the loader's search log, the layer's "active"
    // banner) are not findings.
    (void)type;
    if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
    auto* m = static_cast<Messages*>(user);
    m->count.fetch_add(1);
    if (m->texts.size() < 20) m->texts.emplace_back(data->pMessage != nullptr ? data->pMessage : "(no text)");
    fprintf(stderr, "validation: %s\n", data->pMessage != nullptr ? data->pMessage : "(no text)");
    return VK_FALSE;
}

}  // namespace

Harness::Harness(bool validation, const std::vector<const char*>& extensions, uint32_t api_version) {
    const char* layers[] = {"VK_LAYER_KHRONOS_validation"};
    // The instance extensions of Vulkan 1.1 (physical-device queries of extensions, device groups, external
    // handle capabilities): both drivers offer them.
    std::vector<const char*> exts = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME,
                                     VK_KHR_GET_PHYSICAL_DEVICE_PROPERTIES_2_EXTENSION_NAME,
                                     VK_KHR_DEVICE_GROUP_CREATION_EXTENSION_NAME,
                                     VK_KHR_EXTERNAL_MEMORY_CAPABILITIES_EXTENSION_NAME,
                                     VK_KHR_EXTERNAL_FENCE_CAPABILITIES_EXTENSION_NAME,
                                     VK_KHR_EXTERNAL_SEMAPHORE_CAPABILITIES_EXTENSION_NAME};
    exts.insert(exts.end(), extensions.begin(), extensions.end());
    VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    // Every warning and error, of every type (validation, performance, general: the loader's own warnings too).
    mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    mci.pfnUserCallback = on_message;
    mci.pUserData = &messages_;
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "tilevk-icd-test";
    // Vulkan 1.2 by default: the validation layer holds both drivers to its rules (SPIR-V up to 1.5); the tests of
    // Vulkan 1.3 itself ask for 1.3.
    app.apiVersion = api_version;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pNext = &mci;  // also catches messages from vkCreateInstance/vkDestroyInstance
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = validation ? 1 : 0;
    ci.ppEnabledLayerNames = layers;
    ci.enabledExtensionCount = uint32_t(exts.size());
    ci.ppEnabledExtensionNames = exts.data();
    if (vkCreateInstance(&ci, nullptr, &instance_) != VK_SUCCESS) {
        instance_ = VK_NULL_HANDLE;
        return;
    }
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create == nullptr || create(instance_, &mci, nullptr, &messenger_) != VK_SUCCESS) messenger_ = VK_NULL_HANDLE;
}

Harness::~Harness() {
    if (instance_ == VK_NULL_HANDLE) return;
    if (messenger_ != VK_NULL_HANDLE) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        destroy(instance_, messenger_, nullptr);
    }
    vkDestroyInstance(instance_, nullptr);
}

std::string Harness::message_report() const {
    std::string s;
    for (const std::string& t : messages_.texts) s += t + "\n";
    return s;
}

std::vector<VkPhysicalDevice> Harness::physical_devices() const {
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(instance_, &n, nullptr);
    std::vector<VkPhysicalDevice> pds(n);
    vkEnumeratePhysicalDevices(instance_, &n, pds.data());
    pds.resize(n);
    return pds;
}

VkPhysicalDevice Harness::find_device(const char* prefix) const {
    for (VkPhysicalDevice pd : physical_devices()) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        if (std::strncmp(p.deviceName, prefix, std::strlen(prefix)) == 0) return pd;
    }
    return VK_NULL_HANDLE;
}

Device::Device(VkPhysicalDevice pd, const VkPhysicalDeviceFeatures* features,
               const std::vector<const char*>& extensions, const void* chain)
    : pd_(pd) {
    float prio = 1.0f;
    VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    q.queueFamilyIndex = 0;
    q.queueCount = 1;
    q.pQueuePriorities = &prio;
    VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    ci.queueCreateInfoCount = 1;
    ci.pQueueCreateInfos = &q;
    ci.pEnabledFeatures = features;
    ci.pNext = chain;
    ci.enabledExtensionCount = uint32_t(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    if (vkCreateDevice(pd, &ci, nullptr, &device_) != VK_SUCCESS) {
        device_ = VK_NULL_HANDLE;
        return;
    }
    vkGetDeviceQueue(device_, 0, 0, &queue_);
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = 0;
    vkCreateCommandPool(device_, &pci, nullptr, &pool_);
}

Device::~Device() {
    if (device_ == VK_NULL_HANDLE) return;
    vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
}

uint32_t Device::memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(pd_, &mp);
    for (uint32_t i = 0; i < mp.memoryTypeCount; ++i) {
        if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & flags) == flags) return i;
    }
    return ~0u;
}

Device::Buffer Device::make_buffer(VkDeviceSize size, VkBufferUsageFlags extra_usage) {
    Buffer b;
    b.size = size;
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = size;
    ci.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | extra_usage;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    vkCreateBuffer(device_, &ci, nullptr, &b.buffer);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, b.buffer, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex =
        memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    // a buffer whose address shaders use must live in memory allocated for device addresses
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    if ((extra_usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0) ai.pNext = &flags;
    vkAllocateMemory(device_, &ai, nullptr, &b.memory);
    vkBindBufferMemory(device_, b.buffer, b.memory, 0);
    vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.map);
    return b;
}

void Device::destroy(Buffer& b) {
    vkUnmapMemory(device_, b.memory);
    vkDestroyBuffer(device_, b.buffer, nullptr);
    vkFreeMemory(device_, b.memory, nullptr);
    b = {};
}

VkImageCreateInfo image_info_2d(VkFormat format, uint32_t width, uint32_t height, uint32_t levels, uint32_t layers,
                                VkSampleCountFlagBits samples, VkImageUsageFlags usage, VkImageTiling tiling,
                                VkImageLayout initial_layout) {
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = format;
    ci.extent = {width, height, 1};
    ci.mipLevels = levels;
    ci.arrayLayers = layers;
    ci.samples = samples;
    ci.tiling = tiling;
    ci.usage = usage;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.initialLayout = initial_layout;
    return ci;
}

Device::Image Device::make_image(VkFormat format, uint32_t width, uint32_t height, uint32_t levels, uint32_t layers,
                                 VkSampleCountFlagBits samples, VkImageUsageFlags usage) {
    return make_image(image_info_2d(format, width, height, levels, layers, samples, usage));
}

Device::Image Device::make_image(const VkImageCreateInfo& ci) {
    Image img;
    if (vkCreateImage(device_, &ci, nullptr, &img.image) != VK_SUCCESS) return {};
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, img.image, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = memory_type(req.memoryTypeBits, 0);
    vkAllocateMemory(device_, &ai, nullptr, &img.memory);
    vkBindImageMemory(device_, img.image, img.memory, 0);
    return img;
}

void Device::destroy(Image& i) {
    vkDestroyImage(device_, i.image, nullptr);
    vkFreeMemory(device_, i.memory, nullptr);
    i = {};
}

VkResult Device::run(const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cb;
    vkAllocateCommandBuffers(device_, &ai, &cb);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cb, &bi);
    record(cb);
    vkEndCommandBuffer(cb);
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    vkCreateFence(device_, &fci, nullptr, &fence);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    VkResult result = vkQueueSubmit(queue_, 1, &si, fence);
    const VkResult waited = vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX);
    if (result == VK_SUCCESS) result = waited;
    vkDestroyFence(device_, fence, nullptr);
    vkFreeCommandBuffers(device_, pool_, 1, &cb);
    return result;
}

VkPipelineShaderStageCreateInfo shader_stage(VkShaderStageFlagBits stage, VkShaderModule module) {
    VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    s.stage = stage;
    s.module = module;
    s.pName = "main";
    return s;
}

PipelineStates::PipelineStates(uint32_t width, uint32_t height) {
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    viewport = {0, 0, float(width), float(height), 0, 1};
    scissor = {{0, 0}, {width, height}};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.lineWidth = 1.0f;
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    blend.colorWriteMask = 0xF;
    color_blend.attachmentCount = 1;
}

VkResult PipelineStates::create(VkDevice device, VkRenderPass pass, VkPipelineLayout layout,
                                const VkPipelineShaderStageCreateInfo* stages, uint32_t stage_count, VkPipeline* out) {
    VkPipelineViewportStateCreateInfo vps{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vps.viewportCount = 1;
    vps.pViewports = &viewport;
    vps.scissorCount = 1;
    vps.pScissors = &scissor;
    color_blend.pAttachments = &blend;
    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    ci.stageCount = stage_count;
    ci.pStages = stages;
    ci.pVertexInputState = &vertex_input;
    ci.pInputAssemblyState = &assembly;
    ci.pViewportState = &vps;
    ci.pRasterizationState = &raster;
    ci.pMultisampleState = &multisample;
    ci.pDepthStencilState = depth_stencil_enabled ? &depth_stencil : nullptr;
    ci.pColorBlendState = &color_blend;
    ci.layout = layout;
    ci.renderPass = pass;
    *out = VK_NULL_HANDLE;
    return vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &ci, nullptr, out);
}

SingleAttachmentPass::SingleAttachmentPass(VkDevice device, VkImage image, const VkAttachmentDescription& attachment,
                                           VkImageAspectFlags aspect, uint32_t width, uint32_t height,
                                           const std::vector<VkSubpassDependency>& dependencies) {
    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = image;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = attachment.format;
    vci.subresourceRange = {aspect, 0, 1, 0, 1};
    EXPECT_EQ(vkCreateImageView(device, &vci, nullptr, &view), VK_SUCCESS);
    const bool depth_stencil = (aspect & (VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT)) != 0;
    const VkAttachmentReference ref{
        0, depth_stencil ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    if (depth_stencil) {
        sub.pDepthStencilAttachment = &ref;
    } else {
        sub.colorAttachmentCount = 1;
        sub.pColorAttachments = &ref;
    }
    VkRenderPassCreateInfo rpci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rpci.attachmentCount = 1;
    rpci.pAttachments = &attachment;
    rpci.subpassCount = 1;
    rpci.pSubpasses = &sub;
    rpci.dependencyCount = uint32_t(dependencies.size());
    rpci.pDependencies = dependencies.data();
    EXPECT_EQ(vkCreateRenderPass(device, &rpci, nullptr, &pass), VK_SUCCESS);
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = pass;
    fci.attachmentCount = 1;
    fci.pAttachments = &view;
    fci.width = width;
    fci.height = height;
    fci.layers = 1;
    EXPECT_EQ(vkCreateFramebuffer(device, &fci, nullptr, &framebuffer), VK_SUCCESS);
}

void SingleAttachmentPass::destroy(VkDevice device) {
    vkDestroyFramebuffer(device, framebuffer, nullptr);
    vkDestroyRenderPass(device, pass, nullptr);
    vkDestroyImageView(device, view, nullptr);
    framebuffer = VK_NULL_HANDLE;
    pass = VK_NULL_HANDLE;
    view = VK_NULL_HANDLE;
}

std::unique_ptr<Harness> TwoDriverSuite::harness_;
std::unique_ptr<Device> TwoDriverSuite::tilevk_, TwoDriverSuite::lavapipe_;

void TwoDriverSuite::SetUpTestSuite() {
    harness_ = std::make_unique<Harness>();
    ASSERT_TRUE(harness_->ok());
    VkPhysicalDevice t = harness_->find_device("tilevk"), l = harness_->find_device("llvmpipe");
    ASSERT_NE(t, VK_NULL_HANDLE);
    ASSERT_NE(l, VK_NULL_HANDLE);
    tilevk_ = std::make_unique<Device>(t);
    lavapipe_ = std::make_unique<Device>(l);
    ASSERT_TRUE(tilevk_->ok() && lavapipe_->ok());
}

void TwoDriverSuite::TearDownTestSuite() {
    tilevk_.reset();
    lavapipe_.reset();
    harness_.reset();
}

void TwoDriverSuite::TearDown() {
    EXPECT_EQ(harness_->message_count(), 0) << harness_->message_report();
}

void transition(VkCommandBuffer cb, VkImage image, VkImageAspectFlags aspects, VkImageLayout from, VkImageLayout to,
                uint32_t levels, uint32_t layers) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspects, 0, levels, 0, layers};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                         1, &b);
}

}  // namespace tilevk::test
