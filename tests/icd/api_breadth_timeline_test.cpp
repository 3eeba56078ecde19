// Timeline semaphores (VK_KHR_timeline_semaphore, Vulkan 1.2 core), on tilevk and lavapipe with the validation layer
// on: wait-before-signal batches that a host signal releases, in submission order; vkWaitSemaphores with any/all
// and timeouts; counters that only grow; binary and timeline semaphores in the same submissions; vkQueueSubmit2's
// timeline values. Each case returns what it observed (buffer contents, counters, results) and the bytes of both
// drivers must be equal, besides the expectations written here.
#include <atomic>
#include <chrono>
#include <thread>

#include "api_breadth.h"

namespace tilevk::test::breadth {
namespace {

struct TimelineFns {
    PFN_vkGetSemaphoreCounterValueKHR value = nullptr;
    PFN_vkWaitSemaphoresKHR wait = nullptr;
    PFN_vkSignalSemaphoreKHR signal = nullptr;
    explicit TimelineFns(VkDevice d)
        : value(reinterpret_cast<PFN_vkGetSemaphoreCounterValueKHR>(
              vkGetDeviceProcAddr(d, "vkGetSemaphoreCounterValueKHR"))),
          wait(reinterpret_cast<PFN_vkWaitSemaphoresKHR>(vkGetDeviceProcAddr(d, "vkWaitSemaphoresKHR"))),
          signal(reinterpret_cast<PFN_vkSignalSemaphoreKHR>(vkGetDeviceProcAddr(d, "vkSignalSemaphoreKHR"))) {
        EXPECT_NE(value, nullptr);
        EXPECT_NE(wait, nullptr);
        EXPECT_NE(signal, nullptr);
    }
    uint64_t get(VkDevice d, VkSemaphore s) const {
        uint64_t v = ~uint64_t(0);
        EXPECT_EQ(value(d, s, &v), VK_SUCCESS);
        return v;
    }
    void host_signal(VkDevice d, VkSemaphore s, uint64_t v) const {
        VkSemaphoreSignalInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO};
        si.semaphore = s;
        si.value = v;
        EXPECT_EQ(signal(d, &si), VK_SUCCESS);
    }
    VkResult wait_for(VkDevice d, std::vector<VkSemaphore> s, std::vector<uint64_t> v, bool any,
                      uint64_t timeout) const {
        VkSemaphoreWaitInfo wi{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
        wi.flags = any ? VK_SEMAPHORE_WAIT_ANY_BIT : 0;
        wi.semaphoreCount = uint32_t(s.size());
        wi.pSemaphores = s.data();
        wi.pValues = v.data();
        return wait(d, &wi, timeout);
    }
};

VkSemaphore semaphore(Kit& k, VkSemaphoreType type, uint64_t initial = 0) {
    VkSemaphoreTypeCreateInfo ti{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    ti.semaphoreType = type;
    ti.initialValue = initial;
    VkSemaphoreCreateInfo ci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    ci.pNext = &ti;
    VkSemaphore s = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateSemaphore(k.d, &ci, nullptr, &s), VK_SUCCESS);
    VkDevice d = k.d;
    k.undo(VK_OBJECT_TYPE_SEMAPHORE, s, [d, s] { vkDestroySemaphore(d, s, nullptr); });
    return s;
}

VkFence fence(Kit& k) {
    VkFenceCreateInfo ci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence f = VK_NULL_HANDLE;
    EXPECT_EQ(vkCreateFence(k.d, &ci, nullptr, &f), VK_SUCCESS);
    VkDevice d = k.d;
    k.undo(VK_OBJECT_TYPE_FENCE, f, [d, f] { vkDestroyFence(d, f, nullptr); });
    return f;
}

// A command buffer (of the Kit's pool, freed with it) that fills `words` words of `b` from word `at` with `value`.
VkCommandBuffer fill_commands(Kit& k, const Device::Buffer& b, uint32_t at, uint32_t words, uint32_t value) {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = k.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer c = VK_NULL_HANDLE;
    EXPECT_EQ(vkAllocateCommandBuffers(k.d, &ai, &c), VK_SUCCESS);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(c, &bi);
    vkCmdFillBuffer(c, b.buffer, VkDeviceSize(at) * 4, VkDeviceSize(words) * 4, value);
    vkEndCommandBuffer(c);
    return c;
}

// One VkSubmitInfo with its timeline values (entries of binary semaphores are ignored by the drivers).
struct Submission {
    std::vector<VkSemaphore> waits, signals;
    std::vector<uint64_t> wait_values, signal_values;
    std::vector<VkPipelineStageFlags> stages;
    std::vector<VkCommandBuffer> buffers;
    VkTimelineSemaphoreSubmitInfo timeline{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    VkSubmitInfo info{VK_STRUCTURE_TYPE_SUBMIT_INFO};

    Submission& wait(VkSemaphore s, uint64_t v) {
        waits.push_back(s);
        wait_values.push_back(v);
        stages.push_back(VK_PIPELINE_STAGE_TRANSFER_BIT);
        return *this;
    }
    Submission& signal(VkSemaphore s, uint64_t v) {
        signals.push_back(s);
        signal_values.push_back(v);
        return *this;
    }
    Submission& run(VkCommandBuffer c) {
        buffers.push_back(c);
        return *this;
    }
    const VkSubmitInfo& get() {
        timeline.waitSemaphoreValueCount = uint32_t(wait_values.size());
        timeline.pWaitSemaphoreValues = wait_values.data();
        timeline.signalSemaphoreValueCount = uint32_t(signal_values.size());
        timeline.pSignalSemaphoreValues = signal_values.data();
        info.pNext = &timeline;
        info.waitSemaphoreCount = uint32_t(waits.size());
        info.pWaitSemaphores = waits.data();
        info.pWaitDstStageMask = stages.data();
        info.signalSemaphoreCount = uint32_t(signals.size());
        info.pSignalSemaphores = signals.data();
        info.commandBufferCount = uint32_t(buffers.size());
        info.pCommandBuffers = buffers.data();
        return info;
    }
};

VkResult submit(Kit& k, std::vector<Submission*> subs, VkFence f = VK_NULL_HANDLE) {
    std::vector<VkSubmitInfo> infos;
    for (Submission* s : subs) infos.push_back(s->get());
    return vkQueueSubmit(k.queue, uint32_t(infos.size()), infos.data(), f);
}

Bytes words(const Device::Buffer& b, uint32_t n) {
    const auto* p = static_cast<const uint8_t*>(b.map);
    return Bytes(p, p + n * 4);
}

void append(Bytes& out, uint64_t v) {
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    out.insert(out.end(), p, p + sizeof v);
}

uint32_t word(const Device::Buffer& b, uint32_t i) {
    return static_cast<const uint32_t*>(b.map)[i];
}

constexpr uint64_t kForever = UINT64_MAX;
constexpr uint64_t kShort = 20'000'000;  // 20 ms

class TimelineSemaphores : public ApiBreadth {
  protected:
    void SetUp() override {
        features_.timelineSemaphore = VK_TRUE;
        dev_ = std::make_unique<DevicePair>(tilevk_->physical(), lavapipe_->physical(), extensions(), &features_);
        ASSERT_TRUE(dev_->ok());
    }
    virtual std::vector<const char*> extensions() const { return {VK_KHR_TIMELINE_SEMAPHORE_EXTENSION_NAME}; }
    Bytes both(const std::function<Bytes(Kit&)>& scene) { return both_on(dev_->tilevk, dev_->lavapipe, scene); }

