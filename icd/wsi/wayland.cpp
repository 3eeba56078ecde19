// Wayland surfaces (VK_KHR_wayland_surface): frames go into wl_shm buffers (a memfd shared with the compositor),
// three per swapchain, each reused once the compositor has released it. All of tilevk's Wayland objects live on a
// private event queue, so the application's own event dispatching never sees them, and tilevk never dispatches the
// application's. Requests are sent with wl_proxy_marshal_flags and the opcodes of wayland-client-protocol.h (the
// header's inline request wrappers would have to be linked against libwayland-client, which is opened at run time).
#define VK_USE_PLATFORM_WAYLAND_KHR
#include <poll.h>
#include <sys/mman.h>
#include <unistd.h>
#include <wayland-client-core.h>
#include <wayland-client-protocol.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <vector>

#include "object.h"
#include "wsi/dynamic_library.h"
#include "wsi/platform.h"
#include "wsi/swapchain.h"

namespace tilevk::icd::wsi {
namespace {

struct WaylandLibrary {
    bool ok = false;
    decltype(&wl_display_create_queue) create_queue;
    decltype(&wl_event_queue_destroy) queue_destroy;
    decltype(&wl_proxy_create_wrapper) create_wrapper;
    decltype(&wl_proxy_wrapper_destroy) wrapper_destroy;
    decltype(&wl_proxy_set_queue) set_queue;
    decltype(&wl_proxy_add_listener) add_listener;
    decltype(&wl_proxy_marshal_flags) marshal_flags;
    decltype(&wl_proxy_destroy) proxy_destroy;
    decltype(&wl_proxy_get_version) get_version;
    decltype(&wl_display_roundtrip_queue) roundtrip_queue;
    decltype(&wl_display_dispatch_queue_pending) dispatch_queue_pending;
    decltype(&wl_display_prepare_read_queue) prepare_read_queue;
    decltype(&wl_display_read_events) read_events;
    decltype(&wl_display_cancel_read) cancel_read;
    decltype(&wl_display_flush) flush;
    decltype(&wl_display_get_fd) get_fd;
    decltype(&wl_display_get_error) get_error;
    const wl_interface* registry_interface;
    const wl_interface* shm_interface;
    const wl_interface* shm_pool_interface;
    const wl_interface* buffer_interface;
};

WaylandLibrary load_wayland() {
    WaylandLibrary w;
    void* lib = open_library("libwayland-client.so.0");
    w.ok = resolve(lib, "wl_display_create_queue", &w.create_queue) &&
           resolve(lib, "wl_event_queue_destroy", &w.queue_destroy) &&
           resolve(lib, "wl_proxy_create_wrapper", &w.create_wrapper) &&
           resolve(lib, "wl_proxy_wrapper_destroy", &w.wrapper_destroy) &&
           resolve(lib, "wl_proxy_set_queue", &w.set_queue) && resolve(lib, "wl_proxy_add_listener", &w.add_listener) &&
           resolve(lib, "wl_proxy_marshal_flags", &w.marshal_flags) &&
           resolve(lib, "wl_proxy_destroy", &w.proxy_destroy) && resolve(lib, "wl_proxy_get_version", &w.get_version) &&
           resolve(lib, "wl_display_roundtrip_queue", &w.roundtrip_queue) &&
           resolve(lib, "wl_display_dispatch_queue_pending", &w.dispatch_queue_pending) &&
           resolve(lib, "wl_display_prepare_read_queue", &w.prepare_read_queue) &&
           resolve(lib, "wl_display_read_events", &w.read_events) &&
           resolve(lib, "wl_display_cancel_read", &w.cancel_read) && resolve(lib, "wl_display_flush", &w.flush) &&
           resolve(lib, "wl_display_get_fd", &w.get_fd) && resolve(lib, "wl_display_get_error", &w.get_error) &&
           resolve(lib, "wl_registry_interface", &w.registry_interface) &&
           resolve(lib, "wl_shm_interface", &w.shm_interface) &&
           resolve(lib, "wl_shm_pool_interface", &w.shm_pool_interface) &&
           resolve(lib, "wl_buffer_interface", &w.buffer_interface);
    if (!w.ok)
        log_error("Wayland surfaces: libwayland-client.so.0 could not be opened or lacks a function tilevk uses");
    return w;
}

const WaylandLibrary& wl() {
    static const WaylandLibrary library = load_wayland();
    return library;
}

wl_proxy* proxy(void* p) {
    return static_cast<wl_proxy*>(p);
}

// wl_shm bound on a private queue, with the pixel formats the compositor announced.
class Shm {
  public:
    explicit Shm(wl_display* display) : display_(display) {}
    ~Shm() {
        if (shm_ != nullptr) wl().proxy_destroy(proxy(shm_));
        if (registry_ != nullptr) wl().proxy_destroy(proxy(registry_));
        if (wrapper_ != nullptr) wl().wrapper_destroy(wrapper_);
        if (queue_ != nullptr) wl().queue_destroy(queue_);
    }
    Shm(const Shm&) = delete;
    Shm& operator=(const Shm&) = delete;

