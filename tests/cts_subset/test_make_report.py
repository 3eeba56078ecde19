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
        run("hier", [case("api.smoke.triangle", "Pass", 1.0, 2.0),
                     case("rasterization.culling.back_ccw_fan", "Fail", 4.0, 2.0, 17, "color: 17 of 4096 differ"),
                     case("depth.compare.d16_less", "NotSupported", -1, -1, reason="tilevk: format")]),
        run("bbox", [case("api.smoke.triangle", "Pass", 3.0, 2.0),
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
    # Independent expectation: hier passes 1 of 3 cases, bbox 3 of 3.
    if "1/3" not in summary or "3/3" not in summary:
        problems.append("summary.md lacks the pass counts 1/3 and 3/3")
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