    VkPhysicalDeviceTimelineSemaphoreFeatures features_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_FEATURES};
    std::unique_ptr<DevicePair> dev_;
};

// The feature and the property, as vkGetPhysicalDevice*2 report them.
TEST_F(TimelineSemaphores, FeatureAndPropertyReported) {
    VkPhysicalDeviceTimelineSemaphoreFeatures f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_FEATURES};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &f;
    auto features2 = reinterpret_cast<PFN_vkGetPhysicalDeviceFeatures2KHR>(
        vkGetInstanceProcAddr(harness_->instance(), "vkGetPhysicalDeviceFeatures2KHR"));
    auto properties2 = reinterpret_cast<PFN_vkGetPhysicalDeviceProperties2KHR>(
        vkGetInstanceProcAddr(harness_->instance(), "vkGetPhysicalDeviceProperties2KHR"));
    ASSERT_NE(features2, nullptr);
    ASSERT_NE(properties2, nullptr);
    features2(tilevk_->physical(), &f2);
    EXPECT_EQ(f.timelineSemaphore, VK_TRUE);
    VkPhysicalDeviceTimelineSemaphoreProperties p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_PROPERTIES};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    p2.pNext = &p;
    properties2(tilevk_->physical(), &p2);
    VkPhysicalDeviceTimelineSemaphoreProperties lp{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TIMELINE_SEMAPHORE_PROPERTIES};
    p2.pNext = &lp;
    properties2(lavapipe_->physical(), &p2);
    EXPECT_EQ(p.maxTimelineSemaphoreValueDifference, lp.maxTimelineSemaphoreValueDifference);
    EXPECT_GE(p.maxTimelineSemaphoreValueDifference, uint64_t(1) << 31);  // the spec's minimum
}

