"""The report's opening section: the frame benchmark (bench/frame/run_frame_bench.py's JSON).

Table: per scene, the median frame time of tilevk and lavapipe (same thread count, alternating processes), the
ratio with its per-round range, the spread of each driver's round medians, peak RSS of each driver's own
process, cold pipeline + first frame, minor page faults per steady frame, whether the images are identical, and
tilevk's time per stage. Charts: the stages (thread time per frame) and the thread scaling. The compute scenes
(`compute_*`: one dispatch per frame, bench/frame/compute_vk.cpp) get their own table after the frame table.
"""
import html
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STAGE_LABELS = {
    "vertex": "vertex shading",
    "setup_bin": "clip/setup/bin",
    "coverage": "coverage",
    "shade": "fragment shading",
    "depth_blend_store": "depth/blend/store",
    "attach": "clears/staging",
    "resolve": "resolve",
}
STAGE_COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:gray", "tab:brown"]


def geomean(xs):
    xs = [x for x in xs if x and x > 0]
    return math.exp(sum(math.log(x) for x in xs) / len(xs)) if xs else None


def _stages(s):
    st = s.get("stages_ms") or {}
    return [(STAGE_LABELS.get(k, k), v) for k, v in st.items()]


def is_compute(s):
    return s["scene"].startswith("compute_")


def graphics_scenes(fb):
    return [s for s in fb["scenes"] if not is_compute(s)]


def compute_rows(fb):
    """(header, rows) of the compute table: one dispatch per frame, tilevk / lavapipe."""
    header = ["kernel", "size", "tilevk ms", "lavapipe ms", "ratio (rounds)", "spread t / l",
              "cold pipeline + 1st frame ms t / l", "results", "what it is"]
    rows = []
    for s in fb["scenes"]:
        if not is_compute(s):
            continue
        t, l = s["tilevk"], s["llvmpipe"]
        rr = s["round_ratios"]
        rows.append([
            s["scene"], s["size"], f"{t['median_ms']:.1f}", f"{l['median_ms']:.1f}",
            f"{s['ratio']:.2f} ({min(rr):.2f}–{max(rr):.2f})",
            f"{100 * t['spread']:.0f} % / {100 * l['spread']:.0f} %",
            f"{t['cold_ms']:.1f} / {l['cold_ms']:.1f}",
            "identical" if s["images_identical"] else
            f"DIFFER: tilevk {t['image_hash'][:8]}, lavapipe {l['image_hash'][:8]}",
            s["description"],
        ])
    return header, rows


def compute_intro(fb):
    return (f"Compute kernels in the same harness: a frame = record (a vkCmdFillBuffer reset where the kernel "
            f"accumulates), vkCmdDispatch, submit, wait; {fb['threads']} threads each, the same rounds and frames. "
            f"Results: the result buffer's bytes hashed on both drivers.")


def table_rows(fb):
    """(header, rows) of the frame table, as plain strings."""
    header = ["scene", "size", "tilevk ms", "lavapipe ms", "ratio (rounds)", "spread t / l", "peak RSS MB t / l",
              "cold pipeline + 1st frame ms t / l", "faults/frame t / l", "allocations/frame t / l", "images",
              "tilevk stages (thread ms)"]
    rows = []
    for s in graphics_scenes(fb):
        t, l = s["tilevk"], s["llvmpipe"]
        rr = s["round_ratios"]
        stages = ", ".join(f"{k} {v:.1f}" for k, v in _stages(s) if v >= 0.05) or "–"
        rows.append([
            s["scene"], s["size"], f"{t['median_ms']:.1f}", f"{l['median_ms']:.1f}",
            f"{s['ratio']:.2f} ({min(rr):.2f}–{max(rr):.2f})",
            f"{100 * t['spread']:.0f} % / {100 * l['spread']:.0f} %",
            f"{t['peak_rss_mb']:.0f} / {l['peak_rss_mb']:.0f}",
            f"{t['cold_ms']:.1f} / {l['cold_ms']:.1f}",
            f"{t['minor_faults_per_frame']:.0f} / {l['minor_faults_per_frame']:.0f}",
            (f"{t['allocations_per_frame']:.0f} / {l['allocations_per_frame']:.0f}"
             if t.get("allocations_per_frame") is not None and l.get("allocations_per_frame") is not None else "–"),
            "identical" if s["images_identical"] else
            f"DIFFER: tilevk {t['image_hash'][:8]}, lavapipe {l['image_hash'][:8]}",
            stages,
        ])
    return header, rows