    // Binds wl_shm and collects its formats: two round trips on the private queue.
    bool open() {
        const WaylandLibrary& w = wl();
        if (!w.ok || display_ == nullptr || w.get_error(display_) != 0) return false;
        queue_ = w.create_queue(display_);
        wrapper_ = static_cast<wl_display*>(w.create_wrapper(display_));
        if (queue_ == nullptr || wrapper_ == nullptr) return false;
        w.set_queue(proxy(wrapper_), queue_);
        registry_ = reinterpret_cast<wl_registry*>(w.marshal_flags(proxy(wrapper_), WL_DISPLAY_GET_REGISTRY,
                                                                   w.registry_interface, w.get_version(proxy(wrapper_)),
                                                                   0, nullptr));
        static const wl_registry_listener kRegistry = {&Shm::on_global, &Shm::on_global_remove};
        w.add_listener(proxy(registry_),
                       reinterpret_cast<void (**)(void)>(const_cast<wl_registry_listener*>(&kRegistry)), this);
        if (w.roundtrip_queue(display_, queue_) < 0 || shm_ == nullptr) return false;
        static const wl_shm_listener kShm = {&Shm::on_format};
        w.add_listener(proxy(shm_), reinterpret_cast<void (**)(void)>(const_cast<wl_shm_listener*>(&kShm)), this);
        return w.roundtrip_queue(display_, queue_) >= 0;
    }

    bool has(uint32_t format) const {
        // ARGB8888 and XRGB8888 are required of every compositor; the others only when announced.
        return format == WL_SHM_FORMAT_ARGB8888 || format == WL_SHM_FORMAT_XRGB8888 ||
               std::find(formats_.begin(), formats_.end(), format) != formats_.end();
    }
    wl_display* display() const { return display_; }
    wl_event_queue* queue() const { return queue_; }
    wl_shm* shm() const { return shm_; }

  private:
    static void on_global(void* data, wl_registry* registry, uint32_t name, const char* interface, uint32_t) {
        auto* self = static_cast<Shm*>(data);
        const WaylandLibrary& w = wl();
        if (self->shm_ == nullptr && strcmp(interface, w.shm_interface->name) == 0) {
            self->shm_ = reinterpret_cast<wl_shm*>(w.marshal_flags(proxy(registry), WL_REGISTRY_BIND, w.shm_interface,
                                                                   1, 0, name, w.shm_interface->name, 1u, nullptr));
        }
    }
    static void on_global_remove(void*, wl_registry*, uint32_t) {}
    static void on_format(void* data, wl_shm*, uint32_t format) { static_cast<Shm*>(data)->formats_.push_back(format); }

    wl_display* display_;
    wl_event_queue* queue_ = nullptr;
    wl_display* wrapper_ = nullptr;
    wl_registry* registry_ = nullptr;
    wl_shm* shm_ = nullptr;
    std::vector<uint32_t> formats_;
};

uint32_t shm_format(VkFormat format, VkCompositeAlphaFlagBitsKHR alpha) {
    const bool opaque = alpha == VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    const bool bgra = format == VK_FORMAT_B8G8R8A8_UNORM || format == VK_FORMAT_B8G8R8A8_SRGB;
    // wl_shm formats name a little-endian 32-bit pixel from its high byte: ARGB8888 is bytes B, G, R, A in memory.
    if (bgra) return opaque ? WL_SHM_FORMAT_XRGB8888 : WL_SHM_FORMAT_ARGB8888;
    return opaque ? WL_SHM_FORMAT_XBGR8888 : WL_SHM_FORMAT_ABGR8888;
}

class WaylandTarget final : public PresentTarget {
  public:
    WaylandTarget(wl_display* display, wl_surface* surface, VkExtent2D extent)
        : shm_(display), surface_(surface), extent_(extent) {}