// A batch waiting for a value nobody has signalled yet: vkQueueSubmit returns at once, neither it nor the batch
// submitted after it (which waits for nothing) runs, its fence and counter stay put; the host's vkSignalSemaphore
// releases both, in order (the second batch's fill lands last).
TEST_F(TimelineSemaphores, HostSignalReleasesAQueuedWaitBeforeSignalBatch) {
    const Bytes b = both([](Kit& k) {
        TimelineFns fn(k.d);
        VkSemaphore gate = semaphore(k, VK_SEMAPHORE_TYPE_TIMELINE);
        VkSemaphore done = semaphore(k, VK_SEMAPHORE_TYPE_TIMELINE, 1);
        VkFence f1 = fence(k), f2 = fence(k);
        Device::Buffer buf = k.buffer(64);
        Submission first, second;
        first.wait(gate, 1).run(fill_commands(k, buf, 0, 16, 0x11111111u)).signal(done, 5);
        second.run(fill_commands(k, buf, 4, 4, 0x22222222u)).signal(done, 6);
        const auto t0 = std::chrono::steady_clock::now();
        EXPECT_EQ(submit(k, {&first}, f1), VK_SUCCESS);
        EXPECT_EQ(submit(k, {&second}, f2), VK_SUCCESS);
        EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(2));  // did not wait for the gate
        std::this_thread::sleep_for(std::chrono::milliseconds(30));
        EXPECT_EQ(vkGetFenceStatus(k.d, f1), VK_NOT_READY);
        EXPECT_EQ(vkGetFenceStatus(k.d, f2), VK_NOT_READY);
        EXPECT_EQ(fn.wait_for(k.d, {done}, {5}, false, kShort), VK_TIMEOUT);
        Bytes out = words(buf, 16);  // untouched: all zero
        append(out, fn.get(k.d, done));
        fn.host_signal(k.d, gate, 1);
        EXPECT_EQ(fn.wait_for(k.d, {done}, {6}, false, kForever), VK_SUCCESS);
        EXPECT_EQ(vkWaitForFences(k.d, 1, &f2, VK_TRUE, kForever), VK_SUCCESS);
        EXPECT_EQ(vkGetFenceStatus(k.d, f1), VK_SUCCESS);
        EXPECT_EQ(vkQueueWaitIdle(k.queue), VK_SUCCESS);
        EXPECT_EQ(word(buf, 0), 0x11111111u);
        EXPECT_EQ(word(buf, 4), 0x22222222u);  // the second batch ran after the first
        const Bytes after = words(buf, 16);
        out.insert(out.end(), after.begin(), after.end());
        append(out, fn.get(k.d, done));
        append(out, fn.get(k.d, gate));
        return out;
    });
    ASSERT_EQ(b.size(), 64u + 8 + 64 + 16);
    for (size_t i = 0; i < 64; ++i) EXPECT_EQ(b[i], 0) << i;
}

// vkQueueWaitIdle and vkDeviceWaitIdle wait for a queued batch that another thread releases.
TEST_F(TimelineSemaphores, WaitIdleWaitsForTheReleasedBatch) {
    both([](Kit& k) {
        TimelineFns fn(k.d);
        VkSemaphore gate = semaphore(k, VK_SEMAPHORE_TYPE_TIMELINE);
        Device::Buffer buf = k.buffer(16);
        Submission s;
        s.wait(gate, 3).run(fill_commands(k, buf, 0, 4, 0x33333333u));
        EXPECT_EQ(submit(k, {&s}), VK_SUCCESS);
        std::thread releaser([&] {
            std::this_thread::sleep_for(std::chrono::milliseconds(40));
            fn.host_signal(k.d, gate, 3);
        });
        EXPECT_EQ(vkQueueWaitIdle(k.queue), VK_SUCCESS);
        EXPECT_EQ(word(buf, 3), 0x33333333u);
        releaser.join();
        // A second one for vkDeviceWaitIdle.
        Submission t;
        t.wait(gate, 4).run(fill_commands(k, buf, 0, 4, 0x44444444u));
        EXPECT_EQ(submit(k, {&t}), VK_SUCCESS);
        std::thread releaser2([&] {
            std::this_thread::sleep_for(std::chrono::milliseconds(40));
            fn.host_signal(k.d, gate, 4);
        });
        EXPECT_EQ(vkDeviceWaitIdle(k.d), VK_SUCCESS);
        EXPECT_EQ(word(buf, 0), 0x44444444u);
        releaser2.join();
        return words(buf, 4);
    });
}

