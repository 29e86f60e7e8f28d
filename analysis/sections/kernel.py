"""Kernel runs (float against exact on the same snapped scene): per scene, what the float kernel's tolerance
changes — fragments it drops, pairs its order check leaves as ties, classifications that differ from the exact
decision — and what exactness costs in build time, per heuristic and size (kernel-SCENE.png).
"""
import html
import os

import matplotlib.pyplot as plt

from sections.common import DPI, Section, aggregates_of, plain, slug, summary_cell, value
from tables import Column, Table

KERNEL_COLUMNS = (("metrics", "float_fragments", "fragments, float kernel"),
                  ("metrics", "exact_fragments", "fragments, exact kernel"),
                  ("metrics", "float_dropped", "fragments the float kernel dropped as slivers (exact: never)"),
                  ("metrics", "float_ties", "hit pairs the float order check left to the tolerance"),
                  ("metrics", "exact_ties", "hit pairs meeting the ray in one point (exact)"),
                  ("metrics", "float_pairs_checked", "fragment pairs judged, float"),
                  ("metrics", "exact_pairs_checked", "fragment pairs judged, exact"),
                  ("metrics", "float_violations", "pairs the float tree draws in the wrong order"),
                  ("metrics", "classify_differences", "input polygon x node plane classifications that differ"),
                  ("metrics", "classify_tests", "classifications compared"),
                  ("metrics", "predicates_filter_rate", "side tests the floating-point filter decided"),
                  ("timings", "float_build_cpu_seconds", "float build, thread CPU seconds"),
                  ("timings", "exact_build_cpu_seconds", "exact build, thread CPU seconds"))


def ratio(entry, num, den):
    a, b = value(entry, "metrics", num), value(entry, "metrics", den)
    return a / b if a is not None and b else None


def plot_kernel(scene, aggs, path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for agg in aggs:
        entries = agg["by_n"]
        xs = [e["n_polygons"]["mean"] for e in entries]
        ties = [(x, ratio(e, "float_ties", "float_pairs_checked")) for x, e in zip(xs, entries)]
        cost = [(x, (value(e, "timings", "exact_build_cpu_seconds") or 0) / (value(e, "timings", "float_build_cpu_seconds") or 1))
                for x, e in zip(xs, entries)]
        for ax, pts in zip(axes, (ties, cost)):
            pts = [(x, y) for x, y in pts if y is not None]
            if pts:
                ax.plot(*zip(*pts), marker="o", label=agg["heuristic"])
    for ax, title in zip(axes, ("float ties per judged pair (exact: none but true ties)", "exact build / float build")):
        ax.set_xscale("log")
        ax.set_xlabel("polygons (n)")
        ax.set_title(f"{scene}: {title}", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 9), fontsize=8)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def scene_table(scene, aggs):
    rows = [[g["heuristic"], plain(e["n"]), e["runs"], e["validation_violations"]]
            + [summary_cell(e[s].get(k)) for s, k, _ in KERNEL_COLUMNS] for g in aggs for e in g["by_n"]]
    return Table(f"kernel-{slug(scene)}", f"{scene}: float against exact kernel per heuristic and size",
                 [("heuristic", ""), ("n", ""), ("runs", ""), ("exact order violations", "")]
                 + [Column(k, title=doc) for _, k, doc in KERNEL_COLUMNS], rows)


def render(report, ctx):
    scenes = {}
    for agg in aggregates_of(report, "kernel"):
        scenes.setdefault(agg["scene"], []).append(agg)
    if not scenes:
        return None
    parts = ["<h2 id='kernel'>What the tolerance costs: float against exact geometry</h2>"
             "<p>Each scene is snapped to its integer grid and built twice with the same heuristic and seed: by the "
             "float kernel, which decides sides within plane_eps of a plane and drops slivers narrower than it, and by "
             "the exact kernel, which decides every side as the sign of a determinant [Sugihara1989] "
             "[BernsteinFussell2009] and drops nothing. Both trees' back-to-front orders are checked by Embree ray "
             "casts; the float check leaves pairs closer than its tolerance as ties, the exact check decides every "
             "pair. A column of differences is what the tolerance decided differently from the geometry.</p>" + ctx.how]
    tables = []
    for scene, aggs in sorted(scenes.items()):
        aggs = sorted(aggs, key=lambda a: a["heuristic"])
        png = f"kernel-{slug(scene)}.png"
        plot_kernel(scene, aggs, os.path.join(ctx.out_dir, png))
        t = scene_table(scene, aggs)
        tables.append(t)
        parts.append(f"<h3 id='kernel-{slug(scene)}'>{html.escape(scene)}</h3>"
                     f"<img src='{png}' alt='float against exact for {html.escape(scene)}'>{t.html(scroll=True)}")
    return Section([("kernel", "float against exact")], "".join(parts), tables)
