"""End-to-end proof that tilevk-cts --fuzz catches, minimises and reproduces a failure: with --selftest-perturb one
bit of the device-under-test's read-back is flipped, so the seed's random scene, its extreme-vertex scene and its
random compute shader must all fail; the minimiser must then keep exactly one draw / one triangle (any part still
fails; the compute case has no parts), the failure lines
must also be in the --fuzz-log file, and each printed reproduction (environment + --filter) must run that one
case again and fail it."""
import json
import os
import re
import subprocess
import sys
import tempfile

runner = sys.argv[1]
seed = 1000000
problems = []
with tempfile.TemporaryDirectory() as tmp:
    log = os.path.join(tmp, "fuzz.log")
    run = subprocess.run([runner, "--fuzz", "5", "--fuzz-seed", str(seed), "--fuzz-seeds", "1", "--selftest-perturb",
                          "--fuzz-log", log], capture_output=True, text=True)
    print(run.stdout)
    if run.returncode != 1:
        problems.append(f"exit status {run.returncode}, expected 1 (a case failed)")
    fails = [line[len("fuzz: FAIL "):] for line in run.stdout.splitlines() if line.startswith("fuzz: FAIL ")]
    logged = open(log).read().splitlines() if os.path.exists(log) else []
    if logged != fails:
        problems.append(f"the log file holds {logged}, expected the printed failures {fails}")
    for name, knob in ((f"random.seed_{seed}", "TILEVK_CTS_RANDOM_DRAWS"),
                       (f"extreme.random.seed_{seed}", "TILEVK_CTS_EXTREME_KEEP"),
                       (f"random.compute.seed_{seed}", None)):
        line = next((f for f in fails if f.startswith(name + ":")), None)
        if line is None:
            problems.append(f"{name}: no failure reported")
            continue
        reproduction = line.split(" | ", 1)[1].split()
        env = dict(kv.split("=", 1) for kv in reproduction if "=" in kv and not kv.startswith("-"))
        mask = int(env.get(knob, "0"), 16) if knob else 1
        if bin(mask).count("1") != 1:
            problems.append(f"{name}: {knob}={env.get(knob)} keeps {bin(mask).count('1')} parts, expected 1")
        args = reproduction[reproduction.index("tilevk-cts") + 1:]
        js = os.path.join(tmp, name + ".json")
        again = subprocess.run([runner, *args, "--selftest-perturb", "--json", js], env={**os.environ, **env},
                               capture_output=True, text=True)
        cases = json.load(open(js))["cases"] if os.path.exists(js) else []
        if [(c["name"], c["status"]) for c in cases] != [(name, "Fail")] or again.returncode != 1:
            problems.append(f"{name}: the reproduction {' '.join(reproduction)} gave exit {again.returncode} and "
                            f"{[(c['name'], c['status']) for c in cases]}, expected one Fail of {name}")
print("\n".join(problems) or "failures found, minimised to one part each, logged and reproduced")
sys.exit(1 if problems else 0)