def intro_lines(fb):
    ratios = [s["ratio"] for s in graphics_scenes(fb)]
    small = [s["ratio"] for s in graphics_scenes(fb) if s["scene"].startswith(("tri4_", "tri16_"))]
    lines = [
        f"Whole frames through the Vulkan API (record the command buffer, submit, wait), tilevk and lavapipe at "
        f"{fb['threads']} threads each (TILEVK_THREADS = LP_NUM_THREADS), one process per driver and round, "
        f"{fb['rounds']} rounds alternating the drivers, {fb['frames']} timed frames per process after "
        f"{fb['warmup']} warm-up frame(s). Ratio = tilevk median / lavapipe median (lower is faster; the range is "
        f"the per-round ratios). Spread = (largest - smallest round median) / median. Peak RSS = each driver's own "
        f"process (harness included). Images: the final frames' colour bytes hashed on both drivers.",
        f"Geometric mean of the ratios over these {len(ratios)} scenes: {geomean(ratios):.2f}; "
        f"100 000 triangles of 4 and 16 px: {geomean(small) or float('nan'):.2f}. "
        f"Load average {fb['load_average_start']:.1f} at the start, {fb['load_average_end']:.1f} at the end "
        f"({fb['hardware_threads']} hardware threads); {fb['seconds']:.0f} s. Command: `{fb['command']}`.",
        "tilevk stages: thread time per frame summed over threads (TILEVK_STAGE_TIMES, one more tilevk process per "
        "scene; coverage = a tile's time outside the fragment stage).",
    ]
    differ = [s["scene"] for s in fb["scenes"] if not s["images_identical"]]
    if differ:
        lines.insert(0, f"MISMATCH: tilevk's image differs from lavapipe's in {len(differ)} scene(s): "
                        f"{', '.join(differ)} (column images; tilevk-frame-bench --dump and --draws find the draw).")
    return lines


def markdown(fb):
    header, rows = table_rows(fb)
    md = ["## Frame benchmark (bench/frame)", ""] + intro_lines(fb) + [""]
    md.append("| " + " | ".join(header) + " |")
    md.append("|" + "---|" * len(header))
    md += ["| " + " | ".join(r) + " |" for r in rows]
    cheader, crows = compute_rows(fb)
    if crows:
        md += ["", "### Compute benchmark", "", compute_intro(fb), ""]
        md.append("| " + " | ".join(cheader) + " |")
        md.append("|" + "---|" * len(cheader))
        md += ["| " + " | ".join(r) + " |" for r in crows]
    if fb.get("scaling"):
        md += ["", "Thread scaling (median frame ms, tilevk / lavapipe):", ""]
        threads = sorted({r["threads"] for r in fb["scaling"]})
        md.append("| scene | " + " | ".join(f"{t} thread(s)" for t in threads) + " | tilevk 1→2 |")
        md.append("|" + "---|" * (len(threads) + 2))
        for scene in dict.fromkeys(r["scene"] for r in fb["scaling"]):
            by_t = {r["threads"]: r for r in fb["scaling"] if r["scene"] == scene}
            cells = [f"{by_t[t]['tilevk_ms']:.1f} / {by_t[t]['llvmpipe_ms']:.1f}" if t in by_t else "–" for t in threads]
            speedup = (f"{by_t[1]['tilevk_ms'] / by_t[2]['tilevk_ms']:.2f}x" if 1 in by_t and 2 in by_t else "–")
            md.append(f"| {scene} | " + " | ".join(cells) + f" | {speedup} |")
    md.append("")
    return md


