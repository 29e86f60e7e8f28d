"""Merge runs (set operations on solid pairs): per pair, merge CPU time against the operands' size for
every heuristic and operation (merge-PAIR.png), the result's size before and after reduction at the
largest size (sizes-PAIR.png), a table of merge cost per heuristic and operation, and a verdict per
pair and operation: which heuristic's trees merge fastest, whether its interval over seeds
separates it from the runner-up, and where Naylor's expected-cost trees rank.
"""
import html
import os

import matplotlib.pyplot as plt

from sections.common import DPI, Section, aggregates_of, plain, slug, summary_cell
from tables import Cell, Column, Table

OPERATIONS = ("union", "intersection", "difference", "xor")
# The merge cost columns, with what each counts.
MERGE_COLUMNS = (
    ("metrics", "a_nodes", "nodes of the first operand's solid tree"),
    ("metrics", "a_depth", "its depth"),
    ("metrics", "partition_calls", "partitionTree calls"),
    ("metrics", "partition_nodes", "nodes of the second tree visited while partitioning"),
    ("metrics", "shp_splits", "sub-hyperplanes cut in two"),
    ("metrics", "before_nodes", "result nodes as merged"),
    ("metrics", "after_nodes", "result nodes after reduction"),
    ("metrics", "after_depth", "result depth after reduction"),
    ("timings", "merge_cpu_seconds", "merge and reduce, thread CPU seconds (median of the timed batches)"),
    ("timings", "build_a_cpu_seconds", "first operand's solid tree, thread CPU seconds"),
    ("timings", "corefine_seconds", "CGAL corefinement of the same operands, wall seconds (the reference)"),
)


def by_pair(report):
    """Pair -> operation -> its merge aggregates (one per heuristic), in the order of OPERATIONS."""
    pairs = {}
    for agg in aggregates_of(report, "merge"):
        if agg.get("kernel"):  # the exact kernel's merges are the kernel section's
            continue
        pairs.setdefault(agg["scene"], {}).setdefault(agg["operation"], []).append(agg)
    return {p: {op: ops[op] for op in OPERATIONS if op in ops} for p, ops in sorted(pairs.items())}


def ci_half(summary):
    ci = summary.get("ci95") if summary else None
    return 0.0 if ci is None else (ci[1] - ci[0]) / 2