// vkWaitSemaphores: all vs any, timeout 0 and a short timeout answer VK_TIMEOUT (after about that long), values
// already reached answer VK_SUCCESS at once; initial values and host signals read back.
TEST_F(TimelineSemaphores, WaitSemaphoresAnyAllAndTimeouts) {
    both([](Kit& k) {
        TimelineFns fn(k.d);
        VkSemaphore a = semaphore(k, VK_SEMAPHORE_TYPE_TIMELINE, 3);
        VkSemaphore b = semaphore(k, VK_SEMAPHORE_TYPE_TIMELINE, 0);
        Bytes out;
        append(out, fn.get(k.d, a));
        append(out, fn.get(k.d, b));
        EXPECT_EQ(fn.wait_for(k.d, {a, b}, {2, 1}, false, 0), VK_TIMEOUT);
        const auto t0 = std::chrono::steady_clock::now();
        EXPECT_EQ(fn.wait_for(k.d, {a, b}, {2, 1}, false, kShort), VK_TIMEOUT);
        EXPECT_GE(std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(15));
        EXPECT_EQ(fn.wait_for(k.d, {a, b}, {2, 1}, true, 0), VK_SUCCESS);       // a is past 2
        EXPECT_EQ(fn.wait_for(k.d, {a, b}, {4, 1}, true, kShort), VK_TIMEOUT);  // neither
        EXPECT_EQ(fn.wait_for(k.d, {a}, {3}, false, 0), VK_SUCCESS);            // equal counts
        fn.host_signal(k.d, b, 7);
        EXPECT_EQ(fn.wait_for(k.d, {a, b}, {3, 7}, false, kForever), VK_SUCCESS);
        append(out, fn.get(k.d, b));
        // A host signal from another thread ends an endless wait.
        std::thread later([&] {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            fn.host_signal(k.d, a, 10);
        });
        EXPECT_EQ(fn.wait_for(k.d, {a, b}, {10, 100}, true, kForever), VK_SUCCESS);
        later.join();
        append(out, fn.get(k.d, a));
        return out;
    });
}

// A chain of submissions in one call, each waiting for the value the previous one signals, while another thread
// reads the counter: it never goes down and ends at the last value; every batch's fill landed.
TEST_F(TimelineSemaphores, CountersOnlyGrow) {
    both([](Kit& k) {
        TimelineFns fn(k.d);
        VkSemaphore s = semaphore(k, VK_SEMAPHORE_TYPE_TIMELINE);
        constexpr uint32_t kSteps = 16;
        Device::Buffer buf = k.buffer(kSteps * 4);
        std::vector<Submission> subs(kSteps);
        std::vector<Submission*> ptrs;
        for (uint32_t i = 0; i < kSteps; ++i) {
            // Step 0 waits for 1, which the host signals: the whole chain is wait-before-signal.
            subs[i].wait(s, 2 * i + 1).run(fill_commands(k, buf, i, 1, 100 + i)).signal(s, 2 * i + 3);
            ptrs.push_back(&subs[i]);
        }
        std::atomic<bool> stop{false}, grew_only{true};
        std::thread reader([&] {
            uint64_t last = 0;
            while (!stop.load()) {
                uint64_t v = 0;
                fn.value(k.d, s, &v);
                if (v < last) grew_only = false;
                last = v;
            }
        });
        EXPECT_EQ(submit(k, ptrs), VK_SUCCESS);
        fn.host_signal(k.d, s, 1);
        EXPECT_EQ(fn.wait_for(k.d, {s}, {2 * kSteps + 1}, false, kForever), VK_SUCCESS);
        stop = true;
        reader.join();
        EXPECT_TRUE(grew_only.load());
        for (uint32_t i = 0; i < kSteps; ++i) EXPECT_EQ(word(buf, i), 100 + i);
        Bytes out = words(buf, kSteps);
        append(out, fn.get(k.d, s));
        return out;
    });
}

