#!/usr/bin/python3
"""Merges partial tilevk-cts JSON files (a run resumed after a crash) into one; the case that was running when a
part stopped is recorded as a Fail. usage: merge_runs.py [--fallback CASE_LIST ERROR] OUT PART...
With --fallback, a run that produced no results at all becomes every listed case failing with ERROR."""
import json
import sys


def all_failed(case_list, error):
    """A run in which the runner produced nothing (e.g. the instance could not be created): every case fails."""
    names = [line.split()[0] for line in open(case_list) if line.strip()]
    return {"device": "tilevk", "ref": "llvmpipe", "device_name": "(runner failed)", "ref_name": "(unknown)",
            "device_found": False, "rast_method": "", "threads": "", "icd_filenames": "", "timing_reps": 0,
            "complete": True, "running": "",
            "cases": [{"name": n, "status": "Fail", "reason": error, "note": "", "differing": 0, "total": 0,
                       "max_error": 0, "check": "none", "ours_ms": -1, "ref_ms": -1, "ours_pipeline_ms": -1,
                       "ref_pipeline_ms": -1, "seconds": 0} for n in names]}


def main():
    args = sys.argv[1:]
    fallback = None
    if args[:1] == ["--fallback"]:
        fallback, args = (args[1], args[2]), args[3:]
    out, parts = args[0], args[1:]
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
                                    "reason": "the runner process died in this case (driver crash, or hung past --case-timeout)"})
    if merged is None and fallback:
        merged = all_failed(*fallback)
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
