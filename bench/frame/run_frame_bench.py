#!/usr/bin/python3
"""The frame benchmark: tilevk and lavapipe alternating, one process per driver and run, same thread count.

    bench/frame/run_frame_bench.py --build build --out report/frame_bench.json

For every scene, `--rounds` rounds each run tilevk-frame-bench once per driver (the order alternates between
rounds), each process timing `--frames` whole frames after `--warmup` frames. Per driver: the median of all its
timed frames, each round's median (the spread), the median peak RSS and the cold pipeline + first frame. The
ratio is tilevk's median / lavapipe's; the per-round ratios show how far one round can be trusted. One more tilevk
process per scene runs with TILEVK_STAGE_TIMES (the stage timers of rast/render and icd/) for the time per stage;
its frames are not in the table (the timers cost a little). `--scaling` times some scenes at 1, 2 and all
hardware threads on both drivers. Every process reads back its final image: the table says whether tilevk's and
lavapipe's images are identical.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

DEFAULT_SCENES = [
    "tri4_flat", "tri16_flat", "tri64_flat", "tri4_smooth", "tri16_smooth", "tri64_smooth", "tri4_depth",
    "tri16_depth", "tri64_depth", "blend16", "msaa4_tri16", "meshes_lit", "draws1000", "large_textured",
    "tri16_flat@1024x1024", "blend16@1024x1024", "meshes_lit@1024x1024",
    "compute_saxpy", "compute_histogram256", "compute_matmul512",
]
DEFAULT_SCALING = ["tri16_flat", "blend16", "meshes_lit"]
DRIVERS = ["tilevk", "llvmpipe"]
BASELINE = {}  # --baseline-icd: "baseline" = device tilevk loaded from another manifest (a build before a change)


TRIANGLES = []  # ["--triangles", N] when --triangles is given


def run_process(binary, driver, scene, threads, frames, warmup, extra_env=None, timeout=900):
    env = dict(os.environ)
    env.pop("VK_ICD_FILENAMES", None)  # the bench loads the one driver's manifest
    if driver == "baseline":
        env["VK_ICD_FILENAMES"] = BASELINE["icd"]
        driver = "tilevk"
    env["TILEVK_THREADS"] = str(threads)
    env["LP_NUM_THREADS"] = str(threads)
    env.pop("TILEVK_STAGE_TIMES", None)
    if extra_env:
        env.update(extra_env)
    cmd = [binary, "--device", driver, "--scene", scene, "--frames", str(frames), "--warmup", str(warmup)] + TRIANGLES
    p = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=timeout)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}): {p.stderr.strip()[-500:]}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def stage_times(binary, scene, threads, frames, warmup):
    """Median nanoseconds per stage over the timed frames of one tilevk process with the stage timers on."""
    fd, path = tempfile.mkstemp(prefix="tilevk-stages-", suffix=".jsonl")
    os.close(fd)
    os.unlink(path)
    try:
        r = run_process(binary, "tilevk", scene, threads, frames, warmup, {"TILEVK_STAGE_TIMES": path})
        with open(path) as f:
            lines = [json.loads(l) for l in f if l.strip()]
    finally:
        if os.path.exists(path):
            os.unlink(path)
    # One line per vkQueueSubmit; the last one is the read-back, the `frames` before it the timed frames.
    timed = lines[-(frames + 1):-1]
    if len(timed) != frames:
        raise RuntimeError(f"stage timers of {scene}: {len(lines)} submits, expected at least {frames + 1}")
    keys = list(timed[0].keys())
    return {k: statistics.median(l[k] for l in timed) / 1e6 for k in keys}, statistics.median(r["frames_ms"])


def summarise(scene, runs):
    out = {"scene": scene, "description": runs["tilevk"][0]["description"]}
    for d in DRIVERS:
        rs = runs[d]
        frames = [t for r in rs for t in r["frames_ms"]]
        med = [statistics.median(r["frames_ms"]) for r in rs]
        out[d] = {
            "median_ms": statistics.median(frames),
            "round_medians_ms": med,
            "spread": (max(med) - min(med)) / statistics.median(frames) if frames else 0,
            "min_ms": min(frames),
            "cpu_ms": statistics.median(t for r in rs for t in r["cpu_ms"]),
            "peak_rss_mb": statistics.median(r["peak_rss_kb"] for r in rs) / 1024,
            "base_rss_mb": statistics.median(r["base_rss_kb"] for r in rs) / 1024,
            "cold_ms": statistics.median(r["cold_pipeline_ms"] + r["first_frame_ms"] for r in rs),
            "minor_faults_per_frame": statistics.median(r["minor_faults_per_frame"] for r in rs),
            "allocations_per_frame": (statistics.median(r["allocations_per_frame"] for r in rs)
                                      if all(r.get("allocations_per_frame") is not None for r in rs) else None),
            "image_hash": rs[-1]["image_hash"],
            "device_name": rs[0]["device_name"],
        }
        out["triangles"] = rs[0]["triangles"]
        out["draws"] = rs[0]["draws"]
        out["size"] = f'{rs[0]["width"]}x{rs[0]["height"]}' + (f' {rs[0]["samples"]}x' if rs[0]["samples"] > 1 else "")
    t, l = out["tilevk"], out["llvmpipe"]
    out["ratio"] = t["median_ms"] / l["median_ms"]
    out["cpu_ratio"] = t["cpu_ms"] / l["cpu_ms"] if l["cpu_ms"] > 0 else None
    out["round_ratios"] = [a / b for a, b in zip(t["round_medians_ms"], l["round_medians_ms"])]
    out["rss_ratio"] = t["peak_rss_mb"] / l["peak_rss_mb"]
    out["cold_ratio"] = t["cold_ms"] / l["cold_ms"]
    out["images_identical"] = len({r["image_hash"] for d in DRIVERS for r in runs[d]}) == 1
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", required=True)
    ap.add_argument("--scenes", default=",".join(DEFAULT_SCENES))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--frames", type=int, default=5)
    ap.add_argument("--warmup", type=int, default=1)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--scaling", default=",".join(DEFAULT_SCALING), help="scenes timed at 1, 2 and all threads")
    ap.add_argument("--triangles", type=int, help="triangles of the small-triangle scenes (default 100000)")
    ap.add_argument("--baseline-icd", help="also time tilevk from this manifest (before/after a change): "
                    "the rounds alternate all three, the table gains tilevk / baseline")
    ap.add_argument("--no-stages", action="store_true")
    ap.add_argument("--require-identical", action="store_true",
                    help="exit 1 unless every scene's images are identical on both drivers (the smoke test)")
    args = ap.parse_args()
    binary = os.path.join(args.build, "bench", "frame", "tilevk-frame-bench")
    if args.triangles:
        TRIANGLES[:] = ["--triangles", str(args.triangles)]
    drivers = list(DRIVERS)
    if args.baseline_icd:
        BASELINE["icd"] = os.path.abspath(args.baseline_icd)
        drivers.append("baseline")
    scenes = [s for s in args.scenes.split(",") if s]
    started = time.time()
    result = {
        "command": " ".join(sys.argv),
        "threads": args.threads,
        "rounds": args.rounds,
        "frames": args.frames,
        "warmup": args.warmup,
        "hardware_threads": os.cpu_count(),
        "load_average_start": os.getloadavg()[0],
        "scenes": [],
        "scaling": [],
    }
    for scene in scenes:
        runs = {d: [] for d in drivers}
        for r in range(args.rounds):
            order = drivers if r % 2 == 0 else drivers[::-1]
            for d in order:
                runs[d].append(run_process(binary, d, scene, args.threads, args.frames, args.warmup))
        s = summarise(scene, runs)
        if args.baseline_icd:
            base = [t for r in runs["baseline"] for t in r["frames_ms"]]
            s["baseline_median_ms"] = statistics.median(base)
            s["vs_baseline"] = s["tilevk"]["median_ms"] / s["baseline_median_ms"]
            s["baseline_cpu_ms"] = statistics.median(t for r in runs["baseline"] for t in r["cpu_ms"])
            s["cpu_vs_baseline"] = s["tilevk"]["cpu_ms"] / s["baseline_cpu_ms"]
            s["vs_baseline_rounds"] = [statistics.median(a["frames_ms"]) / statistics.median(b["frames_ms"])
                                       for a, b in zip(runs["tilevk"], runs["baseline"])]
            s["baseline_images_identical"] = {r["image_hash"] for r in runs["baseline"]} == {
                r["image_hash"] for r in runs["tilevk"]}
        if not s["images_identical"] or (args.baseline_icd and not s["baseline_images_identical"]):
            hashes = {d: sorted({r["image_hash"] for r in runs[d]}) for d in drivers}
            print(f"frame-bench: MISMATCH in {scene}: the images are not identical (" +
                  ", ".join(f"{d} {'/'.join(h)}" for d, h in hashes.items()) +
                  "); tilevk-frame-bench --dump FILE.ppm --draws LIST narrows it down", file=sys.stderr, flush=True)
        # The stage timers time rasterization stages; a compute scene (one dispatch) has none of them.
        if not args.no_stages and not scene.startswith("compute_"):
            s["stages_ms"], s["stage_run_frame_ms"] = stage_times(binary, scene, args.threads, args.frames,
                                                                   args.warmup)
        result["scenes"].append(s)
        print(f"frame-bench: {scene}: tilevk {s['tilevk']['median_ms']:.1f} ms, lavapipe "
              f"{s['llvmpipe']['median_ms']:.1f} ms, ratio {s['ratio']:.2f} (rounds "
              f"{', '.join(f'{x:.2f}' for x in s['round_ratios'])}; CPU {s['tilevk']['cpu_ms']:.0f} / "
              f"{s['llvmpipe']['cpu_ms']:.0f} ms = {s['cpu_ratio']:.2f}), images "
              f"{'identical' if s['images_identical'] else 'DIFFER (MISMATCH)'}" +
              (f"; vs baseline {s['vs_baseline']:.2f}, CPU {s['cpu_vs_baseline']:.2f} (rounds "
               f"{', '.join(f'{x:.2f}' for x in s['vs_baseline_rounds'])}; baseline {s['baseline_median_ms']:.1f} ms)"
               if args.baseline_icd else ""), flush=True)
    threads = sorted({1, 2, os.cpu_count() or 2})
    for scene in [s for s in args.scaling.split(",") if s]:
        for t in threads:
            row = {"scene": scene, "threads": t}
            for d in DRIVERS:
                r = run_process(binary, d, scene, t, args.frames, args.warmup)
                row[d + "_ms"] = statistics.median(r["frames_ms"])
            result["scaling"].append(row)
            print(f"frame-bench: scaling {scene} {t} thread(s): tilevk {row['tilevk_ms']:.1f} ms, lavapipe "
                  f"{row['llvmpipe_ms']:.1f} ms", flush=True)
    result["load_average_end"] = os.getloadavg()[0]
    result["seconds"] = time.time() - started
    with open(args.out, "w") as f:
        json.dump(result, f, indent=1)
    print(f"frame-bench: {len(result['scenes'])} scenes in {result['seconds']:.0f} s -> {args.out}")
    differ = [s["scene"] for s in result["scenes"] if not s["images_identical"]]
    if differ:
        print(f"frame-bench: MISMATCH: tilevk's images differ from lavapipe's in {len(differ)} of "
              f"{len(result['scenes'])} scene(s): {', '.join(differ)}", file=sys.stderr)
    if args.require_identical and differ:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
