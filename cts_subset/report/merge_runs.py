#!/usr/bin/python3
"""Merges partial tilevk-cts JSON files (a run resumed after a crash) into one; the case that was running when a
part stopped is recorded as a Fail."""
import json
import sys


def main():
    out, parts = sys.argv[1], sys.argv[2:]
    merged = None
    for p in parts:
        try:
            with open(p) as f:
                run = json.load(f)
        except (OSError, ValueError):
            continue
        if merged is None:
            merged = dict(run, cases=[])
        merged["cases"] += run["cases"]
        if not run.get("complete", True) and run.get("running"):
            merged["cases"].append({"name": run["running"], "status": "Fail", "note": "", "differing": 0,
                                    "total": 0, "max_error": 0, "check": "none", "ours_ms": -1, "ref_ms": -1,
                                    "ours_pipeline_ms": -1, "ref_pipeline_ms": -1, "seconds": 0,
                                    "reason": "the runner process died in this case (driver crash)"})
    if merged is None:
        print("merge_runs: no readable results", file=sys.stderr)
        return 1
    merged["complete"] = True
    merged["running"] = ""
    with open(out, "w") as f:
        json.dump(merged, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