    ~WaylandTarget() override {
        for (Buffer& b : buffers_) {
            if (b.buffer != nullptr) {
                wl().marshal_flags(proxy(b.buffer), WL_BUFFER_DESTROY, nullptr, wl().get_version(proxy(b.buffer)),
                                   WL_MARSHAL_FLAG_DESTROY);
            }
        }
        if (shm_.display() != nullptr && wl().ok) wl().flush(shm_.display());
        if (memory_ != nullptr) munmap(memory_, bytes_);
    }

    VkResult init(uint32_t format) {
        const WaylandLibrary& w = wl();
        if (!shm_.open())
            return fail(VK_ERROR_SURFACE_LOST_KHR, "vkCreateSwapchainKHR: no wl_shm on the Wayland display");
        if (!shm_.has(format)) {
            return fail(VK_ERROR_INITIALIZATION_FAILED, "vkCreateSwapchainKHR: the compositor lacks wl_shm format 0x%x",
                        format);
        }
        const size_t frame = size_t(extent_.width) * 4 * extent_.height;
        bytes_ = frame * kBuffers;
        const int fd = memfd_create("tilevk-wsi", MFD_CLOEXEC);
        if (fd < 0 || ftruncate(fd, off_t(bytes_)) != 0) {
            if (fd >= 0) close(fd);
            return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateSwapchainKHR: cannot make %zu bytes of wl_shm memory",
                        bytes_);
        }
        void* map = mmap(nullptr, bytes_, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
        if (map == MAP_FAILED) {
            close(fd);
            return fail(VK_ERROR_OUT_OF_HOST_MEMORY, "vkCreateSwapchainKHR: cannot map wl_shm memory");
        }
        memory_ = static_cast<uint8_t*>(map);
        wl_proxy* pool = w.marshal_flags(proxy(shm_.shm()), WL_SHM_CREATE_POOL, w.shm_pool_interface,
                                         w.get_version(proxy(shm_.shm())), 0, nullptr, fd, int32_t(bytes_));
        static const wl_buffer_listener kBuffer = {&WaylandTarget::on_release};
        for (uint32_t i = 0; i < kBuffers; ++i) {
            buffers_[i].buffer = reinterpret_cast<wl_buffer*>(
                w.marshal_flags(pool, WL_SHM_POOL_CREATE_BUFFER, w.buffer_interface, w.get_version(pool), 0, nullptr,
                                int32_t(frame * i), int32_t(extent_.width), int32_t(extent_.height),
                                int32_t(extent_.width * 4), format));
            w.add_listener(proxy(buffers_[i].buffer),
                           reinterpret_cast<void (**)(void)>(const_cast<wl_buffer_listener*>(&kBuffer)), &buffers_[i]);
        }
        w.marshal_flags(pool, WL_SHM_POOL_DESTROY, nullptr, w.get_version(pool), WL_MARSHAL_FLAG_DESTROY);
        close(fd);  // the pool's buffers keep the memory
        w.flush(shm_.display());
        return w.get_error(shm_.display()) == 0 ? VK_SUCCESS : VK_ERROR_SURFACE_LOST_KHR;
    }

