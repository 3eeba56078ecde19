#!/usr/bin/python3
"""A steady frame allocates nothing: every frame-benchmark scene, on tilevk, at 1 and 3 threads, after two
warm-up frames, must make zero heap allocations (malloc, calloc, realloc, the aligned variants, operator new: the
benchmark's counting allocator, alloc_count.cpp, sees every thread and library of the process) in the frames that
follow. Minor page faults per frame are printed beside (not judged: the kernel may fault pages back in at will).

    bench/frame/steady_frame_test.py BUILD_DIR

Exit 0: every frame allocation-free; 1: some allocated (each listed); 77 (meson's skip): a sanitizer build, where
the counting allocator is not built.
"""
import json
import os
import subprocess
import sys

SCENES = ["tri4_flat@320x240", "tri16_smooth@320x240", "tri64_depth@320x240", "blend16@320x240",
          "msaa4_tri16@320x240", "meshes_lit@320x240", "draws1000@640x480", "large_textured@320x240",
          "compute_saxpy", "compute_histogram256"]


def main():
    build = sys.argv[1]
    binary = os.path.join(build, "bench", "frame", "tilevk-frame-bench")
    failures = []
    for threads in (1, 3):
        for scene in SCENES:
            env = dict(os.environ, TILEVK_THREADS=str(threads))
            cmd = [binary, "--device", "tilevk", "--scene", scene, "--frames", "6", "--warmup", "2",
                   "--triangles", "4000"]
            p = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=600)
            if p.returncode != 0:
                failures.append(f"{scene} at {threads} threads: the benchmark failed: {p.stderr.strip()[-300:]}")
                continue
            r = json.loads(p.stdout.strip().splitlines()[-1])
            allocs = r["allocations_per_frame"]
            if allocs is None:
                print("steady_frame_test: this build does not count allocations (sanitizers); skipped")
                return 77
            print(f"{scene:26s} {threads} thread(s): {allocs:g} allocations, "
                  f"{r['minor_faults_per_frame']:g} minor page faults per frame")
            if allocs != 0:
                failures.append(f"{scene} at {threads} threads: {allocs:g} allocations per steady frame")
    for f in failures:
        print("steady_frame_test: FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
