// X11 windows (VK_KHR_xcb_surface, VK_KHR_xlib_surface): an Xlib surface is presented through the xcb connection
// under its Display. A frame is copied once into a MIT-SHM segment the X server maps read-only and put into the
// window with ShmPutImage; where the server cannot attach the segment (a remote display) or TILEVK_WSI_SHM=0, the
// rows go over the connection with PutImage instead. Every put is a checked request: when it returns, the server has
// read the pixels (the segment may be written again) and a destroyed window shows up as an error.
#define VK_USE_PLATFORM_XCB_KHR
#define VK_USE_PLATFORM_XLIB_KHR
#include <X11/Xlib-xcb.h>
#include <sys/ipc.h>
#include <sys/shm.h>
#include <xcb/shm.h>
#include <xcb/xcb.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "object.h"
#include "vk_names.h"
#include "wsi/dynamic_library.h"
#include "wsi/platform.h"

namespace tilevk::icd::wsi {
namespace {

// The libxcb, libxcb-shm and libX11-xcb functions used here, resolved once per process.
struct XcbLibrary {
    bool core = false;  // libxcb.so.1 with everything below up to `shm_id`
    decltype(&xcb_connection_has_error) connection_has_error;
    decltype(&xcb_get_setup) get_setup;
    decltype(&xcb_setup_roots_iterator) setup_roots_iterator;
    decltype(&xcb_screen_next) screen_next;
    decltype(&xcb_screen_allowed_depths_iterator) screen_allowed_depths_iterator;
    decltype(&xcb_depth_next) depth_next;
    decltype(&xcb_depth_visuals_iterator) depth_visuals_iterator;
    decltype(&xcb_visualtype_next) visualtype_next;
    decltype(&xcb_setup_pixmap_formats) setup_pixmap_formats;
    decltype(&xcb_setup_pixmap_formats_length) setup_pixmap_formats_length;
    decltype(&xcb_get_geometry) get_geometry;
    decltype(&xcb_get_geometry_reply) get_geometry_reply;
    decltype(&xcb_get_window_attributes) get_window_attributes;
    decltype(&xcb_get_window_attributes_reply) get_window_attributes_reply;
    decltype(&xcb_generate_id) generate_id;
    decltype(&xcb_create_gc_checked) create_gc_checked;
    decltype(&xcb_free_gc) free_gc;
    decltype(&xcb_put_image_checked) put_image_checked;
    decltype(&xcb_request_check) request_check;
    decltype(&xcb_get_maximum_request_length) get_maximum_request_length;
    decltype(&xcb_get_extension_data) get_extension_data;
    decltype(&xcb_flush) flush;
    bool shm = false;  // libxcb-shm.so.0
    xcb_extension_t* shm_id;
    decltype(&xcb_shm_attach_checked) shm_attach_checked;
    decltype(&xcb_shm_detach) shm_detach;
    decltype(&xcb_shm_put_image_checked) shm_put_image_checked;
    decltype(&XGetXCBConnection) get_xcb_connection;  // libX11-xcb.so.1, for Xlib surfaces
};

XcbLibrary load_xcb() {
    XcbLibrary x{};
    void* core = open_library("libxcb.so.1");
    x.core = resolve(core, "xcb_connection_has_error", &x.connection_has_error) &&
             resolve(core, "xcb_get_setup", &x.get_setup) &&
             resolve(core, "xcb_setup_roots_iterator", &x.setup_roots_iterator) &&
             resolve(core, "xcb_screen_next", &x.screen_next) &&
             resolve(core, "xcb_screen_allowed_depths_iterator", &x.screen_allowed_depths_iterator) &&
             resolve(core, "xcb_depth_next", &x.depth_next) &&
             resolve(core, "xcb_depth_visuals_iterator", &x.depth_visuals_iterator) &&
             resolve(core, "xcb_visualtype_next", &x.visualtype_next) &&
             resolve(core, "xcb_setup_pixmap_formats", &x.setup_pixmap_formats) &&
             resolve(core, "xcb_setup_pixmap_formats_length", &x.setup_pixmap_formats_length) &&
             resolve(core, "xcb_get_geometry", &x.get_geometry) &&
             resolve(core, "xcb_get_geometry_reply", &x.get_geometry_reply) &&
             resolve(core, "xcb_get_window_attributes", &x.get_window_attributes) &&
             resolve(core, "xcb_get_window_attributes_reply", &x.get_window_attributes_reply) &&
             resolve(core, "xcb_generate_id", &x.generate_id) &&
             resolve(core, "xcb_create_gc_checked", &x.create_gc_checked) && resolve(core, "xcb_free_gc", &x.free_gc) &&
             resolve(core, "xcb_put_image_checked", &x.put_image_checked) &&
             resolve(core, "xcb_request_check", &x.request_check) &&
             resolve(core, "xcb_get_maximum_request_length", &x.get_maximum_request_length) &&
             resolve(core, "xcb_get_extension_data", &x.get_extension_data) && resolve(core, "xcb_flush", &x.flush);
    if (!x.core) log_error("X11 surfaces: libxcb.so.1 could not be opened or lacks a function tilevk uses");
    void* shm = open_library("libxcb-shm.so.0");
    x.shm = resolve(shm, "xcb_shm_id", &x.shm_id) && resolve(shm, "xcb_shm_attach_checked", &x.shm_attach_checked) &&
            resolve(shm, "xcb_shm_detach", &x.shm_detach) &&
            resolve(shm, "xcb_shm_put_image_checked", &x.shm_put_image_checked);
    resolve(open_library("libX11-xcb.so.1"), "XGetXCBConnection", &x.get_xcb_connection);
    return x;
}

const XcbLibrary& xcb() {
    static const XcbLibrary library = load_xcb();
    return library;
}

struct Window {
    xcb_connection_t* connection = nullptr;
    xcb_window_t window = 0;
};

Window window_of(const VkIcdSurfaceBase* surface) {
    if (surface->platform == VK_ICD_WSI_PLATFORM_XCB) {
        const auto* s = reinterpret_cast<const VkIcdSurfaceXcb*>(surface);
        return {s->connection, s->window};
    }
    const auto* s = reinterpret_cast<const VkIcdSurfaceXlib*>(surface);
    return {static_cast<xcb_connection_t*>(xcb_connection_of_xlib(s->dpy)), xcb_window_t(s->window)};
}

bool usable(const Window& w) {
    return xcb().core && w.connection != nullptr && xcb().connection_has_error(w.connection) == 0;
}

// The swapchain formats whose bytes are the pixels of a visual as they are: a TrueColor visual of depth 24 or 32
// whose pixels are 32 bits, 8 bits per channel, little-endian (the server's image byte order), blue in the low byte
// (B8G8R8A8) or red in the low byte (R8G8B8A8). sRGB first, as lavapipe lists them.
std::vector<VkFormat> formats_of(xcb_connection_t* c, const xcb_visualtype_t& v, uint8_t depth) {
    const xcb_setup_t* setup = xcb().get_setup(c);
    if (v._class != XCB_VISUAL_CLASS_TRUE_COLOR || (depth != 24 && depth != 32) || v.bits_per_rgb_value != 8 ||
        setup->image_byte_order != XCB_IMAGE_ORDER_LSB_FIRST) {
        return {};
    }
    const xcb_format_t* f = xcb().setup_pixmap_formats(setup);
    bool bpp32 = false;
    for (int i = 0, n = xcb().setup_pixmap_formats_length(setup); i < n; ++i) {
        bpp32 |= f[i].depth == depth && f[i].bits_per_pixel == 32;
    }
    if (!bpp32) return {};
    if (v.red_mask == 0xff0000 && v.green_mask == 0xff00 && v.blue_mask == 0xff) {
        return {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM};
    }
    if (v.red_mask == 0xff && v.green_mask == 0xff00 && v.blue_mask == 0xff0000) {
        return {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_R8G8B8A8_UNORM};
    }
    return {};
}

// Finds `visual` on the screen whose root is `root` (0: any screen). Returns its depth, or 0 if not found.
uint8_t find_visual(xcb_connection_t* c, xcb_window_t root, xcb_visualid_t visual, xcb_visualtype_t* out) {
    const XcbLibrary& x = xcb();
    for (auto s = x.setup_roots_iterator(x.get_setup(c)); s.rem; x.screen_next(&s)) {
        if (root != 0 && s.data->root != root) continue;
        for (auto d = x.screen_allowed_depths_iterator(s.data); d.rem; x.depth_next(&d)) {
            for (auto v = x.depth_visuals_iterator(d.data); v.rem; x.visualtype_next(&v)) {
                if (v.data->visual_id == visual) {
                    *out = *v.data;
                    return d.data->depth;
                }
            }
        }
    }
    return 0;
}

struct WindowFacts {
    VkExtent2D extent{};
    uint8_t depth = 0;
    std::vector<VkFormat> formats;
};

// The window's size, depth and formats: two requests, one round trip. False when the window is gone.
bool window_facts(const Window& w, WindowFacts* facts) {
    const XcbLibrary& x = xcb();
    const xcb_get_geometry_cookie_t gc = x.get_geometry(w.connection, w.window);
    const xcb_get_window_attributes_cookie_t ac = x.get_window_attributes(w.connection, w.window);
    xcb_get_geometry_reply_t* g = x.get_geometry_reply(w.connection, gc, nullptr);
    xcb_get_window_attributes_reply_t* a = x.get_window_attributes_reply(w.connection, ac, nullptr);
    bool ok = g != nullptr && a != nullptr;
    if (ok) {
        facts->extent = {g->width, g->height};
        xcb_visualtype_t visual{};
        facts->depth = find_visual(w.connection, g->root, a->visual, &visual);
        if (facts->depth != 0) facts->formats = formats_of(w.connection, visual, facts->depth);
    }
    free(g);
    free(a);
    return ok;
}

// TILEVK_WSI_SHM=0 sends frames over the connection even where MIT-SHM works (to test that path).
bool shm_allowed() {
    const char* v = getenv("TILEVK_WSI_SHM");
    return v == nullptr || strcmp(v, "0") != 0;
}

class X11Target final : public PresentTarget {
  public:
    X11Target(const Window& w, uint8_t depth, VkExtent2D extent) : w_(w), depth_(depth), extent_(extent) {}

