// Bounded device loss (icd/README.md, "Device loss"): a submission that runs longer than the device timeout
// (TILEVK_DEVICE_TIMEOUT_MS, 1000 ms here) returns VK_ERROR_DEVICE_LOST within the limit plus one second, whatever
// keeps it busy — an endless fragment or vertex shader on a small or a large target, or a draw of a billion
// instances; the loss is reported once on stderr with the draw and its pipeline; another device drawing at the
// same time is unaffected; everything is destroyed cleanly afterwards (ASan/LSan in tools/run_sanitizers.sh).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>

#include "api_breadth.h"
#include "endless_frag.h"
#include "endless_vert.h"
#include "stderr_capture.h"

namespace tilevk::test::breadth {
namespace {

constexpr int kLimitMs = 1000;

// Under ASan the bound leaves room for its quarantine of freed blocks (256 MB by default); under TSan for the shadow
// memory of every byte the scene touches (measured: 224 MB for the 53 MB scene, build-tsan on GCC 12).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr double kSceneGrowthBoundMb = 400;
#else
constexpr double kSceneGrowthBoundMb = 150;
#endif

class DeviceLoss : public ::testing::Test {
  protected:
    void SetUp() override {
        setenv("TILEVK_DEVICE_TIMEOUT_MS", std::to_string(kLimitMs).c_str(), 1);  // read at vkCreateDevice
        // No validation layer: it would wrap the handles the report names, and it keeps a lost submission's
        // command buffer pending forever, so it reports every later destruction as in use.
        harness_ = std::make_unique<Harness>(false);
        ASSERT_TRUE(harness_->ok());
        pd_ = harness_->find_device("tilevk");
        ASSERT_NE(pd_, VK_NULL_HANDLE);
        dev_ = std::make_unique<Device>(pd_);
        ASSERT_TRUE(dev_->ok());
    }
    void TearDown() override {
        dev_.reset();  // destroying a lost device and its objects must be clean
        EXPECT_EQ(harness_->message_count(), 0) << harness_->message_report();
        harness_.reset();
    }
    std::unique_ptr<Harness> harness_;
    VkPhysicalDevice pd_ = VK_NULL_HANDLE;
    std::unique_ptr<Device> dev_;
};

// Submits `cb` with a fence and returns the result and the milliseconds vkQueueSubmit took.
std::pair<VkResult, double> timed_submit(Kit& k, VkCommandBuffer cb, VkFence fence = VK_NULL_HANDLE) {
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cb;
    const auto t0 = std::chrono::steady_clock::now();
    const VkResult r = vkQueueSubmit(k.queue, 1, &si, fence);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return {r, ms};
}

VkCommandBuffer record(Kit& k, const std::function<void(VkCommandBuffer)>& body) {
    VkCommandBuffer cb = k.command_buffer();
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    EXPECT_EQ(vkBeginCommandBuffer(cb, &bi), VK_SUCCESS);
    body(cb);
    EXPECT_EQ(vkEndCommandBuffer(cb), VK_SUCCESS);
    return cb;
}

// Expects the submission of `cb` to lose the device no sooner than the limit and within the limit + 1 s.
void expect_lost_in_time(Kit& k, VkCommandBuffer cb) {
    const auto [r, ms] = timed_submit(k, cb);
    EXPECT_EQ(r, VK_ERROR_DEVICE_LOST);
    EXPECT_GE(ms, kLimitMs);
    EXPECT_LE(ms, kLimitMs + 1000) << "the device was lost " << ms << " ms after the submission began";
}

// A pass over `t` drawing `pipe`'s full-screen triangle (ab_fullscreen.vert: no vertex input), `instances` times.
void fullscreen_pass(VkCommandBuffer c, const Target& t, VkPipeline pipe, uint32_t instances = 1) {
    begin_pass(c, t.rp, t.fb, t.w, t.h, {clear_color(0, 0, 0, 1)});
    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    vkCmdDraw(c, 3, instances, 0, 0);
    vkCmdEndRenderPass(c);
}

Pipe fullscreen(Spv fs, const Target& t) {
    Pipe p;
    p.vs = SPV(ab_fullscreen_vert);
    p.fs = fs;
    p.bindings = {};
    p.attrs = {};
    p.width = t.w;
    p.height = t.h;
    p.rp = t.rp;
    return p;
}

void endless_fragment_shader(Device& dev, uint32_t w, uint32_t h) {
    Kit k(dev);
    Target t = target(k, VK_FORMAT_R8G8B8A8_UNORM, w, h);
    VkPipeline pipe = k.pipeline(fullscreen(SPV(endless_frag), t));
    expect_lost_in_time(k, record(k, [&](VkCommandBuffer c) { fullscreen_pass(c, t, pipe); }));
}

TEST_F(DeviceLoss, EndlessFragmentShaderSmallTarget) {
    endless_fragment_shader(*dev_, 16, 16);
}

TEST_F(DeviceLoss, EndlessFragmentShaderLargeTarget) {
    endless_fragment_shader(*dev_, 1920, 1080);
}

// `vertices` vertices of triangles spread over the target, drawn with the endless vertex shader.
void endless_vertex_shader(Device& dev, uint32_t w, uint32_t h, uint32_t vertices) {
    Kit k(dev);
    Target t = target(k, VK_FORMAT_R8G8B8A8_UNORM, w, h);
    Pipe p;
    p.vs = SPV(endless_vert);
    p.width = w;
    p.height = h;
    p.rp = t.rp;
    VkPipeline pipe = k.pipeline(p);
    std::vector<Vertex> verts;
    for (uint32_t i = 0; i < vertices; ++i) verts.push_back(kBothTriangles[i % kBothTriangles.size()]);
    Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    expect_lost_in_time(k, record(k, [&](VkCommandBuffer c) {
                            begin_pass(c, t.rp, t.fb, w, h, {clear_color(0, 0, 0, 1)});
                            vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
                            bind_vertices(c, vb);
                            vkCmdDraw(c, vertices, 1, 0, 0);
                            vkCmdEndRenderPass(c);
                        }));
}

// Timeline semaphores (queue_scheduler.h): a wait-before-signal batch that the host releases runs on the queue's
// worker and loses the device there; nothing hangs: a host waiting for its signal gets VK_ERROR_DEVICE_LOST in
// time, the batch queued behind it is dropped with its fence signalled, vkQueueWaitIdle answers VK_ERROR_DEVICE_LOST.
TEST_F(DeviceLoss, QueuedTimelineBatchLosesTheDeviceWithoutHangingItsWaiters) {
    VkPhysicalDeviceTimelineSemaphoreFeatures tf{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_FEATURES};
    tf.timelineSemaphore = VK_TRUE;
    Device dev(pd_, nullptr, {VK_KHR_TIMELINE_SEMAPHORE_EXTENSION_NAME}, &tf);
    ASSERT_TRUE(dev.ok());
    Kit k(dev);
    auto signal = reinterpret_cast<PFN_vkSignalSemaphoreKHR>(vkGetDeviceProcAddr(k.d, "vkSignalSemaphoreKHR"));
    auto wait = reinterpret_cast<PFN_vkWaitSemaphoresKHR>(vkGetDeviceProcAddr(k.d, "vkWaitSemaphoresKHR"));
    ASSERT_NE(signal, nullptr);
    ASSERT_NE(wait, nullptr);
    VkSemaphoreTypeCreateInfo ti{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    ti.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    sci.pNext = &ti;
    VkSemaphore gate = VK_NULL_HANDLE, done = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateSemaphore(k.d, &sci, nullptr, &gate), VK_SUCCESS);
    ASSERT_EQ(vkCreateSemaphore(k.d, &sci, nullptr, &done), VK_SUCCESS);
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateFence(k.d, &fci, nullptr, &fence), VK_SUCCESS);

