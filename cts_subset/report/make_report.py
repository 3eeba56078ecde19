#!/usr/bin/python3
"""Builds report/index.html and report/summary.md from tilevk-cts --json result files
(and, with --frames, the frame benchmark's JSON, which then opens the report: frame_section.py).

Each results file is one run of the conformance subset (tilevk against lavapipe), possibly with a different
rasterization method (TILEVK_RAST); the first file is the main run whose per-case table is shown. Charts: speed
against accuracy (one point per run, lavapipe at 1.0 / 100 %), time ratio per case, and the stability sweep CSV
from bench/rast's stability_sweep when given. Standard library plus matplotlib (Debian's /usr/bin/python3).
"""
import argparse
import csv
import html
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import frame_section  # noqa: E402


def load(path):
    with open(path) as f:
        run = json.load(f)
    run["path"] = path
    run["label"] = run.get("rast_method") or "default"
    return run


def exact_pct(c):
    return 100.0 * (c["total"] - c["differing"]) / c["total"] if c["total"] else None


def ratio(c):
    if c.get("ours_ms", -1) > 0 and c.get("ref_ms", -1) > 0:
        return c["ours_ms"] / c["ref_ms"]
    return None


def geomean(xs):
    xs = [x for x in xs if x and x > 0]
    return math.exp(sum(math.log(x) for x in xs) / len(xs)) if xs else None


def counts(run):
    n = {"Pass": 0, "Fail": 0, "NotSupported": 0}
    for c in run["cases"]:
        n[c["status"]] = n.get(c["status"], 0) + 1
    return n


def independent_check(c):
    """The case's judgement besides byte equality: analytic check and/or coverage oracle (n/a reasons omitted)."""
    parts = []
    if c.get("check", "none") != "none":
        parts.append("analytic: " + c["check"])
    if c.get("oracle") and not c["oracle"].startswith("n/a"):
        parts.append("oracle: " + c["oracle"])
    return "; ".join(parts).replace("|", "/") or "–"


def fmt(v, spec=".3g", none="–"):
    return none if v is None else format(v, spec)


def speed_accuracy_chart(runs, path):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.scatter([1.0], [100.0], marker="*", s=160, color="black", label="lavapipe (reference)")
    missing = []
    placed = []  # points already labelled: a label near an earlier one goes one line lower, so none overlap
    for run in runs:
        g = geomean([ratio(c) for c in run["cases"]])
        n = len(run["cases"])
        acc = 100.0 * counts(run)["Pass"] / n if n else 0.0
        if g is None:
            missing.append(run["label"])
            continue
        ax.scatter([g], [acc], s=60, label=f"tilevk {run['label']}")
        near = sum(1 for pg, pa in placed if abs(math.log10(g / pg)) < 0.08 and abs(acc - pa) < 4)
        placed.append((g, acc))
        ax.annotate(run["label"], (g, acc), textcoords="offset points", xytext=(6, 4 - 11 * near))
    if missing:
        ax.text(0.02, 0.02, "no timings (nothing drawn): " + ", ".join(missing), transform=ax.transAxes, fontsize=8)
    xs = [1.0] + [g for g in (geomean([ratio(c) for c in r["cases"]]) for r in runs) if g]
    ax.set_xscale("log")
    ax.set_xlim(min(xs) / 2, max(xs) * 2)
    ax.set_xlabel("time / lavapipe time (geometric mean over cases, lower is faster)")
    ax.set_ylabel("cases byte-exact with lavapipe (%)")
    ax.set_ylim(-5, 105)
    ax.set_title("Speed against accuracy")
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


METHOD_COLOURS = {"default": "tab:blue", "reference": "tab:orange", "bbox": "tab:green", "hier": "tab:red",
                  "float": "tab:purple"}


def group_of(name):
    """Case group: the name without its last component (rasterization.culling.front_cw -> rasterization.culling)."""
    return name.rsplit(".", 1)[0]