    ~X11Target() override {
        const XcbLibrary& x = xcb();
        if (usable(w_)) {
            if (segment_ != 0) x.shm_detach(w_.connection, segment_);
            if (gc_ != 0) x.free_gc(w_.connection, gc_);
            x.flush(w_.connection);
        }
        if (shm_ != nullptr) shmdt(shm_);
    }

    VkResult init() {
        const XcbLibrary& x = xcb();
        gc_ = x.generate_id(w_.connection);
        const uint32_t no_exposures = 0;
        if (xcb_generic_error_t* e = x.request_check(
                w_.connection,
                x.create_gc_checked(w_.connection, gc_, w_.window, XCB_GC_GRAPHICS_EXPOSURES, &no_exposures))) {
            free(e);
            gc_ = 0;
            return fail(VK_ERROR_SURFACE_LOST_KHR, "vkCreateSwapchainKHR: the X window is gone");
        }
        if (shm_allowed()) attach_shm();
        return VK_SUCCESS;
    }

    VkResult present(const uint8_t* pixels, size_t pitch) override {
        if (!usable(w_)) return VK_ERROR_SURFACE_LOST_KHR;
        const size_t row = size_t(extent_.width) * 4;
        std::vector<xcb_void_cookie_t> cookies;
        if (shm_ != nullptr) {
            if (pitch == row) {
                memcpy(shm_, pixels, row * extent_.height);
            } else {
                for (uint32_t y = 0; y < extent_.height; ++y) memcpy(shm_ + y * row, pixels + y * pitch, row);
            }
            cookies.push_back(xcb().shm_put_image_checked(w_.connection, w_.window, gc_, uint16_t(extent_.width),
                                                          uint16_t(extent_.height), 0, 0, uint16_t(extent_.width),
                                                          uint16_t(extent_.height), 0, 0, depth_,
                                                          XCB_IMAGE_FORMAT_Z_PIXMAP, 0, segment_, 0));
        } else {
            put_rows(pixels, pitch, &cookies);
        }
        xcb().flush(w_.connection);
        bool lost = false;
        for (xcb_void_cookie_t c : cookies) {
            if (xcb_generic_error_t* e = xcb().request_check(w_.connection, c)) {
                lost = true;
                free(e);
            }
        }
        if (lost && !lost_logged_.exchange(true)) log_error("vkQueuePresentKHR: the X window is gone (surface lost)");
        return lost ? VK_ERROR_SURFACE_LOST_KHR : VK_SUCCESS;
    }