    Target t = target(k, VK_FORMAT_R8G8B8A8_UNORM, 64, 64);
    VkPipeline pipe = k.pipeline(fullscreen(SPV(endless_frag), t));
    VkCommandBuffer endless = record(k, [&](VkCommandBuffer c) { fullscreen_pass(c, t, pipe); });
    const uint64_t one = 1, two = 2;
    VkTimelineSemaphoreSubmitInfo tv{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    tv.waitSemaphoreValueCount = 1;
    tv.pWaitSemaphoreValues = &one;
    tv.signalSemaphoreValueCount = 1;
    tv.pSignalSemaphoreValues = &one;
    const VkPipelineStageFlags stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
    VkSubmitInfo first{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    first.pNext = &tv;
    first.waitSemaphoreCount = 1;
    first.pWaitSemaphores = &gate;
    first.pWaitDstStageMask = &stage;
    first.commandBufferCount = 1;
    first.pCommandBuffers = &endless;
    first.signalSemaphoreCount = 1;
    first.pSignalSemaphores = &done;
    VkTimelineSemaphoreSubmitInfo tv2{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    tv2.signalSemaphoreValueCount = 1;
    tv2.pSignalSemaphoreValues = &two;
    VkSubmitInfo second{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    second.pNext = &tv2;
    second.signalSemaphoreCount = 1;
    second.pSignalSemaphores = &done;
    EXPECT_EQ(vkQueueSubmit(k.queue, 1, &first, VK_NULL_HANDLE), VK_SUCCESS);  // queued: the gate is at 0
    EXPECT_EQ(vkQueueSubmit(k.queue, 1, &second, fence), VK_SUCCESS);
    VkSemaphoreSignalInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO};
    si.semaphore = gate;
    si.value = 1;
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(signal(k.d, &si), VK_SUCCESS);
    VkSemaphoreWaitInfo wi{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
    wi.semaphoreCount = 1;
    wi.pSemaphores = &done;
    wi.pValues = &two;
    EXPECT_EQ(wait(k.d, &wi, UINT64_MAX), VK_ERROR_DEVICE_LOST);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_GE(ms, kLimitMs);
    EXPECT_LE(ms, kLimitMs + 1000) << "the waiter was released " << ms << " ms after the signal";
    const VkResult fr = vkWaitForFences(k.d, 1, &fence, VK_TRUE, UINT64_MAX);
    EXPECT_TRUE(fr == VK_SUCCESS || fr == VK_ERROR_DEVICE_LOST) << fr;
    EXPECT_EQ(vkQueueWaitIdle(k.queue), VK_ERROR_DEVICE_LOST);
    EXPECT_EQ(vkDeviceWaitIdle(k.d), VK_ERROR_DEVICE_LOST);
    EXPECT_EQ(timed_submit(k, endless).first, VK_ERROR_DEVICE_LOST);
    vkDestroyFence(k.d, fence, nullptr);
    vkDestroySemaphore(k.d, gate, nullptr);
    vkDestroySemaphore(k.d, done, nullptr);
}

TEST_F(DeviceLoss, EndlessVertexShaderSmallDraw) {
    endless_vertex_shader(*dev_, 16, 16, 3);
}

TEST_F(DeviceLoss, EndlessVertexShaderLargeDraw) {
    endless_vertex_shader(*dev_, 1920, 1080, 30000);
}

// The process's resident set in MB: now (VmRSS) or its peak since the last reset_peak_rss() (VmHWM).
double rss_mb(const char* field) {
    std::ifstream in("/proc/self/status");
    for (std::string line; std::getline(in, line);)
        if (line.rfind(field, 0) == 0) return std::strtod(line.c_str() + std::strlen(field), nullptr) / 1024.0;
    return -1;
}

// Linux resets VmHWM to the current resident set when "5" is written to clear_refs (proc(5)).
bool reset_peak_rss() {
    std::ofstream out("/proc/self/clear_refs");
    out << "5";
    out.flush();
    return out.good();
}

// No shader loops at all: a billion instances of a full-screen triangle keep the vertex stage, setup and the
// fragment stage busy for hours; the limit still holds, and the draw's scene is rendered in parts of bounded size
// (rast/render/renderer.cpp kMaxScenePrimsBetweenInstances: ~50 MB; a part of 2^20 primitives would be ~700 MB).
// Measured: 53 MB, against 366 MB within the second with parts of 2^20 primitives.
TEST_F(DeviceLoss, BillionInstanceDraw) {
    Kit k(*dev_);
    Target t = target(k, VK_FORMAT_R8G8B8A8_UNORM, 256, 256);
    VkPipeline pipe = k.pipeline(fullscreen(SPV(color_frag), t));
    VkCommandBuffer cb = record(k, [&](VkCommandBuffer c) { fullscreen_pass(c, t, pipe, 1u << 30); });
    ASSERT_TRUE(reset_peak_rss());
    const double before = rss_mb("VmRSS:");
    expect_lost_in_time(k, cb);
    const double growth = rss_mb("VmHWM:") - before;
    EXPECT_LT(growth, kSceneGrowthBoundMb) << "the draw's scene grew the resident set by " << growth << " MB";
}

size_t count_of(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// The report: one line naming the limit, the interrupted draw (draw 1: draw 0 is an ordinary one before it) and
// its pipeline; later calls on the lost device return VK_ERROR_DEVICE_LOST at once, signal their fences and print
// nothing more.
TEST_F(DeviceLoss, ReportedOnceWithTheDrawAndItsPipeline) {
    Kit k(*dev_);
    Target t = target(k, VK_FORMAT_R8G8B8A8_UNORM, 64, 64);
    VkPipeline plain = k.pipeline(fullscreen(SPV(color_frag), t));
    VkPipeline endless = k.pipeline(fullscreen(SPV(endless_frag), t));
    VkCommandBuffer cb = record(k, [&](VkCommandBuffer c) {
        begin_pass(c, t.rp, t.fb, t.w, t.h, {clear_color(0, 0, 0, 1)});
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, plain);
        vkCmdDraw(c, 3, 1, 0, 0);
        vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, endless);
        vkCmdDraw(c, 3, 1, 0, 0);
        vkCmdEndRenderPass(c);
    });
    VkResult first = VK_SUCCESS;
    const std::string log = stderr_of([&] { first = timed_submit(k, cb).first; });
    EXPECT_EQ(first, VK_ERROR_DEVICE_LOST);
    char pipeline[64];
    snprintf(pipeline, sizeof pipeline, "(VkPipeline 0x%llx)", static_cast<unsigned long long>(uint64_t(endless)));
    EXPECT_EQ(count_of(log, "the device is lost"), 1u) << log;
    EXPECT_EQ(count_of(log, "device timeout (1000 ms, TILEVK_DEVICE_TIMEOUT_MS)"), 1u) << log;
    EXPECT_EQ(count_of(log, std::string("draw 1 of pSubmits[0].pCommandBuffers[0] ") + pipeline), 1u) << log;

    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateFence(k.d, &fci, nullptr, &fence), VK_SUCCESS);
    double ms = 0;
    VkResult again = VK_SUCCESS;
    const std::string later = stderr_of([&] { std::tie(again, ms) = timed_submit(k, cb, fence); });
    EXPECT_EQ(again, VK_ERROR_DEVICE_LOST);
    EXPECT_LT(ms, 100.0);
    EXPECT_EQ(later, "");
    const VkResult wait = vkWaitForFences(k.d, 1, &fence, VK_TRUE, 1'000'000'000);
    EXPECT_TRUE(wait == VK_SUCCESS || wait == VK_ERROR_DEVICE_LOST) << wait;
    EXPECT_EQ(vkQueueWaitIdle(k.queue), VK_ERROR_DEVICE_LOST);
    EXPECT_EQ(vkDeviceWaitIdle(k.d), VK_ERROR_DEVICE_LOST);
    vkDestroyFence(k.d, fence, nullptr);
}

// A second tilevk device draws while the first one hangs and is lost, and after: it finishes its work in far less
// than the limit, draws the right colour (color.frag writes the vertex colour: ab_fullscreen.vert's blue 0.75) and
// is never lost.
TEST_F(DeviceLoss, OtherDevicesAreUnaffected) {
    Device other(pd_);
    ASSERT_TRUE(other.ok());
    Kit k(*dev_);
    Target t = target(k, VK_FORMAT_R8G8B8A8_UNORM, 256, 256);
    VkPipeline pipe = k.pipeline(fullscreen(SPV(endless_frag), t));
    VkCommandBuffer cb = record(k, [&](VkCommandBuffer c) { fullscreen_pass(c, t, pipe); });
    Kit ko(other);
    Target to = target(ko, VK_FORMAT_R8G8B8A8_UNORM, 256, 256);
    VkPipeline plain = ko.pipeline(fullscreen(SPV(color_frag), to));
    auto draw_other = [&] {
        const auto t0 = std::chrono::steady_clock::now();
        EXPECT_EQ(ko.run([&](VkCommandBuffer c) { fullscreen_pass(c, to, plain); }), VK_SUCCESS);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        EXPECT_LT(ms, kLimitMs / 2.0);
        const Bytes img = ko.read(to.image.image, 256, 256, 4);
        for (uint32_t y = 0; y < 256; y += 51)
            for (uint32_t x = 0; x < 256; x += 51) EXPECT_EQ(px(img, x, y, 256)[2], 191) << x << "," << y;
    };
    std::thread hang([&] { expect_lost_in_time(k, cb); });
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    draw_other();  // while the first device is stuck
    hang.join();
    draw_other();  // after it is lost
    EXPECT_EQ(vkDeviceWaitIdle(other.device()), VK_SUCCESS);
}

}  // namespace
}  // namespace tilevk::test::breadth
