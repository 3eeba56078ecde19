"""run_one.sh against a fake runner that "crashes" (exit 139) inside case b: the merged results must hold a, a Fail
for b naming the crash, then c (resumed with --start-after b). A runner that dies before any case yields every
listed case failing with its last error line."""
import json
import os
import stat
import subprocess
import sys
import tempfile

run_one = sys.argv[1]
FAKE = r'''#!/usr/bin/python3
import json, sys
args = sys.argv[1:]
if "--list" in args:
    print("a\nb\nc"); sys.exit(0)
if MODE == "dead":
    print("tilevk-cts: vkCreateInstance returned VkResult -9", file=sys.stderr); sys.exit(3)
out = args[args.index("--json") + 1]
def case(n):
    return {"name": n, "status": "Pass", "reason": "", "note": "", "differing": 0, "total": 1, "max_error": 0,
            "check": "none", "ours_ms": 1, "ref_ms": 1, "ours_pipeline_ms": 1, "ref_pipeline_ms": 1, "seconds": 0}
run = {"device": "t", "ref": "l", "device_name": "t", "ref_name": "l", "device_found": True, "rast_method": "",
       "threads": "", "icd_filenames": "", "timing_reps": 0}
if "--start-after" in args:
    json.dump(dict(run, complete=True, running="", cases=[case("c")]), open(out, "w")); sys.exit(0)
json.dump(dict(run, complete=False, running="b", cases=[case("a")]), open(out, "w")); sys.exit(139)
'''
problems = []
with tempfile.TemporaryDirectory() as tmp:
    for mode in ["crash", "dead"]:
        fake = os.path.join(tmp, f"fake-{mode}")
        with open(fake, "w") as f:
            f.write(FAKE.replace("MODE", repr(mode)))
        os.chmod(fake, stat.S_IRWXU)
        out = os.path.join(tmp, f"{mode}.json")
        rc = subprocess.run(["bash", run_one, fake, out, "--filter", "*"]).returncode
        if rc != 0:
            problems.append(f"{mode}: run_one exit {rc}")
            continue
        cases = json.load(open(out))["cases"]
        got = [(c["name"], c["status"]) for c in cases]
        want = [("a", "Pass"), ("b", "Fail"), ("c", "Pass")] if mode == "crash" else \
            [("a", "Fail"), ("b", "Fail"), ("c", "Fail")]
        if got != want:
            problems.append(f"{mode}: got {got}, want {want}")
        elif mode == "crash" and "died" not in cases[1]["reason"]:
            problems.append(f"crash: reason {cases[1]['reason']!r}")
        elif mode == "dead" and "VkResult -9" not in cases[0]["reason"]:
            problems.append(f"dead: reason {cases[0]['reason']!r}")
print("\n".join(problems) or "run_one ok")
sys.exit(1 if problems else 0)