def plot_merge_time(pair, ops, path):
    fig, axes = plt.subplots(1, len(ops), figsize=(4.2 * len(ops), 4.2), squeeze=False)
    for ax, (op, aggs) in zip(axes[0], ops.items()):
        for agg in sorted(aggs, key=lambda a: a["heuristic"]):
            # Unsized pairs (n = 0) are placed at their polygons per operand.
            pts = [(e["n"] or e["n_polygons"]["mean"] / 2, e["timings"].get("merge_cpu_seconds")) for e in agg["by_n"]]
            pts = [(x, y) for x, y in pts if y is not None and x > 0 and y["mean"] > 0]
            if pts:
                ax.errorbar([x for x, _ in pts], [y["mean"] for _, y in pts], yerr=[ci_half(y) for _, y in pts],
                            marker="o", capsize=2, label=agg["heuristic"])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("polygons per operand (n)")
        ax.set_ylabel("merge CPU time (s)")
        ax.set_title(f"{pair}: {op}", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0][0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 9), fontsize=8)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def plot_merge_sizes(pair, ops, path):
    fig, axes = plt.subplots(1, len(ops), figsize=(4.2 * len(ops), 4.2), squeeze=False)
    for ax, (op, aggs) in zip(axes[0], ops.items()):
        aggs = sorted(aggs, key=lambda a: a["heuristic"])
        names = [a["heuristic"] for a in aggs]
        largest = [a["by_n"][-1] for a in aggs]
        xs = range(len(aggs))
        for offset, field, colour in ((-0.2, "before_nodes", "#bbb"), (0.2, "after_nodes", "#369")):
            vals = [e["metrics"][field] for e in largest]
            ax.bar([x + offset for x in xs], [v["mean"] for v in vals], width=0.4, yerr=[ci_half(v) for v in vals],
                   color=colour, label=field.replace("_", " "))
        ax.set_xticks(list(xs))
        ax.set_xticklabels(names, rotation=45, ha="right", fontsize=8)
        ax.set_yscale("log")
        ax.set_ylabel("result nodes")
        ax.set_title(f"{pair}: {op}, n = {largest[0]['n'] if largest else '?'}", fontsize=9)
        ax.grid(True, axis="y", which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def timing_mean(entry, field):
    t = entry["timings"].get(field)
    return 0.0 if t is None else t["mean"]


def with_builds(entry):
    """Mean seconds of both operands' builds and the merge: the cost of a set operation from meshes."""
    return sum(timing_mean(entry, f) for f in ("build_a_cpu_seconds", "build_b_cpu_seconds", "merge_cpu_seconds"))


def separation(bt, st, one_heuristic):
    """Whether the best's 95% interval over seeds lies wholly below the runner-up's."""
    if one_heuristic:
        return "— (one heuristic)"
    if bt.get("ci95") is None or st.get("ci95") is None:
        return "— (one seed: no interval)"
    return "yes" if bt["ci95"][1] < st["ci95"][0] else "no (intervals overlap)"


def merge_verdict(op, aggs):
    """One row: the heuristic whose trees merge fastest at the largest size, its separation from the
    runner-up (disjoint 95% intervals over seeds), naylor's rank, the smallest result, and the
    fastest with the operands' builds counted, against CGAL's corefinement of the same operands."""
    n = max(a["by_n"][-1]["n"] for a in aggs)
    at_n = [(a["heuristic"], e) for a in aggs for e in a["by_n"] if e["n"] == n]
    ranked = sorted(at_n, key=lambda he: he[1]["timings"]["merge_cpu_seconds"]["mean"])
    (best, b), (second, s) = ranked[0], ranked[1] if len(ranked) > 1 else ranked[0]
    bt, st = b["timings"]["merge_cpu_seconds"], s["timings"]["merge_cpu_seconds"]
    separated = separation(bt, st, len(ranked) == 1)
    if len(ranked) == 1:
        second, st = "—", None
    names = [h for h, _ in ranked]
    naylor = f"{names.index('naylor') + 1} of {len(names)}" if "naylor" in names else "not run"
    smallest = min(at_n, key=lambda he: he[1]["metrics"]["after_nodes"]["mean"])[0]
    total_name, total = min(at_n, key=lambda he: with_builds(he[1]))
    corefine = timing_mean(total, "corefine_seconds")
    ratio = Cell(with_builds(total) / corefine, f"{with_builds(total) / corefine:.3g}") if corefine > 0 else None
    return [op, plain(n) if n else "fixed", best, summary_cell(bt), second, summary_cell(st), separated, naylor, smallest,
            total_name, Cell(with_builds(total), f"{with_builds(total):.4g}"), ratio]


def verdict_table(pair, ops):
    return Table(f"merge-verdicts-{slug(pair)}", f"{pair}: the fastest merge per operation",
                 [("operation", ""), ("n", ""), ("fastest merge", ""), ("merge CPU s", ""), ("runner-up", ""),
                  ("merge CPU s", ""), ("separated", ""), ("naylor's rank", ""), ("smallest result", ""),
                  ("fastest with builds", ""), ("builds + merge s", ""), ("× CGAL corefinement", "")],
                 [merge_verdict(op, aggs) for op, aggs in ops.items()])


def cost_table(pair, ops):
    rows = [[op, g["heuristic"], plain(e["n"]), e["runs"], e["validation_violations"]]
            + [summary_cell(e[s].get(k)) for s, k, _ in MERGE_COLUMNS]
            for op, aggs in ops.items() for g in sorted(aggs, key=lambda a: a["heuristic"]) for e in g["by_n"]]
    return Table(f"merge-cost-{slug(pair)}", f"{pair}: merge cost per heuristic and operation",
                 [("operation", ""), ("heuristic", ""), ("n", ""), ("runs", ""), ("proof violations", "")]
                 + [Column(k, title=doc) for _, k, doc in MERGE_COLUMNS], rows)


def pair_section(pair, ops, out_dir):
    time_png, sizes_png = f"merge-{slug(pair)}.png", f"sizes-{slug(pair)}.png"
    plot_merge_time(pair, ops, os.path.join(out_dir, time_png))
    plot_merge_sizes(pair, ops, os.path.join(out_dir, sizes_png))
    verdicts, cost = verdict_table(pair, ops), cost_table(pair, ops)
    body = (f"<h3 id='merge-{slug(pair)}'>{html.escape(pair)}</h3>{verdicts.html()}"
            f"<img src='{time_png}' alt='merge time against n for {html.escape(pair)}'>"
            f"<img src='{sizes_png}' alt='result size before and after reduction for {html.escape(pair)}'>"
            f"<h4>Merge cost</h4>{cost.html(scroll=True)}")
    return body, [verdicts, cost]


def render(report, ctx):
    pairs = by_pair(report)
    if not pairs:
        return None
    intro = ("<h2 id='merges'>Set operations: merge cost by heuristic</h2>"
             "<p>Each run builds both operands of a solid pair as solid trees with one heuristic, merges them "
             "[Naylor1990], and proves the result against CGAL (point membership, "
             "volume against corefinement, closed boundary). The verdict asks which heuristic's trees merge "
             "fastest at the largest size, whether the 95% intervals over seeds separate it from the runner-up, "
             "where Naylor's expected-cost trees rank, which result is smallest after reduction, and which "
             "heuristic is fastest once both operands' builds are counted, as a multiple of CGAL's corefinement "
             "of the same operands (its wall time in the same run). Column headers explain themselves on hover.</p>"
             + ctx.how)
    parts = [pair_section(pair, ops, ctx.out_dir) for pair, ops in pairs.items()]
    return Section([("merges", "set operations")], intro + "".join(body for body, _ in parts),
                   [t for _, tables in parts for t in tables])
