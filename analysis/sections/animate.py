"""Animate runs (dynamic scenes), answering: at what moving fraction and speed does each update
strategy stop beating rebuild? Per scene and size, the update time of every strategy divided by
rebuild's at the same objects and speed, against the moving fraction, one panel per speed
(dynamic-SCENE-N.png), the crossover found, and the drift of the updated trees from fresh builds.
"""
import html
import os

import matplotlib.pyplot as plt

from sections.common import DPI, Section, aggregates_of, plain, slug, summary_cell, value
from tables import Column, Table


def dynamic_cases(report):
    """(scene, n) -> {(strategy, moving, speed): by_n entry}, for the animate aggregates."""
    cases = {}
    for agg in aggregates_of(report, "animate"):
        for e in agg["by_n"]:
            cases.setdefault((agg["scene"], e["n"]), {})[(agg["strategy"], agg["moving"], agg["speed"])] = e
    return dict(sorted(cases.items()))


def update_ratio(runs, strategy, moving, speed):
    """Mean update time of a strategy over rebuild's at the same objects and speed."""
    mine, base = runs.get((strategy, moving, speed)), runs.get(("rebuild", moving, speed))
    if mine is None or base is None:
        return None
    t, b = value(mine, "timings", "update_cpu_seconds"), value(base, "timings", "update_cpu_seconds")
    return None if not t or not b else t / b


def ratio_points(runs, strategy, speed):
    """(moving fraction, update ratio) of a strategy at a speed, by fraction, where both are known."""
    pts = sorted((value(e, "metrics", "moving_fraction"), update_ratio(runs, strategy, m, speed))
                 for (s2, m, sp), e in runs.items() if s2 == strategy and sp == speed)
    return [(x, r) for x, r in pts if x is not None and r is not None]


def plot_dynamic(scene, n, runs, path):
    speeds = sorted({sp for _, _, sp in runs})
    strategies = sorted({st for st, _, _ in runs if st != "rebuild"})
    fig, axes = plt.subplots(1, len(speeds), figsize=(4.2 * len(speeds), 4.2), squeeze=False)
    for ax, speed in zip(axes[0], speeds):
        for st in strategies:
            pts = ratio_points(runs, st, speed)
            if pts:
                ax.plot(*zip(*pts), marker="o", label=st)
        ax.axhline(1.0, color="red", linewidth=1, linestyle="--")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("moving fraction of the polygons")
        ax.set_ylabel("update time / rebuild's")
        ax.set_title(f"{scene}, n = {n}, speed {speed} diagonals/frame", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0][0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=8)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def crossover(pts):
    """Where a strategy stops beating rebuild (ratio < 1), said in words."""
    wins = [x for x, r in pts if r < 1]
    losses = [x for x, r in pts if r >= 1]
    if not losses:
        return f"beats rebuild at every fraction measured (to {pts[-1][0]:.3g})"
    if not wins:
        return f"never beats rebuild (from {pts[0][0]:.3g})"
    # Where it stops winning: the first fraction past its last win, else its first loss.
    stop = min((x for x in losses if x > max(wins)), default=min(losses))
    return f"beats rebuild up to {max(wins):.3g}, not at {stop:.3g}"


def crossover_table(scene, n, runs):
    """Per strategy and speed: the largest moving fraction where it still beats rebuild and the
    smallest where it no longer does."""
    rows = []
    for st in sorted({st for st, _, _ in runs if st != "rebuild"}):
        for speed in sorted({sp for _, _, sp in runs}):
            pts = ratio_points(runs, st, speed)
            if pts:
                rows.append([st, plain(speed), crossover(pts), ", ".join(f"{r:.2g}" for _, r in pts)])
    return Table(f"dynamic-crossover-{slug(scene)}-{n}", f"{scene}, n = {n}: crossover with rebuild",
                 [("strategy", ""), ("speed", ""), ("crossover with rebuild", ""),
                  ("time ratios, by moving fraction", "")], rows)


DRIFT_COLUMNS = (("metrics", "drift_fragments_ratio", "fragments / a fresh build's, last drift frame"),
                 ("metrics", "drift_culled_nodes_visited_ratio", "culled traversal nodes / a fresh build's"),
                 ("metrics", "drift_depth_ratio", "depth / a fresh build's"),
                 ("metrics", "work_repairs", "removed nodes with two non-empty subtrees, all updates"),
                 ("metrics", "work_reinserted_fragments", "fragments those repairs reinserted"),
                 ("metrics", "work_partitioned_nodes", "object-tree nodes partitioned by host planes"),
                 ("metrics", "work_moved_nodes", "nodes moved in place (torres)"),
                 ("metrics", "work_objects_whole", "objects placed whole in one cell"),
                 ("timings", "update_cpu_seconds", "median update, thread CPU seconds"),
                 ("timings", "start_cpu_seconds", "first frame (the whole build), thread CPU seconds"))


def drift_table(scene, n, runs):
    rows = [[st, m, plain(sp), e["runs"], e["validation_violations"]]
            + [summary_cell(e[s].get(k)) for s, k, _ in DRIFT_COLUMNS] for (st, m, sp), e in sorted(runs.items())]
    return Table(f"dynamic-drift-{slug(scene)}-{n}", f"{scene}, n = {n}: drift and work",
                 [("strategy", ""), ("moving objects", ""), ("speed", ""), ("runs", ""), ("order violations", "")]
                 + [Column(k, title=doc) for _, k, doc in DRIFT_COLUMNS], rows)


def case_section(scene, n, runs, out_dir):
    png = f"dynamic-{slug(scene)}-{n}.png"
    plot_dynamic(scene, n, runs, os.path.join(out_dir, png))
    cross, drift = crossover_table(scene, n, runs), drift_table(scene, n, runs)
    body = (f"<h3 id='dynamic-{slug(scene)}-{n}'>{html.escape(scene)}, n = {n}</h3>{cross.html()}"
            f"<img src='{png}' alt='update time over rebuild for {html.escape(scene)}'>"
            f"<h4>Drift and work</h4>{drift.html(scroll=True)}")
    return body, [cross, drift]


def render(report, ctx):
    cases = dynamic_cases(report)
    if not cases:
        return None
    intro = ("<h2 id='dynamic'>Dynamic scenes: when does updating beat rebuilding?</h2>"
             "<p>Each run moves spheres through a static scene for a number of frames and keeps one tree with an "
             "update strategy: rebuild (a full build per frame), reinsert and reinsert-each (Chrysanthou and "
             "Slater's removal and reinsertion), merge (Naylor's per-frame merge of the objects' trees into the "
             "static tree) and torres (object trees in cells, separating planes, moved in place while they stay). "
             "Checked frames pass the tree invariants and the Embree order check. The plots give each strategy's "
             "median update time over rebuild's at the same objects and speed (below the dashed line it wins); "
             "the table says where each stops winning. Drift compares the last drift frame's tree with a fresh "
             "build of the same frame.</p>" + ctx.how)
    parts = [case_section(scene, n, runs, ctx.out_dir) for (scene, n), runs in cases.items()]
    return Section([("dynamic", "dynamic scenes")], intro + "".join(body for body, _ in parts),
                   [t for _, tables in parts for t in tables])
