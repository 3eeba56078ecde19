"""The conformance subset under VK_LAYER_KHRONOS_validation (zero messages on both drivers).

  test_validation.py RUNNER full      every case, tilevk vs lavapipe, with --validation: no case may carry a
                                      message, none may arrive outside a case, every case must have run.
  test_validation.py RUNNER full-spirv15  the same with every shader compiled to SPIR-V 1.5 (Vulkan 1.2);
                                      full-spirv16: SPIR-V 1.6 (Vulkan 1.3).
                                      Image differences are not judged here (the cts_tilevk_vs_lavapipe_* slices
                                      do that), so a case failing on pixels alone does not fail this test.
  test_validation.py RUNNER selftest  proves the check can fail: --selftest-validation records one invalid
                                      barrier; with --validation every case must fail with that VUID on BOTH
                                      devices and the exit status must be 1; without --validation (control) the
                                      same command stream must produce no validation verdict at all.
"""
import json
import os
import subprocess
import sys
import tempfile

VUID = "VUID-vkCmdPipelineBarrier-srcAccessMask-02815"


def run(runner, args, tmp, name):
    js = os.path.join(tmp, name + ".json")
    p = subprocess.run([runner, "--json", js] + args, capture_output=True, text=True)
    sys.stdout.write(p.stdout[-3000:])
    sys.stderr.write(p.stderr[-3000:])
    if p.returncode not in (0, 1):
        return p.returncode, None
    return p.returncode, json.load(open(js))


def devices_of(messages):
    return {m[1:m.index("]")] for m in messages if m.startswith("[")}


def full(runner, tmp, extra=()):
    listed = [l.split()[0] for l in subprocess.run([runner, "--list"], capture_output=True, text=True,
                                                     check=True).stdout.splitlines() if l.strip()]
    rc, d = run(runner, ["--validation"] + list(extra), tmp, "full")
    if d is None:
        return [f"runner exit status {rc} (crash or setup error)"]
    problems = []
    if not d.get("validation"):
        problems.append("the JSON says validation was off")
    if not d.get("complete"):
        problems.append(f"run incomplete, running {d.get('running')}")
    if not d["device_name"].startswith("tilevk") or not d["ref_name"].startswith("llvmpipe"):
        problems.append(f"devices {d['device_name']!r} vs {d['ref_name']!r}, expected tilevk vs llvmpipe")
    ran = [c["name"] for c in d["cases"]]
    if ran != listed or len(ran) < 200:
        problems.append(f"{len(ran)} cases ran, {len(listed)} listed")
    per_device = {}
    for c in d["cases"]:
        for m in c["validation"]:
            dev = m[1:m.index("]")] if m.startswith("[") else "?"
            per_device[dev] = per_device.get(dev, 0) + 1
        if c["validation"]:
            problems.append(f"{c['name']}: {len(c['validation'])} messages, first: {c['validation'][0][:300]}")
        if c["reason"].startswith("validation:") and not c["validation"]:
            problems.append(f"{c['name']}: validation verdict without messages")
    for m in d["validation_outside"]:
        problems.append(f"outside any case: {m[:300]}")
    unvalidated = [c["name"] for c in d["cases"] if c["status"] == "NotSupported"]
    print(f"validation messages per device: {per_device or 'none'}; outside cases: {len(d['validation_outside'])}; "
          f"{len(ran) - len(unvalidated)} cases validated, {len(unvalidated)} NotSupported (not recorded): "
          f"{unvalidated[:10]}")
    return problems


def selftest(runner, tmp):
    problems = []
    rc, d = run(runner, ["--validation", "--selftest-validation", "--filter", "api.smoke.*"], tmp, "bad")
    if d is None:
        return [f"runner exit status {rc} with --selftest-validation"]
    if rc != 1:
        problems.append(f"exit status {rc}, expected 1")
    if len(d["cases"]) < 5:
        problems.append(f"only {len(d['cases'])} cases ran")
    for c in d["cases"]:
        want = {d["device_name"].split()[0], d["ref_name"].split()[0]}
        got = devices_of(m for m in c["validation"] if VUID in m)
        if c["status"] != "Fail" or not c["reason"].startswith("validation:") or VUID not in c["reason"]:
            problems.append(f"{c['name']}: {c['status']} ({c['reason'][:200]}), expected a validation Fail")
        if got != want:
            problems.append(f"{c['name']}: {VUID} reported on {sorted(got)}, expected on {sorted(want)}")
    # Control: the same invalid barrier without the layer is not a validation verdict (the verdict comes from
    # the layer, not from the flag).
    rc, d = run(runner, ["--selftest-validation", "--filter", "api.smoke.*"], tmp, "control")
    if d is None:
        return problems + [f"control run exit status {rc}"]
    if d.get("validation"):
        problems.append("control run says validation was on")
    for c in d["cases"]:
        if c["validation"] or c["reason"].startswith("validation:"):
            problems.append(f"control {c['name']}: validation verdict without the layer")
    return problems


runner, mode = sys.argv[1], sys.argv[2]
with tempfile.TemporaryDirectory() as tmp:
    if mode == "full":
        problems = full(runner, tmp)
    elif mode == "full-spirv15":  # the same with SPIR-V 1.5 modules on a Vulkan 1.2 instance (tilevk-cts --spirv)
        problems = full(runner, tmp, ["--spirv", "1.5"])
    elif mode == "full-spirv16":  # SPIR-V 1.6 modules on a Vulkan 1.3 instance
        problems = full(runner, tmp, ["--spirv", "1.6"])
    else:
        problems = selftest(runner, tmp)
print("\n".join(problems) or f"{mode}: ok")
sys.exit(1 if problems else 0)
