"""2D drawing runs of random-segments: the random autopartition against Paterson and Yao's bound
n + 2n ln n. Median fragments over seeds (least to greatest) against the bound on log-log axes and
their ratio (segments-bound.png), a table of the ratio per n, and every heuristic and shape at the
other sizes.
"""
import html
import os
import statistics

import matplotlib.pyplot as plt

from sections.common import DPI, Section
from sections.theory import autopartition_bound
from tables import Cell, Table

# The setting of Paterson and Yao's bound: n pairwise disjoint segments (generators/random_segments.cpp).
SEGMENT_SCENE = "random-segments"


def segment_groups(report):
    """(heuristic label, shape) -> polygon count -> the runs of the segment scene at that size."""
    groups = {}
    for r in report["runs"]:
        rid = r["id"]
        if rid.get("kind") == "draw" and rid["scene"] == SEGMENT_SCENE:
            groups.setdefault((rid["heuristic"], rid["shape"]), {}).setdefault(rid["n_polygons"], []).append(r)
    return groups


def spread(runs, metric):
    """Median, least and greatest over seeds: with a handful of seeds the extremes are the honest interval."""
    values = [r["metrics"][metric] for r in runs]
    return statistics.median(values), min(values), max(values)


def violations(runs):
    """Structural and order-check violations over the runs (runs with no order check count none)."""
    return sum(r["invariants"]["violations"] + (r.get("validation") or {}).get("violations", 0) for r in runs)


def failing_runs(groups):
    """A line per run with a violation, with its command and first problem, or that none has one."""
    runs = [r for sizes in groups.values() for rs in sizes.values() for r in rs if violations([r])]
    if not runs:
        return "<p>No run has an invariant or order-check violation.</p>"

    def problem(r):
        found = r["invariants"]["first_problems"] or (r.get("validation") or {}).get("first_problems") or [""]
        return found[0]
    items = "".join(f"<li><code>{html.escape(r['id']['command'])}</code>: {violations([r])} "
                    f"({html.escape(problem(r))})</li>" for r in sorted(runs, key=lambda r: r["id"]["command"]))
    return f"<p><b>Runs with an invariant or order-check violation: {len(runs)}</b></p><ul>{items}</ul>"


