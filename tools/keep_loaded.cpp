// LD_PRELOAD shim for the ASan runs of tools/run_sanitizers.sh: dlclose() does nothing, so every library a test
// loads (the ICDs and layers the Vulkan loader opens, lavapipe's LLVM) stays mapped until the process exits.
//
// Why: LeakSanitizer checks at exit, after the loader has dlclose'd the drivers and layers. Two things then go
// wrong: memory that an unloaded library still pointed to from its globals is no longer reachable and is reported
// as leaked, and the frames of an unloaded library symbolize as "<unknown module>", so the suppressions in
// tools/lsan.supp, which name the library, cannot match. With the libraries kept loaded, their globals stay roots
// and LSan names the module of every frame: a leak of ours can be told from one of theirs.
//
// Built by the script without sanitizer flags: it is also preloaded into uninstrumented programs (python3 running
// the tests that drive tilevk-cts), which must not pull in the ASan runtime.
extern "C" int dlclose(void* /*handle*/) { return 0; }
