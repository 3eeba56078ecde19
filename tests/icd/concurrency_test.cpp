// A multi-threaded application on one device, using the API's threading rules as an application may
// (the spec's "Threading Behavior"): each thread records into command buffers of its own pool, creates and
// destroys its own buffers, images, views, framebuffers, samplers, descriptor pools/sets and pipelines while the
// others do the same, and submits to the one queue under the application's mutex (a queue is externally
// synchronized); the fences are waited for by another thread, which hands each one back. Run for TILEVK_THREADS
// 1, 2, 3, 8 and 16 (read when the device's queue first submits): every image must be identical to the one-thread
// run, and to lavapipe's for the same work. tools/run_sanitizers.sh runs this test under TSan.
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <future>
#include <map>
#include <mutex>
#include <thread>

#include "api_breadth.h"
#include "lt_sample_frag.h"

namespace tilevk::test::breadth {
namespace {

constexpr uint32_t kAppThreads = 4, kIterations = 5, kSize = 48;

// The thread that waits for fences on behalf of the others.
class FenceWaiter {
  public:
    explicit FenceWaiter(VkDevice d) : d_(d), thread_([this] { run(); }) {}
    ~FenceWaiter() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            quit_ = true;
        }
        cv_.notify_all();
        thread_.join();
    }
    // Returns a future that is ready once `fence` has signalled (the result of vkWaitForFences).
    std::future<VkResult> wait(VkFence fence) {
        std::promise<VkResult> done;
        std::future<VkResult> f = done.get_future();
        {
            std::lock_guard<std::mutex> lock(mutex_);
            jobs_.push_back({fence, std::move(done)});
        }
        cv_.notify_all();
        return f;
    }