def speed_accuracy_panels(runs, panels, path, title):
    """Small multiples: one panel per scene (or group), each method one point, lavapipe the star at (1, 100 %).

    panels: list of (panel title, predicate on case name). x: tilevk time / lavapipe time measured in the same run
    (geometric mean over the panel's cases), y: share of pixels that differ from lavapipe's (over the panel's cases).
    """
    cols = 5
    rows = max(1, math.ceil(len(panels) / cols))
    fig, axs = plt.subplots(rows, cols, figsize=(3.2 * cols, 2.6 * rows), squeeze=False)
    for ax in axs.flat[len(panels):]:
        ax.axis("off")
    for ax, (label, keep) in zip(axs.flat, panels):
        ax.scatter([1.0], [0.0], marker="*", s=120, color="black", zorder=3)
        xs, ys = [1.0], [0.0]
        for run in runs:
            cases = [c for c in run["cases"] if keep(c["name"])]
            px = sum(c["total"] for c in cases)
            g = geomean([ratio(c) for c in cases])
            if g is None or not px:
                continue
            wrong = 100.0 * sum(c["differing"] for c in cases) / px
            ax.scatter([g], [wrong], s=36, color=METHOD_COLOURS.get(run["label"]), zorder=2)
            xs.append(g)
            ys.append(wrong)
        ax.set_xscale("log")
        ax.set_xlim(min(xs) / 1.6, max(xs) * 1.6)
        ax.xaxis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
        ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.axvline(1.0, color="grey", linewidth=0.5)
        # Differing pixels, 0 (exact, like lavapipe) at the top; the range adapts to the worst method shown.
        top = max(max(ys), 0.01)
        ax.set_ylim(top * 1.15, -top * 0.1)
        ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.set_title(label, fontsize=8)
        ax.tick_params(labelsize=7)
    handles = [plt.Line2D([], [], marker="*", linestyle="", color="black", markersize=10, label="lavapipe")]
    handles += [plt.Line2D([], [], marker="o", linestyle="", color=METHOD_COLOURS.get(r["label"]),
                           label=f"tilevk {r['label']}") for r in runs]
    fig.legend(handles=handles, loc="lower right", fontsize=8, ncol=len(handles))
    fig.suptitle(title + "  (x: time / lavapipe time in the same run, log; y: pixels differing from lavapipe, %, exact at the top)", fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 0.97))
    fig.savefig(path, dpi=90)
    plt.close(fig)


