"""Runs make_report.py on a small fake result set in a temporary directory and checks what it wrote."""
import json
import os
import subprocess
import sys
import tempfile

script = sys.argv[1]


def case(name, status, ours, ref, diff=0, reason=""):
    return {"name": name, "status": status, "reason": reason, "note": "", "differing": diff, "total": 4096,
            "max_error": 3 if diff else 0, "check": "none", "ours_ms": ours, "ref_ms": ref,
            "ours_pipeline_ms": 1.5, "ref_pipeline_ms": 3.0, "seconds": 0.1}


def run(rast_method, cases, found=True):
    return {"device": "tilevk", "ref": "llvmpipe", "device_name": "tilevk (fake)", "ref_name": "llvmpipe (fake)",
            "device_found": found, "rast_method": rast_method, "threads": "LP_NUM_THREADS=2 TILEVK_THREADS=2",
            "icd_filenames": "", "timing_reps": 3, "complete": True, "running": "", "cases": cases}


with tempfile.TemporaryDirectory() as tmp:
    runs = [
        run("hier", [case("api.smoke.triangle", "Pass", 1.0, 2.0), case("compute.atomic.buffer.add", "Pass", 1.0, 2.0),
                     case("rasterization.culling.back_ccw_fan", "Fail", 4.0, 2.0, 17, "color: 17 of 4096 differ"),
                     case("depth.compare.d16_less", "NotSupported", -1, -1, reason="tilevk: format")]),
        run("bbox", [case("api.smoke.triangle", "Pass", 3.0, 2.0), case("compute.atomic.buffer.add", "Pass", 1.0, 2.0),
                     case("rasterization.culling.back_ccw_fan", "Pass", 3.0, 2.0),
                     case("depth.compare.d16_less", "Pass", 3.0, 2.0)]),
    ]
    paths = []
    for i, r in enumerate(runs):
        p = os.path.join(tmp, f"results-{i}.json")
        with open(p, "w") as f:
            json.dump(r, f)
        paths.append(p)
    sweep = os.path.join(tmp, "sweep.csv")
    with open(sweep, "w") as f:
        f.write("offset,reference,hier\n0,0,0\n0.5,0,2\n1,0,1\n")
    out = os.path.join(tmp, "report")
    subprocess.run([sys.executable, script, "--out", out, "--stability", sweep] + paths, check=True)
    summary = open(os.path.join(out, "summary.md")).read()
    html = open(os.path.join(out, "index.html")).read()
    problems = []
    for needle in ["rasterization.culling.back_ccw_fan", "17 of 4096", "NotSupported", "hier", "bbox"]:
        if needle not in summary:
            problems.append(f"summary.md lacks {needle!r}")
    # Independent expectation: hier passes 2 of 4 cases, bbox 4 of 4.
    if "2/4" not in summary or "4/4" not in summary:
        problems.append("summary.md lacks the pass counts 2/4 and 4/4")
    # The case groups of the main run (hier): one passing compute.atomic case, one failing culling case.
    if "| compute.atomic | 1 | 1 | 0 | 0 |" not in summary or "| rasterization.culling | 1 | 0 | 1 | 0 |" not in summary:
        problems.append("summary.md lacks the case-group rows")
    if "<td>compute.atomic</td>" not in html:
        problems.append("index.html lacks the case-group table")
    for png in ["speed_accuracy.png", "speed_accuracy_scenes.png", "speed_accuracy_groups.png", "time_ratio.png",
                "stability.png"]:
        if not os.path.getsize(os.path.join(out, png)):
            problems.append(f"{png} empty")
        if png not in html:
            problems.append(f"index.html does not show {png}")
    # bench/rast/stability_sweep's long format.
    long_sweep = os.path.join(tmp, "long.csv")
    with open(long_sweep, "w") as f:
        f.write("sweep,param,samples,method,triangles,mismatches,rate\n")
        for m, r in [("hier", 0.0), ("float", 0.25)]:
            for p in [8, 512, 16000]:
                f.write(f"magnitude,{p},1,{m},100,{int(r * 100)},{r}\n")
                f.write(f"offset,{p / 16000},4,{m},100,0,0\n")
    out3 = os.path.join(tmp, "report3")
    subprocess.run([sys.executable, script, "--out", out3, "--stability", long_sweep, paths[0]], check=True)
    if not os.path.getsize(os.path.join(out3, "stability.png")):
        problems.append("long-format sweep not plotted")
    # The frame benchmark's JSON: a graphics scene in the frame table, a compute scene in its own table.
    def side(ms, h):
        return {"median_ms": ms, "round_medians_ms": [ms], "spread": 0.0, "min_ms": ms, "cpu_ms": ms,
                "peak_rss_mb": 10.0, "base_rss_mb": 5.0, "cold_ms": 1.0, "minor_faults_per_frame": 0,
                "allocations_per_frame": 0, "image_hash": h, "device_name": "x"}

    def scene(name, t, l, same=True):
        return {"scene": name, "description": f"{name} described", "tilevk": side(t, "aa"),
                "llvmpipe": side(l, "aa" if same else "bb"), "triangles": 0, "draws": 0, "size": "8x8",
                "ratio": t / l, "cpu_ratio": 1.0, "round_ratios": [t / l], "rss_ratio": 1.0, "cold_ratio": 1.0,
                "images_identical": same, "stages_ms": {}}
    fb = {"command": "fake", "threads": 2, "rounds": 1, "frames": 1, "warmup": 0, "hardware_threads": 2,
          "load_average_start": 0.0, "load_average_end": 0.0, "seconds": 1.0, "scaling": [],
          "scenes": [scene("tri16_flat", 2.0, 4.0), scene("compute_saxpy", 3.0, 4.0, same=False)]}
    fb_path = os.path.join(tmp, "frames.json")
    with open(fb_path, "w") as f:
        json.dump(fb, f)
    out4 = os.path.join(tmp, "report4")
    subprocess.run([sys.executable, script, "--out", out4, "--frames", fb_path, paths[0]], check=True)
    summary4 = open(os.path.join(out4, "summary.md")).read()
    compute_part = summary4.split("### Compute benchmark", 1)[-1].split("## Conformance subset", 1)[0]
    if "### Compute benchmark" not in summary4 or "| compute_saxpy | 8x8 | 3.0 | 4.0 | 0.75" not in compute_part:
        problems.append("summary.md lacks the compute table with compute_saxpy's ratio 0.75")
    if "DIFFER" not in compute_part:
        problems.append("the compute table does not flag differing results")
    if "tri16_flat" in compute_part:
        problems.append("a graphics scene is in the compute table")
    # Without a sweep file the report says so.
    out2 = os.path.join(tmp, "report2")
    subprocess.run([sys.executable, script, "--out", out2, paths[0]], check=True)
    if "not available" not in open(os.path.join(out2, "summary.md")).read():
        problems.append("missing stability sweep not reported as 'not available'")
    # No input at all: an error, not a report.
    if subprocess.run([sys.executable, script, "--out", out2, os.path.join(tmp, "nope.json")]).returncode == 0:
        problems.append("a missing results file did not fail")
    if problems:
        print("\n".join(problems))
        sys.exit(1)
    print("report ok")