    VkResult present(const uint8_t* pixels, size_t pitch) override {
        const WaylandLibrary& w = wl();
        if (w.get_error(shm_.display()) != 0) return VK_ERROR_SURFACE_LOST_KHR;
        pump(0);
        Buffer* free_buffer = find_free();
        // A compositor holds a buffer until a newer one replaces it; with three there is normally one free. A busy
        // compositor (a loaded machine) may need several refreshes to release one, and a hidden surface may keep
        // them: wait up to a second (or four refreshes, if longer), then drop this frame rather than block forever.
        const auto give_up = std::chrono::steady_clock::now() + std::max<std::chrono::steady_clock::duration>(
                                                                    4 * refresh_interval(), std::chrono::seconds(1));
        while (free_buffer == nullptr && std::chrono::steady_clock::now() < give_up) {
            pump(int(std::chrono::duration_cast<std::chrono::milliseconds>(refresh_interval()).count()) + 1);
            free_buffer = find_free();
        }
        if (free_buffer == nullptr) return VK_SUCCESS;
        const size_t row = size_t(extent_.width) * 4;
        uint8_t* dst = memory_ + row * extent_.height * size_t(free_buffer - buffers_);
        if (pitch == row) {
            memcpy(dst, pixels, row * extent_.height);
        } else {
            for (uint32_t y = 0; y < extent_.height; ++y) memcpy(dst + y * row, pixels + y * pitch, row);
        }
        free_buffer->busy = true;
        const uint32_t version = w.get_version(proxy(surface_));
        w.marshal_flags(proxy(surface_), WL_SURFACE_ATTACH, nullptr, version, 0, free_buffer->buffer, 0, 0);
        w.marshal_flags(proxy(surface_), version >= 4 ? WL_SURFACE_DAMAGE_BUFFER : WL_SURFACE_DAMAGE, nullptr, version,
                        0, 0, 0, int32_t(extent_.width), int32_t(extent_.height));
        w.marshal_flags(proxy(surface_), WL_SURFACE_COMMIT, nullptr, version, 0);
        w.flush(shm_.display());
        return w.get_error(shm_.display()) == 0 ? VK_SUCCESS : VK_ERROR_SURFACE_LOST_KHR;
    }

    VkResult check() override { return wl().get_error(shm_.display()) == 0 ? VK_SUCCESS : VK_ERROR_SURFACE_LOST_KHR; }

  private:
    static constexpr uint32_t kBuffers = 3;
    struct Buffer {
        wl_buffer* buffer = nullptr;
        std::atomic<bool> busy{false};
    };
    static void on_release(void* data, wl_buffer*) { static_cast<Buffer*>(data)->busy = false; }

    Buffer* find_free() {
        for (Buffer& b : buffers_) {
            if (!b.busy) return &b;
        }
        return nullptr;
    }

    // Reads and dispatches tilevk's queue, waiting up to `timeout_ms` for the compositor (the read protocol that lets
    // the application read its own queue on other threads at the same time).
    void pump(int timeout_ms) {
        const WaylandLibrary& w = wl();
        wl_display* d = shm_.display();
        while (w.prepare_read_queue(d, shm_.queue()) != 0) w.dispatch_queue_pending(d, shm_.queue());
        w.flush(d);
        pollfd p{w.get_fd(d), POLLIN, 0};
        if (poll(&p, 1, timeout_ms) > 0) {
            w.read_events(d);
        } else {
            w.cancel_read(d);
        }
        w.dispatch_queue_pending(d, shm_.queue());
    }

    Shm shm_;
    wl_surface* surface_;
    VkExtent2D extent_;
    Buffer buffers_[kBuffers];
    uint8_t* memory_ = nullptr;
    size_t bytes_ = 0;
};

}  // namespace

VkResult query_wayland(const VkIcdSurfaceBase* surface, SurfaceInfo* info) {
    Shm shm(reinterpret_cast<const VkIcdSurfaceWayland*>(surface)->display);
    if (!shm.open()) return VK_ERROR_SURFACE_LOST_KHR;
    info->current_extent = {kExtentFromSwapchain, kExtentFromSwapchain};
    info->has_alpha = true;
    info->opaque_possible = true;
    info->formats = {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM};
    if (shm.has(WL_SHM_FORMAT_ABGR8888) && shm.has(WL_SHM_FORMAT_XBGR8888)) {
        info->formats.push_back(VK_FORMAT_R8G8B8A8_SRGB);
        info->formats.push_back(VK_FORMAT_R8G8B8A8_UNORM);
    }
    return VK_SUCCESS;
}

VkResult create_wayland_target(const VkIcdSurfaceBase* surface, const TargetDesc& desc,
                               std::unique_ptr<PresentTarget>* target) {
    const auto* s = reinterpret_cast<const VkIcdSurfaceWayland*>(surface);
    auto t = std::make_unique<WaylandTarget>(s->display, s->surface, desc.extent);
    if (VkResult r = t->init(shm_format(desc.format, desc.composite_alpha)); r != VK_SUCCESS) return r;
    *target = std::move(t);
    return VK_SUCCESS;
}

}  // namespace tilevk::icd::wsi