def time_ratio_chart(run, path):
    pairs = sorted(((ratio(c), c["name"]) for c in run["cases"] if ratio(c)), reverse=True)
    fig, ax = plt.subplots(figsize=(10, 4.5))
    if pairs:
        ax.bar(range(len(pairs)), [p[0] for p in pairs], width=1.0, color="tab:blue")
        ax.axhline(1.0, color="black", linewidth=0.8)
        ax.set_yscale("log")
        ax.set_xlabel(f"case (sorted, {len(pairs)} timed)")
    else:
        ax.text(0.5, 0.5, "no case was timed on both devices", ha="center", va="center", transform=ax.transAxes)
    ax.set_ylabel("tilevk time / lavapipe time")
    ax.set_title(f"Frame time ratio per case ({run['label']})")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def stability_chart_long(rows, path):
    """bench/rast/stability_sweep's format: sweep,param,samples,method,triangles,mismatches,rate."""
    sweeps = sorted({r["sweep"] for r in rows})
    fig, axs = plt.subplots(1, len(sweeps), figsize=(4.2 * len(sweeps), 4), squeeze=False)
    for ax, sweep in zip(axs[0], sweeps):
        series = {}
        for r in rows:
            if r["sweep"] == sweep:
                key = f"{r['method']} {r['samples']}x"
                series.setdefault(key, []).append((float(r["param"]), float(r["rate"])))
        for key, pts in sorted(series.items()):
            pts.sort()
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=".", label=key)
        ax.set_title(sweep)
        ax.set_xlabel("param")
        if max(float(r["param"]) for r in rows if r["sweep"] == sweep) > 100:
            ax.set_xscale("log")
        ax.set_ylabel("mismatch rate vs reference")
        ax.legend(fontsize=7)
    fig.suptitle("Stability sweep (bench/rast stability_sweep): where each method departs from the reference")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def stability_chart(csv_path, path):
    with open(csv_path, newline="") as f:
        rows = list(csv.reader(f))
    if {"sweep", "param", "method", "rate"} <= set(rows[0]):
        return stability_chart_long([dict(zip(rows[0], r)) for r in rows[1:] if r], path)
    header, data = rows[0], [r for r in rows[1:] if r]
    cols = list(zip(*data))
    x = [float(v) for v in cols[0]]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for name, col in zip(header[1:], cols[1:]):
        try:
            ax.plot(x, [float(v) for v in col], marker=".", label=name)
        except ValueError:
            continue  # a non-numeric column (labels): not plotted
    ax.set_xlabel(header[0])
    ax.set_ylabel("value")
    ax.set_title("Stability sweep (bench/rast stability_sweep)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", required=True, help="output folder (index.html, summary.md, *.png)")
    ap.add_argument("--stability", help="stability sweep CSV (optional)")
    ap.add_argument("--frames", help="bench/frame/run_frame_bench.py JSON: the frame table opens the report")
    ap.add_argument("--title", default="tilevk conformance subset")
    ap.add_argument("results", nargs="+", help="tilevk-cts --json files; the first is the main run")
    a = ap.parse_args()
    runs = []
    for p in a.results:
        try:
            runs.append(load(p))
        except (OSError, ValueError) as e:
            print(f"make_report: cannot read {p}: {e}", file=sys.stderr)
            return 1
    os.makedirs(a.out, exist_ok=True)
    frames = None
    if a.frames:
        try:
            with open(a.frames) as f:
                frames = json.load(f)
            frame_section.stage_chart(frames, os.path.join(a.out, "frame_stages.png"))
            frame_section.scaling_chart(frames, os.path.join(a.out, "frame_scaling.png"))
        except (OSError, ValueError, KeyError) as e:
            print(f"make_report: frame benchmark results unreadable ({a.frames}): {e}", file=sys.stderr)
            frames = None
    main_run = runs[0]
    speed_accuracy_chart(runs, os.path.join(a.out, "speed_accuracy.png"))
    names = [c["name"] for c in main_run["cases"]]
    scenes = [n for n in names if n.startswith("scene.")]
    speed_accuracy_panels(runs, [(n.split(".", 1)[1], lambda x, n=n: x == n) for n in scenes],
                          os.path.join(a.out, "speed_accuracy_scenes.png"), "Speed against accuracy per scene")
    groups = sorted({group_of(n) for n in names})
    speed_accuracy_panels(runs, [(g, lambda x, g=g: group_of(x) == g) for g in groups],
                          os.path.join(a.out, "speed_accuracy_groups.png"), "Speed against accuracy per case group")
    time_ratio_chart(main_run, os.path.join(a.out, "time_ratio.png"))
    have_sweep = bool(a.stability) and os.path.exists(a.stability)
    if have_sweep:
        try:
            stability_chart(a.stability, os.path.join(a.out, "stability.png"))
        except (OSError, ValueError, IndexError) as e:
            have_sweep = False
            print(f"make_report: stability sweep unreadable: {e}", file=sys.stderr)

    # --- summary.md ---
    md = [f"# {a.title}", ""]
    if frames:
        md += frame_section.markdown(frames) + ["## Conformance subset", ""]
    md.append(f"Device under test: **{main_run['device_name']}**; reference: **{main_run['ref_name']}**; "
              f"{main_run['threads']}; timing repetitions: {main_run['timing_reps']}.")
    md += ["", "Times are medians of the timed repetitions, the two devices alternating; a frame is one submit of "
           "the case's command buffer to its fence (uploads, the pass, read-back copies). Most cases are 64x64, so "
           "their times, and the geomean time ratio below, are dominated by per-submit overhead, not rendering "
           "speed: the frame benchmark above measures that; `scene.perf.*` (1024x1024) measure rasterization."]
    md.append("")
    if not main_run.get("device_found", True):
        md += ["**The tilevk device was not available (or cannot draw yet): every case fails with the driver's "
               "reason below. This is the honest state of the driver, not a harness fault.**", ""]
    for run in runs:
        if not run.get("complete", True):
            md += [f"**Run `{run['label']}` did not finish: the runner stopped (crash?) while running "
                   f"`{run.get('running')}`; later cases are missing.**", ""]
    md += ["## Runs", "", "| run (TILEVK_RAST) | passed | failed | not supported | geomean time ratio | exact pixels |",
           "|---|---|---|---|---|---|"]
    for run in runs:
        n = counts(run)
        tot = len(run["cases"])
        px = sum(c["total"] for c in run["cases"])
        same = sum(c["total"] - c["differing"] for c in run["cases"])
        g = geomean([ratio(c) for c in run["cases"]])
        compared = sum(1 for c in run["cases"] if c["total"])
        timed = sum(1 for c in run["cases"] if ratio(c))
        md.append(f"| {run['label']} | {n['Pass']}/{tot} | {n['Fail']} | {n['NotSupported']} | "
                  f"{fmt(g)} over {timed} timed cases | "
                  f"{fmt(100.0 * same / px if px else None, '.4f')} % of {px} px in {compared} compared cases |")
    md += ["", "Case groups (main run; the first two parts of the name, e.g. `compute.atomic`):", "",
           "| group | cases | passed | failed | not supported |", "|---|---|---|---|---|"]
    group_rows = []
    for g in sorted({".".join(c["name"].split(".")[:2]) for c in main_run["cases"]}):
        cs = [c for c in main_run["cases"] if ".".join(c["name"].split(".")[:2]) == g]
        group_rows.append([g, str(len(cs)), str(sum(c["status"] == "Pass" for c in cs)),
                           str(sum(c["status"] == "Fail" for c in cs)),
                           str(sum(c["status"] == "NotSupported" for c in cs))])
    md += ["| " + " | ".join(r) + " |" for r in group_rows]
    ns = [c for c in main_run["cases"] if c["status"] == "NotSupported"]
    if ns:
        on_ours = sum(1 for c in ns if c["reason"].startswith(main_run["device_name"]))
        md += ["", f"NotSupported: {on_ours} of {len(ns)} because the device under test lacks a feature or format "
               f"(a gap in tilevk, not a pass), {len(ns) - on_ours} because the reference lacks it."]
    pipe = [(c["ours_pipeline_ms"], c["ref_pipeline_ms"]) for c in main_run["cases"]
            if c.get("ours_pipeline_ms", -1) > 0 and c.get("ref_pipeline_ms", -1) > 0]
    md.append("")
    if pipe:
        md.append(f"Pipeline creation (sum over cases): tilevk {sum(p[0] for p in pipe):.1f} ms, "
                  f"lavapipe {sum(p[1] for p in pipe):.1f} ms.")
    else:
        md.append("Pipeline creation time: not measured (no case created pipelines on both devices).")
    md.append("")
    md.append("Stability sweep: " + ("see stability.png." if have_sweep else "not available "
                                      "(bench/rast's stability_sweep did not produce a CSV)."))
    analytic = [c for c in main_run["cases"] if c.get("check", "none") != "none"]
    oracle = [c for c in main_run["cases"] if c.get("oracle", "").startswith(("ok", "FAIL", "fail"))]
    md.append("")
    md.append(f"Independent checks (besides byte equality with the reference): {len(analytic)} cases carry an "
              f"analytic check ({sum(1 for c in analytic if c['check'] == 'ok')} ok); {len(oracle)} cases are "
              f"judged by the coverage oracle, rast/'s `reference` method "
              f"({sum(1 for c in oracle if c['oracle'].startswith('ok'))} agree).")
    md += ["", "## Cases (main run)", "",
           "| case | status | exact % | max err | tilevk ms | lavapipe ms | ratio | pipeline ms (t/l) | independent check | reason |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for c in main_run["cases"]:
        pm = (f"{c['ours_pipeline_ms']:.2f}/{c['ref_pipeline_ms']:.2f}"
              if c.get("ours_pipeline_ms", -1) >= 0 and c.get("ref_pipeline_ms", -1) >= 0 else "–")
        ours_ms = c["ours_ms"] if c.get("ours_ms", -1) >= 0 else None
        ref_ms = c["ref_ms"] if c.get("ref_ms", -1) >= 0 else None
        note = f" [{c['note']}]" if c.get("note") else ""
        md.append(f"| {c['name']}{note} | {c['status']} | {fmt(exact_pct(c), '.3f')} | {fmt(c['max_error'] if c['total'] else None, 'g')} | "
                  f"{fmt(ours_ms)} | {fmt(ref_ms)} | {fmt(ratio(c))} | {pm} | {independent_check(c)} | "
                  f"{c['reason'].replace('|', '/')} |")
    with open(os.path.join(a.out, "summary.md"), "w") as f:
        f.write("\n".join(md) + "\n")

    # --- index.html ---
    esc = html.escape
    h = [f"<!doctype html><html><head><meta charset='utf-8'><title>{esc(a.title)}</title>",
         "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;font-size:13px}"
         "td,th{border:1px solid #ccc;padding:2px 6px}.Pass{background:#dfd}.Fail{background:#fdd}"
         ".NotSupported{background:#eee}</style></head><body>", f"<h1>{esc(a.title)}</h1>"]
    if frames:
        h += frame_section.html_section(frames) + ["<h2>Conformance subset</h2>"]
    start = md.index("## Conformance subset") + 2 if frames else 2
    intro = [line for line in md[start:] if not line.startswith("## Cases")]
    cut = intro.index("## Runs") if "## Runs" in intro else len(intro)
    h += [f"<p>{esc(line).replace('**', '')}</p>" for line in intro[:cut] if line]
    h.append("<h2>Runs</h2><table><tr><th>run</th><th>passed</th><th>failed</th><th>not supported</th>"
             "<th>geomean time ratio</th></tr>")
    for run in runs:
        n = counts(run)
        h.append(f"<tr><td>{esc(run['label'])}</td><td>{n['Pass']}/{len(run['cases'])}</td><td>{n['Fail']}</td>"
                 f"<td>{n['NotSupported']}</td><td>{fmt(geomean([ratio(c) for c in run['cases']]))}</td></tr>")
    h.append("</table>")
    h += [f"<p>{esc(line)}</p>" for line in intro[cut:] if line and not line.startswith("|") and line != "## Runs"]
    h.append("<h3>Case groups</h3><table><tr><th>group</th><th>cases</th><th>passed</th><th>failed</th>"
             "<th>not supported</th></tr>")
    h += ["<tr>" + "".join(f"<td>{esc(x)}</td>" for x in r) + "</tr>" for r in group_rows]
    h.append("</table>")
    h.append("<h2>Charts</h2><img src='speed_accuracy.png'> <img src='time_ratio.png'>")
    h.append("<h3>Per scene</h3><img src='speed_accuracy_scenes.png'>")
    h.append("<h3>Per case group</h3><img src='speed_accuracy_groups.png'>")
    h.append("<img src='stability.png'>" if have_sweep else "<p>Stability sweep: not available.</p>")
    h.append("<h2>Cases (main run)</h2><table><tr><th>case</th><th>status</th><th>exact %</th><th>max err</th>"
             "<th>tilevk ms</th><th>lavapipe ms</th><th>ratio</th><th>pipeline ms (t/l)</th><th>independent check</th>"
             "<th>reason</th></tr>")
    for line in md[md.index("## Cases (main run)") + 4:]:
        cells = [x.strip() for x in line.strip("|").split("|")]
        h.append(f"<tr class='{esc(cells[1])}'>" + "".join(f"<td>{esc(x)}</td>" for x in cells) + "</tr>")
    h.append("</table></body></html>")
    with open(os.path.join(a.out, "index.html"), "w") as f:
        f.write("\n".join(h) + "\n")
    print(f"make_report: wrote {a.out}/index.html and summary.md ({len(main_run['cases'])} cases, {len(runs)} runs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