    VkResult check() override {
        if (!usable(w_)) return VK_ERROR_SURFACE_LOST_KHR;
        WindowFacts f;
        if (!window_facts(w_, &f)) return VK_ERROR_SURFACE_LOST_KHR;
        return f.extent.width == extent_.width && f.extent.height == extent_.height ? VK_SUCCESS : VK_SUBOPTIMAL_KHR;
    }

  private:
    // A segment the size of one frame, attached read-only; any failure leaves the PutImage path.
    void attach_shm() {
        const XcbLibrary& x = xcb();
        if (!x.shm) return;
        const xcb_query_extension_reply_t* ext = x.get_extension_data(w_.connection, x.shm_id);
        if (ext == nullptr || !ext->present) return;
        const int id = shmget(IPC_PRIVATE, size_t(extent_.width) * 4 * extent_.height, IPC_CREAT | 0600);
        if (id < 0) return;
        void* addr = shmat(id, nullptr, 0);
        if (addr == reinterpret_cast<void*>(-1)) {  // NOLINT(performance-no-int-to-ptr): shmat's documented failure
            shmctl(id, IPC_RMID, nullptr);
            return;
        }
        const xcb_shm_seg_t seg = x.generate_id(w_.connection);
        xcb_generic_error_t* e = x.request_check(w_.connection, x.shm_attach_checked(w_.connection, seg, id, 1));
        shmctl(id, IPC_RMID, nullptr);  // freed once both sides have detached
        if (e != nullptr) {             // e.g. a server on another machine
            free(e);
            shmdt(addr);
            return;
        }
        shm_ = static_cast<uint8_t*>(addr);
        segment_ = seg;
    }