  private:
    struct Job {
        VkFence fence;
        std::promise<VkResult> done;
    };
    void run() {
        for (;;) {
            Job job;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                cv_.wait(lock, [this] { return quit_ || !jobs_.empty(); });
                if (jobs_.empty()) return;
                job = std::move(jobs_.front());
                jobs_.pop_front();
            }
            job.done.set_value(vkWaitForFences(d_, 1, &job.fence, VK_TRUE, 60'000'000'000ull));
        }
    }
    VkDevice d_;
    std::mutex mutex_;
    std::condition_variable cv_;
    std::deque<Job> jobs_;
    bool quit_ = false;
    std::thread thread_;
};

struct Shared {
    VkQueue queue = VK_NULL_HANDLE;
    std::mutex queue_mutex;  // the application's: vkQueueSubmit's queue is externally synchronized
    FenceWaiter* waiter = nullptr;
};

// The images one application thread produces: iteration i of thread t.
using Images = std::map<std::pair<uint32_t, uint32_t>, Bytes>;

// One application thread: its own Kit (command pool, objects), pipelines made while the other threads make theirs,
// and per iteration a new vertex buffer, view, framebuffer, sampler and descriptor set, destroyed again.
void app_thread(Device& dev, Shared& shared, uint32_t t, Images* out, std::mutex* out_mutex) {
    Kit k(dev);
    const VkFormat C = VK_FORMAT_R8G8B8A8_UNORM;
    Device::Image target =
        k.image(C, kSize, kSize, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    VkRenderPass rp =
        k.render_pass({attachment(C, VK_ATTACHMENT_LOAD_OP_CLEAR, VK_ATTACHMENT_STORE_OP_STORE)}, {subpass(&kColour0)});
    Device::Image tex = k.image(C, 8, 8, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    Device::Buffer texels = k.buffer(8 * 8 * 4);
    for (uint32_t i = 0; i < 8 * 8 * 4; ++i) static_cast<uint8_t*>(texels.map)[i] = uint8_t(i * 29 + t * 71);
    Device::Buffer uniforms = k.buffer(256, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    const float u[4] = {0.1f * float(t), 0.2f, 0.8f - 0.1f * float(t), 1.0f};
    std::memcpy(uniforms.map, u, sizeof u);
    Device::Buffer readback = k.buffer(kSize * kSize * 4);
    VkDescriptorSetLayout dsl =
        k.set_layout({{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
                      {1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}});
    VkPipelineLayout layout = k.pipeline_layout({dsl});
    Target tg{target, rp, VK_NULL_HANDLE, kSize, kSize};
    VkPipeline textured = k.pipeline(fullscreen_pipe(SPV(lt_sample_frag), tg, layout));
    Pipe tri;
    tri.rp = rp;
    tri.width = tri.height = kSize;
    tri.blend = {alpha_over()};
    VkPipeline blended = k.pipeline(tri);
    VkFence fence = VK_NULL_HANDLE;
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    EXPECT_EQ(vkCreateFence(k.d, &fci, nullptr, &fence), VK_SUCCESS);
    VkCommandBuffer cb = k.command_buffer();

    for (uint32_t it = 0; it < kIterations; ++it) {
        VkImageView view = k.view(target.image, C, VK_IMAGE_ASPECT_COLOR_BIT);
        VkFramebuffer fb = k.framebuffer(rp, {view}, kSize, kSize);
        VkImageView tex_view = k.view(tex.image, C, VK_IMAGE_ASPECT_COLOR_BIT);
        VkSampler sampler = k.sampler(it % 2 ? VK_FILTER_LINEAR : VK_FILTER_NEAREST);
        VkDescriptorSet set = k.descriptor_set(dsl);
        const VkDescriptorImageInfo ii{sampler, tex_view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        k.write(set, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &ii);
        const VkDescriptorBufferInfo bi{uniforms.buffer, 0, 16};
        k.write(set, 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &bi, nullptr);
        std::vector<Vertex> verts = kBothTriangles;
        for (Vertex& v : verts) v.pos[0] += 0.05f * float(it) - 0.1f * float(t);
        Device::Buffer vb = k.buffer_of(verts, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);

        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        EXPECT_EQ(vkBeginCommandBuffer(cb, &begin), VK_SUCCESS);  // implicit reset (pool has RESET_COMMAND_BUFFER)
        if (it == 0) {
            transition(cb, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkBufferImageCopy r{};
            r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            r.imageExtent = {8, 8, 1};
            vkCmdCopyBufferToImage(cb, texels.buffer, tex.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
            transition(cb, tex.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        }
        begin_pass(cb, rp, fb, kSize, kSize, {clear_color(0, 0, 0, 0)});
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, textured);
        vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
        vkCmdDraw(cb, 3, 1, 0, 0);
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, blended);
        bind_vertices(cb, vb);
        vkCmdDraw(cb, uint32_t(verts.size()), 1, 0, 0);
        vkCmdEndRenderPass(cb);
        VkBufferImageCopy r{};
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        r.imageExtent = {kSize, kSize, 1};
        vkCmdCopyImageToBuffer(cb, target.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1, &r);
        EXPECT_EQ(vkEndCommandBuffer(cb), VK_SUCCESS);
        {
            std::lock_guard<std::mutex> lock(shared.queue_mutex);
            VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
            si.commandBufferCount = 1;
            si.pCommandBuffers = &cb;
            EXPECT_EQ(vkQueueSubmit(shared.queue, 1, &si, fence), VK_SUCCESS);
        }
        EXPECT_EQ(shared.waiter->wait(fence).get(), VK_SUCCESS);
        EXPECT_EQ(vkResetFences(k.d, 1, &fence), VK_SUCCESS);
        {
            std::lock_guard<std::mutex> lock(*out_mutex);
            (*out)[{t, it}] = Kit::bytes(readback);
        }
        // This iteration's objects go while the other threads keep creating theirs.
        k.destroy_now(VK_OBJECT_TYPE_BUFFER, vb.buffer);
        k.destroy_now(VK_OBJECT_TYPE_DESCRIPTOR_POOL, VkDescriptorPool(VK_NULL_HANDLE));
        k.destroy_now(VK_OBJECT_TYPE_SAMPLER, sampler);
        k.destroy_now(VK_OBJECT_TYPE_FRAMEBUFFER, fb);
        k.destroy_now(VK_OBJECT_TYPE_IMAGE_VIEW, view);
        k.destroy_now(VK_OBJECT_TYPE_IMAGE_VIEW, tex_view);
    }
    vkDestroyFence(k.d, fence, nullptr);
}

// The whole application on the device of `pd`: kAppThreads threads and the fence waiter.
Images run_application(VkPhysicalDevice pd) {
    Device dev(pd);
    EXPECT_TRUE(dev.ok());
    Images images;
    std::mutex images_mutex;
    Shared shared;
    vkGetDeviceQueue(dev.device(), 0, 0, &shared.queue);
    {
        FenceWaiter waiter(dev.device());
        shared.waiter = &waiter;
        std::vector<std::thread> threads;
        for (uint32_t t = 0; t < kAppThreads; ++t)
            threads.emplace_back(app_thread, std::ref(dev), std::ref(shared), t, &images, &images_mutex);
        for (std::thread& th : threads) th.join();
    }
    EXPECT_EQ(vkDeviceWaitIdle(dev.device()), VK_SUCCESS);
    return images;
}

bool under_tsan() {
#if defined(__SANITIZE_THREAD__)
    return true;
#else
    return false;
#endif
}

TEST(Concurrency, ThreadedApplicationImagesDoNotDependOnThreadCounts) {
    // The validation layer's own threading checks stay on; it is left out under TSan (uninstrumented, and slow).
    Harness h(!under_tsan());
    ASSERT_TRUE(h.ok());
    VkPhysicalDevice tilevk = h.find_device("tilevk");
    ASSERT_NE(tilevk, VK_NULL_HANDLE);
    Images reference;
    for (const char* threads : {"1", "2", "3", "8", "16"}) {
        setenv("TILEVK_THREADS", threads, 1);  // no other thread runs here; read at the queue's first submission
        const Images images = run_application(tilevk);
        ASSERT_EQ(images.size(), size_t(kAppThreads) * kIterations) << "TILEVK_THREADS=" << threads;
        if (reference.empty()) {
            reference = images;
            continue;
        }
        for (const auto& [key, img] : images)
            EXPECT_EQ(img, reference.at(key))
                << "TILEVK_THREADS=" << threads << ": thread " << key.first << " iteration " << key.second;
    }
    unsetenv("TILEVK_THREADS");
    if (!under_tsan()) {
        VkPhysicalDevice lvp = h.find_device("llvmpipe");
        ASSERT_NE(lvp, VK_NULL_HANDLE);
        const Images images = run_application(lvp);
        for (const auto& [key, img] : images) {
            const Bytes& ours = reference.at(key);
            size_t diffs = 0;
            for (size_t i = 0; i < img.size(); ++i) diffs += img[i] != ours[i];
            EXPECT_EQ(diffs, 0u) << "lavapipe: thread " << key.first << " iteration " << key.second;
        }
    }
    // The images differ between threads and iterations (the work really is different).
    EXPECT_NE(reference.at({0, 0}), reference.at({1, 0}));
    EXPECT_NE(reference.at({0, 0}), reference.at({0, 1}));
    EXPECT_EQ(h.message_count(), 0) << h.message_report();
}

}  // namespace
}  // namespace tilevk::test::breadth
