// Preloaded into a windowed program (vkcube) by vkcube_capture_test.py: when the program destroys its window, the
// window is first captured with `xwd` into $TILEVK_CAPTURE_XWD, so the capture holds the last frame the program
// presented, whatever the driver's timing. A round trip first makes sure the X server has executed every request the
// program (and its driver, on the same connection) sent before.
#include <dlfcn.h>
#include <xcb/xcb.h>

#include <cstdio>
#include <cstdlib>

extern "C" __attribute__((visibility("default"))) xcb_void_cookie_t xcb_destroy_window(xcb_connection_t* c,
                                                                                       xcb_window_t window) {
    using DestroyWindow = xcb_void_cookie_t (*)(xcb_connection_t*, xcb_window_t);
    static const auto real = reinterpret_cast<DestroyWindow>(dlsym(RTLD_NEXT, "xcb_destroy_window"));
    const char* out = getenv("TILEVK_CAPTURE_XWD");
    if (out != nullptr && getenv("TILEVK_CAPTURE_DONE") == nullptr) {
        free(xcb_get_input_focus_reply(c, xcb_get_input_focus(c), nullptr));
        char command[4096];
        snprintf(command, sizeof command, "xwd -silent -id %u -out '%s'", unsigned(window), out);
        if (system(command) != 0) fprintf(stderr, "capture_window: '%s' failed\n", command);
        setenv("TILEVK_CAPTURE_DONE", "1", 1);  // the first window only
    }
    return real(c, window);
}
