#include "device_timeout.h"

#include <cstdlib>
#include <cstring>

#include "object.h"

namespace tilevk::icd {

std::chrono::milliseconds device_timeout_from_env() {
    const char* env = std::getenv("TILEVK_DEVICE_TIMEOUT_MS");
    if (env == nullptr || *env == '\0') return kDefaultDeviceTimeout;
    char* end = nullptr;
    const long long ms = std::strtoll(env, &end, 10);
    if (*end != '\0' || ms <= 0) {
        static std::atomic<bool> said{false};
        if (!said.exchange(true))
            log_error("TILEVK_DEVICE_TIMEOUT_MS=\"%s\" is not a positive number of milliseconds; using %lld", env,
                      static_cast<long long>(kDefaultDeviceTimeout.count()));
        return kDefaultDeviceTimeout;
    }
    return std::chrono::milliseconds(ms);
}

SubmitTimeout::~SubmitTimeout() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        quit_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
}

void SubmitTimeout::arm() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        expired_.store(false, std::memory_order_relaxed);
        deadline_ = std::chrono::steady_clock::now() + limit_;
        if (!thread_.joinable()) thread_ = std::thread([this] { wait_for_deadlines(); });
    }
    cv_.notify_all();
}

void SubmitTimeout::disarm() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        deadline_.reset();
    }
    cv_.notify_all();
}

void SubmitTimeout::wait_for_deadlines() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!quit_) {
        if (!deadline_) {
            cv_.wait(lock);
        } else if (cv_.wait_until(lock, *deadline_) == std::cv_status::timeout && deadline_ &&
                   std::chrono::steady_clock::now() >= *deadline_) {
            expired_.store(true, std::memory_order_relaxed);
            deadline_.reset();
        }
    }
}

}  // namespace tilevk::icd
