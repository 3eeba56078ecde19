"""The known-differences list is what decides: tilevk-cts reads cts_subset/expectations.txt. With the shipped list
query.linear_path.across_pass passes (its lavapipe-defect plane is not compared); with an empty list it fails;
a listed Fail that passes is a failure (an unexpected pass keeps the list true), a listed Fail that fails is an
ExpectedFail; a malformed list stops the run with status 2."""
import json
import os
import subprocess
import sys
import tempfile

runner = sys.argv[1]
problems = []


def run(tmp, name, lines, case):
    path = os.path.join(tmp, name + ".txt")
    with open(path, "w") as f:
        f.write(lines)
    js = os.path.join(tmp, name + ".json")
    args = [runner, "--filter", case, "--json", js] + (["--expectations", path] if lines is not None else [])
    rc = subprocess.run(args, stdout=subprocess.DEVNULL).returncode
    cases = json.load(open(js))["cases"] if os.path.exists(js) else []
    return rc, cases


with tempfile.TemporaryDirectory() as tmp:
    defect = "query.linear_path.across_pass"
    js = os.path.join(tmp, "shipped.json")
    rc = subprocess.run([runner, "--filter", defect, "--json", js], stdout=subprocess.DEVNULL).returncode
    cases = json.load(open(js))["cases"]
    if rc != 0 or [c["status"] for c in cases] != ["Pass"] or "reference defect in 'queries'" not in cases[0]["note"]:
        problems.append(f"shipped list: exit {rc}, {cases}")
    rc, cases = run(tmp, "empty", "# nothing\n", defect)
    if rc != 1 or [c["status"] for c in cases] != ["Fail"]:
        problems.append(f"empty list: exit {rc}, expected 1 with {defect} failing")
    rc, cases = run(tmp, "unexpected", "api.smoke.triangle,Fail # listed although it passes\n", "api.smoke.triangle")
    if rc != 1 or [c["status"] for c in cases] != ["Fail"] or "unexpected pass" not in cases[0]["reason"]:
        problems.append(f"unexpected pass: exit {rc}, {cases}")
    rc, cases = run(tmp, "expected", defect + ",Fail # the whole case, without its defect plane\n", defect)
    if rc != 0 or [c["status"] for c in cases] != ["ExpectedFail"]:
        problems.append(f"expected fail: exit {rc}, {cases}")
    for name, text in (("noreason", defect + ",Fail\n"), ("noplane", defect + ",ReferenceDefect # x\n"),
                       ("kind", defect + ",Crash # x\n")):
        rc, _ = run(tmp, name, text, defect)
        if rc != 2:
            problems.append(f"malformed list '{text.strip()}': exit {rc}, expected 2")
print("\n".join(problems) or "expectations.txt decides the known differences")
sys.exit(1 if problems else 0)