def html_section(fb):
    esc = html.escape
    header, rows = table_rows(fb)
    h = ["<h2>Frame benchmark (bench/frame)</h2>"] + [f"<p>{esc(x)}</p>" for x in intro_lines(fb)]
    h.append("<table><tr>" + "".join(f"<th>{esc(x)}</th>" for x in header) + "</tr>")
    for r in rows:
        cls = "" if r[10] == "identical" else " class='Fail'"  # a mismatch row is red
        h.append(f"<tr{cls}>" + "".join(f"<td>{esc(x)}</td>" for x in r) + "</tr>")
    h.append("</table>")
    cheader, crows = compute_rows(fb)
    if crows:
        h += ["<h3>Compute benchmark</h3>", f"<p>{esc(compute_intro(fb))}</p>"]
        h.append("<table><tr>" + "".join(f"<th>{esc(x)}</th>" for x in cheader) + "</tr>")
        for r in crows:
            cls = "" if r[7] == "identical" else " class='Fail'"
            h.append(f"<tr{cls}>" + "".join(f"<td>{esc(x)}</td>" for x in r) + "</tr>")
        h.append("</table>")
    h.append("<p><img src='frame_stages.png'> <img src='frame_scaling.png'></p>")
    return h


def stage_chart(fb, path):
    """One bar per scene: each stage's share of tilevk's thread time, labelled with the frame times."""
    scenes = graphics_scenes(fb)
    fig, ax = plt.subplots(figsize=(11, 0.42 * len(scenes) + 1.8))
    y = list(range(len(scenes)))
    left = [0.0] * len(scenes)
    totals = [sum((s.get("stages_ms") or {}).values()) or 1.0 for s in scenes]
    for k, colour in zip(STAGE_LABELS, STAGE_COLOURS):
        vals = [100.0 * (s.get("stages_ms") or {}).get(k, 0.0) / t for s, t in zip(scenes, totals)]
        if not any(vals):
            continue
        ax.barh(y, vals, left=left, color=colour, label=STAGE_LABELS[k], height=0.6)
        left = [a + b for a, b in zip(left, vals)]
    for i, (s, t) in enumerate(zip(scenes, totals)):
        ax.text(101, i, f"{t:.0f} thread-ms; frame {s['tilevk']['median_ms']:.0f} ms, lavapipe "
                f"{s['llvmpipe']['median_ms']:.0f} ms ({s['ratio']:.2f}x)", va="center", fontsize=7)
    ax.set_yticks(y)
    ax.set_yticklabels([s["scene"] for s in scenes], fontsize=8)
    ax.invert_yaxis()
    ax.set_xlim(0, 150)
    ax.set_xticks([0, 25, 50, 75, 100])
    ax.set_xlabel("share of tilevk's thread time per frame (%), stage timers (TILEVK_STAGE_TIMES)")
    ax.set_title(f"tilevk time per stage, {fb['threads']} threads")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=len(STAGE_LABELS))
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def scaling_chart(fb, path):
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    scenes = list(dict.fromkeys(r["scene"] for r in fb.get("scaling", [])))
    for i, scene in enumerate(scenes):
        rows = sorted((r for r in fb["scaling"] if r["scene"] == scene), key=lambda r: r["threads"])
        colour = f"C{i}"
        ax.plot([r["threads"] for r in rows], [r["tilevk_ms"] for r in rows], marker="o", color=colour,
                label=f"{scene} tilevk")
        ax.plot([r["threads"] for r in rows], [r["llvmpipe_ms"] for r in rows], marker="*", linestyle="--",
                color=colour, label=f"{scene} lavapipe")
    if not scenes:
        ax.text(0.5, 0.5, "no scaling runs", ha="center", va="center", transform=ax.transAxes)
    threads = sorted({r["threads"] for r in fb.get("scaling", [])}) or [1, 2]
    ax.set_xticks(threads)
    ax.set_yscale("log")
    ax.set_xlabel("threads (TILEVK_THREADS = LP_NUM_THREADS)")
    ax.set_ylabel("median frame ms (log)")
    ax.set_title("Thread scaling")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)

