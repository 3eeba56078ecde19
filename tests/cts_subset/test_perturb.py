"""End-to-end proof that the runner's comparison catches a difference: with --selftest-perturb one bit of the
device-under-test's read-back is flipped, so every case that draws must fail with exactly 1 differing pixel,
exit non-zero, and write ours/ref/diff PNGs."""
import json
import os
import subprocess
import sys
import tempfile

runner = sys.argv[1]
with tempfile.TemporaryDirectory() as tmp:
    js, pngs = os.path.join(tmp, "r.json"), os.path.join(tmp, "png")
    rc = subprocess.run([runner, "--device", "llvmpipe", "--ref", "llvmpipe", "--filter", "api.smoke.*",
                         "--selftest-perturb", "--json", js, "--png-dir", pngs]).returncode
    cases = json.load(open(js))["cases"]
    problems = [] if rc == 1 else [f"exit status {rc}, expected 1"]
    if len(cases) < 5:
        problems.append(f"only {len(cases)} cases ran")
    for c in cases:
        if c["status"] != "Fail" or c["differing"] != 1:
            problems.append(f"{c['name']}: {c['status']} with {c['differing']} differing pixels, expected Fail/1")
        elif not os.path.exists(os.path.join(pngs, c["name"] + ".color.diff.png")) and \
                not os.path.exists(os.path.join(pngs, c["name"] + ".depth.diff.png")):
            problems.append(f"{c['name']}: no diff PNG")
    print("\n".join(problems) or "perturbation detected in every case")
    sys.exit(1 if problems else 0)