    // PutImage in bands that fit the server's maximum request length.
    void put_rows(const uint8_t* pixels, size_t pitch, std::vector<xcb_void_cookie_t>* cookies) {
        const size_t row = size_t(extent_.width) * 4;
        const size_t max_bytes = size_t(xcb().get_maximum_request_length(w_.connection)) * 4;
        const size_t header = sizeof(xcb_put_image_request_t);
        const uint32_t band =
            max_bytes > header + row ? uint32_t(std::min<size_t>((max_bytes - header) / row, 65535)) : 1;
        std::vector<uint8_t> packed;  // only when the image's rows are not packed (tilevk's always are)
        for (uint32_t y = 0; y < extent_.height; y += band) {
            const uint32_t rows = std::min(band, extent_.height - y);
            const uint8_t* src = pixels + y * pitch;
            if (pitch != row) {
                packed.resize(row * rows);
                for (uint32_t r = 0; r < rows; ++r) memcpy(packed.data() + r * row, src + r * pitch, row);
                src = packed.data();
            }
            cookies->push_back(xcb().put_image_checked(w_.connection, XCB_IMAGE_FORMAT_Z_PIXMAP, w_.window, gc_,
                                                       uint16_t(extent_.width), uint16_t(rows), 0, int16_t(y), 0,
                                                       depth_, uint32_t(row * rows), src));
        }
    }

    Window w_;
    uint8_t depth_;
    VkExtent2D extent_;
    xcb_gcontext_t gc_ = 0;
    uint8_t* shm_ = nullptr;
    xcb_shm_seg_t segment_ = 0;
    std::atomic<bool> lost_logged_{false};
};

}  // namespace

void* xcb_connection_of_xlib(void* display) {
    const XcbLibrary& x = xcb();
    if (x.get_xcb_connection == nullptr) {
        log_error("Xlib surfaces: libX11-xcb.so.1 (XGetXCBConnection) could not be opened");
        return nullptr;
    }
    return x.get_xcb_connection(static_cast<Display*>(display));
}

bool x11_presentation_supported(void* connection, uint32_t visual_id) {
    auto* c = static_cast<xcb_connection_t*>(connection);
    if (!usable({c, 0})) return false;
    xcb_visualtype_t visual{};
    const uint8_t depth = find_visual(c, 0, visual_id, &visual);
    return depth != 0 && !formats_of(c, visual, depth).empty();
}

VkResult query_x11(const VkIcdSurfaceBase* surface, SurfaceInfo* info) {
    const Window w = window_of(surface);
    WindowFacts f;
    if (!usable(w) || !window_facts(w, &f)) return VK_ERROR_SURFACE_LOST_KHR;
    info->current_extent = f.extent;
    info->has_alpha = f.depth == 32;
    info->opaque_possible = f.depth != 32;
    info->formats = f.formats;  // empty: a visual tilevk cannot present to (the surface is not supported)
    return VK_SUCCESS;
}

VkResult create_x11_target(const VkIcdSurfaceBase* surface, const TargetDesc& desc,
                           std::unique_ptr<PresentTarget>* target) {
    const Window w = window_of(surface);
    WindowFacts f;
    if (!usable(w) || !window_facts(w, &f)) {
        return fail(VK_ERROR_SURFACE_LOST_KHR, "vkCreateSwapchainKHR: the X window or its connection is gone");
    }
    auto t = std::make_unique<X11Target>(w, f.depth, desc.extent);
    if (VkResult r = t->init(); r != VK_SUCCESS) return r;
    *target = std::move(t);
    return VK_SUCCESS;
}

}  // namespace tilevk::icd::wsi
