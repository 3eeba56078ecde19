// Window-system libraries are opened at run time (dlopen), not linked: the ICD then loads, and renders offscreen, on
// machines without libxcb or libwayland-client, and a program that never makes a surface never maps them. A surface
// of a window system exists only in a process that already has its library loaded, so opening it there succeeds.
#pragma once
#include <dlfcn.h>

namespace tilevk::icd::wsi {

// Resolves `name` from `library` into `*fn` (typed as the library's own declaration, `decltype(&xcb_flush)`).
// False (and *fn nullptr) when missing.
template <class Fn>
bool resolve(void* library, const char* name, Fn* fn) {
    *fn = library != nullptr ? reinterpret_cast<Fn>(dlsym(library, name)) : nullptr;
    return *fn != nullptr;
}

// dlopen with the flags every window-system library is opened with: resolved now, symbols kept local.
inline void* open_library(const char* soname) {
    return dlopen(soname, RTLD_NOW | RTLD_LOCAL);
}

}  // namespace tilevk::icd::wsi