def plot_bound(sizes, path):
    ns = sorted(sizes)
    med, lo, hi = zip(*(spread(sizes[n], "fragments") for n in ns))
    bounds = [autopartition_bound(n) for n in ns]
    curve = [ns[0] * (ns[-1] / ns[0]) ** (i / 60) for i in range(61)]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    left.errorbar(ns, med, yerr=[[m - x for m, x in zip(med, lo)], [x - m for m, x in zip(med, hi)]], marker="o",
                  capsize=3, label="random autopartition: median fragments (min–max over seeds)")
    left.plot(curve, [autopartition_bound(n) for n in curve], "--", color="red", label="bound n + 2n ln n")
    left.plot(curve, curve, ":", color="grey", label="n (no split at all)")
    left.set_xscale("log")
    left.set_yscale("log")
    left.set_ylabel("fragments")
    left.legend(fontsize=7)
    below = [(m - x) / b for m, x, b in zip(med, lo, bounds)]
    above = [(x - m) / b for m, x, b in zip(med, hi, bounds)]
    right.errorbar(ns, [m / b for m, b in zip(med, bounds)], yerr=[below, above], marker="o", capsize=3)
    right.axhline(1.0, color="red", linewidth=1, linestyle="--")
    right.set_xscale("log")
    right.set_ylim(0, max(1.1, max(hi[i] / bounds[i] for i in range(len(ns))) * 1.1))
    right.set_ylabel("fragments / (n + 2n ln n)")
    for ax, title in ((left, "fragments against n, log-log"), (right, "measured over the bound (1: at the bound)")):
        ax.set_xlabel("segments (n)")
        ax.set_title(f"{SEGMENT_SCENE}, random, strict: {title}", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def grouped(x, spec=","):
    """A number with thousands separated by commas, as the section's prose writes them."""
    return Cell(x, format(x, spec))


def bound_row(n, runs):
    med, lo, hi = spread(runs, "fragments")
    bound = autopartition_bound(n)
    return [grouped(n), len(runs), grouped(med, ",.0f"), grouped(lo), grouped(hi), grouped(bound, ",.0f"),
            Cell(med / bound, f"{med / bound:.3f}"), Cell(hi / bound, f"{hi / bound:.3f}"), violations(runs)]


def bound_verdict(sizes):
    """One sentence: does every size stay under the bound, and how close it comes."""
    ratios = []
    for n in sorted(sizes):
        med, _, hi = spread(sizes[n], "fragments")
        ratios.append((med / autopartition_bound(n), hi / autopartition_bound(n), n))
    worst_median, worst_run = max(ratios), max(ratios, key=lambda r: r[1])
    if all(hi < 1 for _, hi, _ in ratios):
        return (f"Every size stays under the bound, every seed included: the largest ratio of the median to the "
                f"bound is {worst_median[0]:.3f} (n = {worst_median[2]:,}), of a single run {worst_run[1]:.3f} "
                f"(n = {worst_run[2]:,}).")
    return ("Not every size stays under the bound: over it at n = "
            + ", ".join(f"{n:,} (median ratio {m:.3f}, largest run {h:.3f})" for m, h, n in ratios if h >= 1)
            + f"; the largest ratio of the median to the bound is {worst_median[0]:.3f} (n = {worst_median[2]:,}).")


def bound_table(sizes):
    return Table("segments-bound", f"{SEGMENT_SCENE}, random, strict: fragments against n + 2n ln n",
                 [("n", ""), ("seeds", ""), ("median fragments", ""), ("least", ""), ("greatest", ""),
                  ("bound n + 2n ln n", ""), ("median / bound", ""), ("greatest / bound", ""),
                  ("invariant + order violations", "")],
                 [bound_row(n, sizes[n]) for n in sorted(sizes)])


def medians(runs):
    """Median fragments (and over the bound) and depths of one heuristic's runs at one size."""
    if not runs:
        return [None] * 4
    frags = statistics.median(r["metrics"]["fragments"] for r in runs)
    over = frags / autopartition_bound(runs[0]["id"]["n_polygons"])
    max_depth = statistics.median(r["metrics"]["max_depth"] for r in runs)
    mean_depth = statistics.median(r["metrics"]["mean_depth"] for r in runs)
    return [grouped(frags, ",.0f"), Cell(over, f"{over:.3f}"), Cell(max_depth, f"{max_depth:g}"),
            Cell(mean_depth, f"{mean_depth:.2f}")]


def heuristics_table(groups, sizes):
    """Every heuristic and shape at the given sizes, ranked by median fragments at the largest."""
    largest = sizes[-1]
    ranked = sorted((g for g in groups.items() if largest in g[1]),
                    key=lambda g: statistics.median(r["metrics"]["fragments"] for r in g[1][largest]))
    rows = []
    for (heuristic, shape), runs in ranked:
        at = [runs.get(n, []) for n in sizes]
        rows.append([heuristic, shape, sum(map(len, at)), sum(map(violations, at))]
                    + [c for runs_at in at for c in medians(runs_at)])
    return Table("segments-heuristics", f"{SEGMENT_SCENE}: every heuristic and shape, medians over seeds",
                 [("heuristic", ""), ("shape", ""), ("runs", ""), ("invariant + order violations", "")]
                 + [(head, "") for _ in sizes for head in ("fragments", "/ bound", "max depth", "mean depth")],
                 rows, groups=[(None, 4)] + [(f"n = {n:,}", 4) for n in sizes])


def render(report, ctx):
    groups = segment_groups(report)
    if not groups:
        return None
    parts = ["<h2 id='segments'>2D segments: random autopartitions against the Paterson–Yao bound</h2>"
             f"<p>{SEGMENT_SCENE} holds n pairwise disjoint segments in the unit square. A random autopartition "
             "(heuristic random, strict shape: each node splits along the line of a segment chosen uniformly "
             "from its cell) makes at most n + 2n ln n fragments in expectation [PatersonYao1990; deBerg2008 "
             "§12.2]. Medians and least–greatest over seeds; 2D trees get size and shape metrics and the order "
             "check on extruded walls, not the 3D query costs.</p>" + ctx.how + failing_runs(groups)]
    tables = []
    bound_sizes = groups.get(("random", "strict"))
    if bound_sizes:
        png = "segments-bound.png"
        plot_bound(bound_sizes, os.path.join(ctx.out_dir, png))
        tables.append(bound_table(bound_sizes))
        parts.append(f"<img src='{png}' alt='random autopartition fragments against the Paterson–Yao bound'>"
                     f"<p><b>{html.escape(bound_verdict(bound_sizes))}</b></p>{tables[-1].html()}")
    # The sizes where more than the bound's series ran: there every heuristic and shape sit side by side.
    sizes = sorted({n for key, runs in groups.items() if key != ("random", "strict") for n in runs})
    if sizes:
        tables.append(heuristics_table(groups, sizes))
        parts.append("<h3>Every heuristic and shape (medians over seeds, ranked by fragments at the largest "
                     "size)</h3>" + tables[-1].html(scroll=True))
    return Section([("segments", "2D segments")], "".join(parts), tables)
