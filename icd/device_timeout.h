// A GPU-style time limit for submissions (TILEVK_DEVICE_TIMEOUT_MS): a submission that runs longer loses the device.
// arm() starts the clock, disarm() stops it; the flag turns true once the limit has passed while armed. One waiting
// thread per queue sets it, so the checks in the renderer and the shader interpreter (between tiles, between
// shader batches, at loop back edges) are a relaxed load of the flag, never a clock read.
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

namespace tilevk::icd {

// TILEVK_DEVICE_TIMEOUT_MS (a positive number of milliseconds), else the default; a bad value is reported once.
std::chrono::milliseconds device_timeout_from_env();
// 10 s, as amdgpu's default lockup timeout: the limit is wall time, and a loaded host (a CI box running several
// builds) can stretch a submission of ordinary size several times. Sanitizer builds run 3-20x slower again, so
// their default is ten times longer.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr std::chrono::milliseconds kDefaultDeviceTimeout{100000};
#else
inline constexpr std::chrono::milliseconds kDefaultDeviceTimeout{10000};
#endif

class SubmitTimeout {
  public:
    explicit SubmitTimeout(std::chrono::milliseconds limit) : limit_(limit) {}
    ~SubmitTimeout();
    SubmitTimeout(const SubmitTimeout&) = delete;
    SubmitTimeout& operator=(const SubmitTimeout&) = delete;

    void arm();     // clears the flag; it turns true `limit` from now unless disarm() comes first
    void disarm();  // the flag keeps its value
    const std::atomic<bool>* flag() const { return &expired_; }
    bool expired() const { return expired_.load(std::memory_order_relaxed); }
    std::chrono::milliseconds limit() const { return limit_; }

  private:
    void wait_for_deadlines();

    const std::chrono::milliseconds limit_;
    std::mutex mutex_;
    std::condition_variable cv_;
    std::optional<std::chrono::steady_clock::time_point> deadline_;  // armed
    bool quit_ = false;
    std::atomic<bool> expired_{false};
    std::thread thread_;  // started by the first arm()
};

}  // namespace tilevk::icd