// Binary and timeline semaphores in the same submissions: the first signals a binary semaphore and a timeline
// value, the second waits for both and signals another value; a third, separate submission waits for the binary
// semaphore the second signals and for a timeline value the host gives later.
TEST_F(TimelineSemaphores, BinaryAndTimelineTogether) {
    both([](Kit& k) {
        TimelineFns fn(k.d);
        VkSemaphore t = semaphore(k, VK_SEMAPHORE_TYPE_TIMELINE);
        VkSemaphore b1 = semaphore(k, VK_SEMAPHORE_TYPE_BINARY);
        VkSemaphore b2 = semaphore(k, VK_SEMAPHORE_TYPE_BINARY);
        VkFence f = fence(k);
        Device::Buffer buf = k.buffer(48);
        Submission one, two, three;
        one.run(fill_commands(k, buf, 0, 12, 0x01010101u)).signal(b1, 0).signal(t, 2);
        two.wait(b1, 0).wait(t, 2).run(fill_commands(k, buf, 4, 8, 0x02020202u)).signal(t, 3).signal(b2, 0);
        three.wait(t, 8).wait(b2, 0).run(fill_commands(k, buf, 8, 4, 0x03030303u)).signal(t, 9);
        EXPECT_EQ(submit(k, {&one, &two}), VK_SUCCESS);
        EXPECT_EQ(submit(k, {&three}, f), VK_SUCCESS);
        EXPECT_EQ(fn.wait_for(k.d, {t}, {3}, false, kForever), VK_SUCCESS);
        Bytes out;
        append(out, fn.get(k.d, t));
        EXPECT_EQ(vkWaitForFences(k.d, 1, &f, VK_TRUE, kShort), VK_TIMEOUT);
        fn.host_signal(k.d, t, 8);
        EXPECT_EQ(vkWaitForFences(k.d, 1, &f, VK_TRUE, kForever), VK_SUCCESS);
        // The fence and the batch's semaphore signals need not become visible together (lavapipe's fence may be
        // seen before t = 9): wait for the value itself before reading it.
        EXPECT_EQ(fn.wait_for(k.d, {t}, {9}, false, kForever), VK_SUCCESS);
        append(out, fn.get(k.d, t));
        EXPECT_EQ(word(buf, 0), 0x01010101u);
        EXPECT_EQ(word(buf, 4), 0x02020202u);
        EXPECT_EQ(word(buf, 8), 0x03030303u);
        const Bytes w = words(buf, 12);
        out.insert(out.end(), w.begin(), w.end());
        return out;
    });
}

class TimelineSemaphoresSync2 : public TimelineSemaphores {
  protected:
    void SetUp() override {
        sync2_.synchronization2 = VK_TRUE;
        features_.pNext = &sync2_;
        TimelineSemaphores::SetUp();
    }
    std::vector<const char*> extensions() const override {
        return {VK_KHR_TIMELINE_SEMAPHORE_EXTENSION_NAME, VK_KHR_SYNCHRONIZATION_2_EXTENSION_NAME};
    }
    VkPhysicalDeviceSynchronization2Features sync2_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES};
};

// vkQueueSubmit2 carries timeline values in VkSemaphoreSubmitInfo: a wait-before-signal batch released by the host.
TEST_F(TimelineSemaphoresSync2, QueueSubmit2TimelineValues) {
    both([](Kit& k) {
        TimelineFns fn(k.d);
        auto submit2 = reinterpret_cast<PFN_vkQueueSubmit2KHR>(vkGetDeviceProcAddr(k.d, "vkQueueSubmit2KHR"));
        EXPECT_NE(submit2, nullptr);
        VkSemaphore t = semaphore(k, VK_SEMAPHORE_TYPE_TIMELINE);
        Device::Buffer buf = k.buffer(16);
        VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
        wait.semaphore = t;
        wait.value = 4;
        wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        VkSemaphoreSubmitInfo signal = wait;
        signal.value = 12;
        VkCommandBufferSubmitInfo cb{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
        cb.commandBuffer = fill_commands(k, buf, 0, 4, 0x55555555u);
        VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        si.waitSemaphoreInfoCount = 1;
        si.pWaitSemaphoreInfos = &wait;
        si.commandBufferInfoCount = 1;
        si.pCommandBufferInfos = &cb;
        si.signalSemaphoreInfoCount = 1;
        si.pSignalSemaphoreInfos = &signal;
        EXPECT_EQ(submit2(k.queue, 1, &si, VK_NULL_HANDLE), VK_SUCCESS);
        EXPECT_EQ(fn.wait_for(k.d, {t}, {12}, false, kShort), VK_TIMEOUT);
        Bytes out = words(buf, 4);
        fn.host_signal(k.d, t, 4);
        EXPECT_EQ(fn.wait_for(k.d, {t}, {12}, false, kForever), VK_SUCCESS);
        EXPECT_EQ(word(buf, 2), 0x55555555u);
        const Bytes w = words(buf, 4);
        out.insert(out.end(), w.begin(), w.end());
        append(out, fn.get(k.d, t));
        return out;
    });
}

}  // namespace
}  // namespace tilevk::test::breadth
