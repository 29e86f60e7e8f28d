#!/usr/bin/python3
"""Render a bspbench sweep report (analysis/SCHEMA.md) as an HTML page with plots.

    /usr/bin/python3 analysis/report.py --in results/report.json --out results/report

(`bspbench report --in FILE --out DIR` runs this.) Writes DIR/index.html and, per scene, two PNG
plots it links:
  * pareto-SCENE.png: fragments against maximum depth at the largest size, coloured by E_line,
    one point per heuristic (and shape); the heuristics no other beats on all three (lower is
    better on each) are ringed and named in the page;
  * scaling-SCENE.png: build time and fragments against the polygon count on log-log axes, with
    each heuristic's fitted growth exponent in the legend.
Then a table of every metric and timing: mean and 95% interval over seeds, per heuristic and size.

Merge runs (set operations on solid pairs) get their own section: per pair, merge CPU time against
the operands' size for every heuristic and operation (merge-PAIR.png), the result's size before and
after reduction at the largest size (sizes-PAIR.png), a table of merge cost per heuristic and
operation, and a verdict per pair and operation: which heuristic's trees merge fastest, whether its
interval over seeds separates it from the runner-up, and where Naylor's expected-cost trees rank.

Animate runs (dynamic scenes) get a section answering: at what moving fraction and speed does each
update strategy stop beating rebuild? Per scene and size, the update time of every strategy divided
by rebuild's at the same objects and speed, against the moving fraction, one panel per speed
(dynamic-SCENE-N.png), the crossover found, and the drift of the updated trees from fresh builds.
Occlude runs get a section on occlusion culling: per scene, what culling emits against what Embree
sees and against frustum culling alone, and its cost, per heuristic and size (occlusion-SCENE.png).

Needs matplotlib (Debian: python3-matplotlib; call /usr/bin/python3, a pyenv python3 may lack it).
Exit status: 0 written, 2 bad input (unreadable file, not a bspbench report, other version).
"""
import argparse
import html
import json
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)

SCHEMA = "bspbench-report"
VERSION = 4
# The three axes of the Pareto view, all "lower is better": fragments vs depth vs E_line.
PARETO_AXES = ("fragments", "max_depth", "e_line")
SCALING_AXES = (("timings", "build_cpu_seconds", "build CPU time (s)"), ("metrics", "fragments", "fragments"))
DPI = 100


def fail(message):
    print("report.py: " + message, file=sys.stderr)
    sys.exit(2)


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            report = json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{path}: cannot read a JSON report ({e})")
    if not isinstance(report, dict) or report.get("schema") != SCHEMA:
        fail(f"{path}: not a bspbench report")
    if report.get("version") != VERSION:
        fail(f"{path}: report version {report.get('version')}, this script reads version {VERSION}")
    return report


def label(agg, params_vary=False):
    """The heuristic, with the shape when not strict and the scene parameters when they vary."""
    extra = "" if agg["shape"] == "strict" else f" ({agg['shape']})"
    params = agg.get("scene_params") or {}
    if params_vary and params:
        extra += " [" + ",".join(f"{k}={v}" for k, v in sorted(params.items())) + "]"
    return agg["heuristic"] + extra


def slug(text):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text)


def is_merge(agg):
    return agg.get("kind") == "merge"


def kind(agg):
    return agg.get("kind", "draw")


def by_scene(report):
    """Scene -> its drawing aggregates, each given a "label" that tells it from the others of the scene."""
    scenes = {}
    for agg in report["aggregates"]:
        if kind(agg) == "draw":
            scenes.setdefault(agg["scene"], []).append(agg)
    for aggs in scenes.values():
        vary = len({json.dumps(a.get("scene_params"), sort_keys=True) for a in aggs}) > 1
        for a in aggs:
            a["label"] = label(a, vary)
    return dict(sorted(scenes.items()))


def mean_of(entry, section, field):
    s = entry.get(section, {}).get(field)
    return None if s is None else s.get("mean")


def pareto_rows(aggs):
    """(label, values) at each group's largest size, for the axes every group has."""
    axes = [a for a in PARETO_AXES if all(mean_of(g["by_n"][-1], "metrics", a) is not None for g in aggs)]
    rows = [(g["label"], [mean_of(g["by_n"][-1], "metrics", a) for a in axes]) for g in aggs if g["by_n"]]
    return axes, rows


def non_dominated(rows):
    """Labels of the rows no other row beats: at most equal on every axis and lower on one."""
    def beats(a, b):
        return all(x <= y for x, y in zip(a, b)) and any(x < y for x, y in zip(a, b))
    return {name for name, v in rows if not any(beats(w, v) for other, w in rows if other != name)}


def plot_pareto(scene, aggs, path):
    axes, rows = pareto_rows(aggs)
    front = non_dominated(rows)
    fig, ax = plt.subplots(figsize=(7, 5))
    xs = [v[0] for _, v in rows]
    ys = [v[1] for _, v in rows]
    colour = [v[2] for _, v in rows] if len(axes) == 3 else None
    points = ax.scatter(xs, ys, c=colour, cmap="viridis", s=60, zorder=2)
    if colour is not None:
        fig.colorbar(points, ax=ax, label=axes[2] + " (mean)")
    for (name, v), x, y in zip(rows, xs, ys):
        on_front = name in front
        if on_front:
            ax.scatter([x], [y], s=200, facecolors="none", edgecolors="red", linewidths=1.5, zorder=3)
        ax.annotate(name, (x, y), textcoords="offset points", xytext=(6, 4), fontsize=8,
                    fontweight="bold" if on_front else "normal")
    sizes = sorted({g["by_n"][-1]["n"] for g in aggs if g["by_n"]})
    ax.set_xscale("log")
    ax.margins(x=0.2, y=0.1)  # room for the names of the outermost points
    ax.set_xlabel(axes[0] + " (mean over seeds)")
    ax.set_ylabel(axes[1] + " (mean over seeds)")
    ax.set_title(f"{scene}, n = {', '.join(map(str, sizes))}: red rings = not beaten on all of "
                 + ", ".join(axes), fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return axes, rows, front


def growth_text(agg, section, field):
    fits = agg.get("timing_growth" if section == "timings" else "growth", {})
    fit = fits.get(field)
    return "" if fit is None else f" (k={fit['exponent']:.2f}, R²={fit['r2']:.2f})"


def plot_scaling(scene, aggs, path):
    fig, axes = plt.subplots(1, len(SCALING_AXES), figsize=(12, 4.5))
    for ax, (section, field, title) in zip(axes, SCALING_AXES):
        for agg in aggs:
            pts = [(e["n_polygons"]["mean"], mean_of(e, section, field)) for e in agg["by_n"]]
            pts = [(x, y) for x, y in pts if y is not None and x > 0 and y > 0]
            if pts:
                ax.plot(*zip(*pts), marker="o", label=agg["label"] + growth_text(agg, section, field))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("polygons (n)")
        ax.set_ylabel(title)
        ax.set_title(f"{scene}: {title} against n, log-log", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def cell(summary):
    if summary is None:
        return ""
    mean = summary["mean"]
    ci = summary.get("ci95")
    text = f"{mean:.4g}"
    if ci is not None and ci[1] > ci[0]:
        text += f" ± {(ci[1] - ci[0]) / 2:.2g}"
    return html.escape(text)


def metric_table(aggs):
    names = sorted({(s, k) for g in aggs for e in g["by_n"] for s in ("metrics", "timings") for k in e[s]})
    head = "".join(f"<th>{html.escape(k)}</th>" for _, k in names)
    rows = []
    for g in aggs:
        for e in g["by_n"]:
            cells = "".join(f"<td>{cell(e[s].get(k))}</td>" for s, k in names)
            rows.append(f"<tr><td>{html.escape(g['label'])}</td><td>{e['n']}</td><td>{e['runs']}</td>"
                        f"<td>{e['validation_violations']}</td>{cells}</tr>")
    return ("<div class=scroll><table><tr><th>heuristic</th><th>n</th><th>runs</th><th>validation violations</th>"
            + head + "</tr>" + "".join(rows) + "</table></div>")


def growth_table(aggs):
    def fit(f):
        return "" if f is None else f"{f['exponent']:.3f} (R² {f['r2']:.3f})"

    # Against n, build time measures the heuristic only where the scene keeps its density as n grows;
    # elsewhere each polygon meets more others at larger n, so the exponent mixes in the scene.
    def time_vs_n(g):
        if not g.get("constant_density", False):
            return "— (density grows with n)"
        return fit(g["timing_growth"].get("build_cpu_seconds"))
    rows = "".join(
        f"<tr><td>{html.escape(g['label'])}</td><td>{html.escape(time_vs_n(g))}</td>"
        f"<td>{fit(g.get('timing_growth_vs_fragments', {}).get('build_cpu_seconds'))}</td>"
        f"<td>{fit(g['growth'].get('fragments'))}</td><td>{fit(g['growth'].get('nodes'))}</td></tr>" for g in aggs)
    return ("<table><tr><th>heuristic</th><th>build CPU time exponent against n</th>"
            "<th>build CPU time exponent against fragments</th><th>fragments exponent</th>"
            "<th>nodes exponent</th></tr>" + rows + "</table>")


def header(report):
    env = "".join(
        f"<li>shard {s['index']}/{s['count']}: {html.escape(json.dumps(s.get('environment', {})))}, calibration "
        f"{s.get('calibration', {}).get('seconds', float('nan')):.4g} s</li>" for s in report["shards"])
    summary = html.escape(json.dumps(report.get("summary", {})))
    suite = report["suite"]
    return (f"<h1>bspbench report: suite {html.escape(suite['name'])}</h1>"
            f"<p>definition {html.escape(suite['definition_hash'])}, {suite['jobs']} jobs; summary {summary}</p>"
            f"<ul>{env}</ul>"
            "<p>Intervals are 95% Student-t intervals over seeds (± half-width). Growth exponents k fit "
            "y = c·n^k by least squares on log-log axes over every run.</p>")


STYLE = ("<style>body{font-family:sans-serif;margin:1em 2em}table{border-collapse:collapse;font-size:12px}"
         "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}th{background:#eee}"
         ".scroll{overflow-x:auto}img{max-width:100%}</style>")


def scene_section(scene, aggs, out_dir):
    pareto_png, scaling_png = f"pareto-{slug(scene)}.png", f"scaling-{slug(scene)}.png"
    axes, _, front = plot_pareto(scene, aggs, os.path.join(out_dir, pareto_png))
    plot_scaling(scene, aggs, os.path.join(out_dir, scaling_png))
    return (f"<h2 id='{slug(scene)}'>{html.escape(scene)}</h2>"
            f"<p>Not beaten on all of {', '.join(axes)}: <b>{html.escape(', '.join(sorted(front)))}</b></p>"
            f"<img src='{pareto_png}' alt='Pareto view for {html.escape(scene)}'>"
            f"<img src='{scaling_png}' alt='log-log scaling for {html.escape(scene)}'>"
            f"<h3>Growth</h3>{growth_table(aggs)}<h3>Every metric</h3>{metric_table(aggs)}")


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
    for agg in report["aggregates"]:
        if is_merge(agg):
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


def merge_verdict(op, aggs):
    """One row: the heuristic whose trees merge fastest at the largest size, its separation from the
    runner-up (disjoint 95% intervals over seeds), naylor's rank, the smallest result, and the
    fastest with the operands' builds counted, against CGAL's corefinement of the same operands."""
    n = max(a["by_n"][-1]["n"] for a in aggs)
    at_n = [(a["heuristic"], e) for a in aggs for e in a["by_n"] if e["n"] == n]
    ranked = sorted(at_n, key=lambda he: he[1]["timings"]["merge_cpu_seconds"]["mean"])
    (best, b), (second, s) = ranked[0], ranked[1] if len(ranked) > 1 else ranked[0]
    bt, st = b["timings"]["merge_cpu_seconds"], s["timings"]["merge_cpu_seconds"]
    b_hi = bt["ci95"][1] if bt.get("ci95") else bt["mean"]
    s_lo = st["ci95"][0] if st.get("ci95") else st["mean"]
    if len(ranked) == 1:
        second, st, separated = "—", None, "— (one heuristic)"
    elif bt.get("ci95") is None or st.get("ci95") is None:
        separated = "— (one seed: no interval)"
    else:
        separated = "yes" if b_hi < s_lo else "no (intervals overlap)"
    names = [h for h, _ in ranked]
    naylor = f"{names.index('naylor') + 1} of {len(names)}" if "naylor" in names else "not run"
    smallest = min(at_n, key=lambda he: he[1]["metrics"]["after_nodes"]["mean"])[0]
    total_name, total = min(at_n, key=lambda he: with_builds(he[1]))
    corefine = timing_mean(total, "corefine_seconds")
    ratio = f"{with_builds(total) / corefine:.3g}" if corefine > 0 else ""
    size = n if n else "fixed"
    return (f"<tr><td>{html.escape(op)}</td><td>{size}</td><td>{html.escape(best)}</td><td>{cell(bt)}</td>"
            f"<td>{html.escape(second)}</td><td>{cell(st)}</td><td>{separated}</td><td>{naylor}</td>"
            f"<td>{html.escape(smallest)}</td><td>{html.escape(total_name)}</td><td>{with_builds(total):.4g}</td>"
            f"<td>{ratio}</td></tr>")


def merge_table(ops):
    head = "".join(f"<th title='{html.escape(doc)}'>{html.escape(k)}</th>" for _, k, doc in MERGE_COLUMNS)
    rows = []
    for op, aggs in ops.items():
        for g in sorted(aggs, key=lambda a: a["heuristic"]):
            for e in g["by_n"]:
                cells = "".join(f"<td>{cell(e[s].get(k))}</td>" for s, k, _ in MERGE_COLUMNS)
                rows.append(f"<tr><td>{html.escape(op)}</td><td>{html.escape(g['heuristic'])}</td><td>{e['n']}</td>"
                            f"<td>{e['runs']}</td><td>{e['validation_violations']}</td>{cells}</tr>")
    return ("<div class=scroll><table><tr><th>operation</th><th>heuristic</th><th>n</th><th>runs</th>"
            "<th>proof violations</th>" + head + "</tr>" + "".join(rows) + "</table></div>")


def merge_section(report, out_dir):
    pairs = by_pair(report)
    if not pairs:
        return "", ""
    parts = ["<h2 id='merges'>Set operations: merge cost by heuristic</h2>"
             "<p>Each run builds both operands of a solid pair as solid trees with one heuristic, merges them "
             "[Naylor1990], and proves the result against CGAL (point membership, "
             "volume against corefinement, closed boundary). The verdict asks which heuristic's trees merge "
             "fastest at the largest size, whether the 95% intervals over seeds separate it from the runner-up, "
             "where Naylor's expected-cost trees rank, which result is smallest after reduction, and which "
             "heuristic is fastest once both operands' builds are counted, as a multiple of CGAL's corefinement "
             "of the same operands (its wall time in the same run). Column headers explain themselves on hover.</p>"]
    for pair, ops in pairs.items():
        time_png, sizes_png = f"merge-{slug(pair)}.png", f"sizes-{slug(pair)}.png"
        plot_merge_time(pair, ops, os.path.join(out_dir, time_png))
        plot_merge_sizes(pair, ops, os.path.join(out_dir, sizes_png))
        verdicts = "".join(merge_verdict(op, aggs) for op, aggs in ops.items())
        parts.append(
            f"<h3 id='merge-{slug(pair)}'>{html.escape(pair)}</h3>"
            "<table><tr><th>operation</th><th>n</th><th>fastest merge</th><th>merge CPU s</th><th>runner-up</th>"
            "<th>merge CPU s</th><th>separated</th><th>naylor's rank</th><th>smallest result</th>"
            "<th>fastest with builds</th><th>builds + merge s</th><th>× CGAL corefinement</th></tr>"
            f"{verdicts}</table>"
            f"<img src='{time_png}' alt='merge time against n for {html.escape(pair)}'>"
            f"<img src='{sizes_png}' alt='result size before and after reduction for {html.escape(pair)}'>"
            f"<h4>Merge cost</h4>{merge_table(ops)}")
    return "<li><a href='#merges'>set operations</a></li>", "".join(parts)


def value(entry, section, field):
    v = entry.get(section, {}).get(field)
    return None if v is None else v["mean"]


def dynamic_cases(report):
    """(scene, n) -> {(strategy, moving, speed): by_n entry}, for the animate aggregates."""
    cases = {}
    for agg in report["aggregates"]:
        if kind(agg) != "animate":
            continue
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


def plot_dynamic(scene, n, runs, path):
    speeds = sorted({sp for _, _, sp in runs})
    strategies = sorted({st for st, _, _ in runs if st != "rebuild"})
    fig, axes = plt.subplots(1, len(speeds), figsize=(4.2 * len(speeds), 4.2), squeeze=False)
    for ax, speed in zip(axes[0], speeds):
        for st in strategies:
            pts = sorted((value(e, "metrics", "moving_fraction"), update_ratio(runs, st, m, speed))
                         for (s2, m, sp), e in runs.items() if s2 == st and sp == speed)
            pts = [(x, y) for x, y in pts if x is not None and y is not None]
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


def crossover_rows(runs):
    """Per strategy and speed: the largest moving fraction where it still beats rebuild (ratio < 1) and
    the smallest where it no longer does."""
    rows = []
    for st in sorted({st for st, _, _ in runs if st != "rebuild"}):
        for speed in sorted({sp for _, _, sp in runs}):
            pts = sorted((value(e, "metrics", "moving_fraction"), update_ratio(runs, st, m, speed))
                         for (s2, m, sp), e in runs.items() if s2 == st and sp == speed)
            pts = [(x, r) for x, r in pts if x is not None and r is not None]
            if not pts:
                continue
            wins = [x for x, r in pts if r < 1]
            losses = [x for x, r in pts if r >= 1]
            if not losses:
                verdict = f"beats rebuild at every fraction measured (to {pts[-1][0]:.3g})"
            elif not wins:
                verdict = f"never beats rebuild (from {pts[0][0]:.3g})"
            else:
                # Where it stops winning: the first fraction past its last win, else its first loss.
                stop = min((x for x in losses if x > max(wins)), default=min(losses))
                verdict = f"beats rebuild up to {max(wins):.3g}, not at {stop:.3g}"
            ratios = ", ".join(f"{r:.2g}" for _, r in pts)
            rows.append(f"<tr><td>{html.escape(st)}</td><td>{speed}</td><td>{html.escape(verdict)}</td>"
                        f"<td>{html.escape(ratios)}</td></tr>")
    return rows


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


def drift_table(runs):
    head = "".join(f"<th title='{html.escape(doc)}'>{html.escape(k)}</th>" for _, k, doc in DRIFT_COLUMNS)
    rows = []
    for (st, m, sp), e in sorted(runs.items()):
        cells = "".join(f"<td>{cell(e[s].get(k))}</td>" for s, k, _ in DRIFT_COLUMNS)
        rows.append(f"<tr><td>{html.escape(st)}</td><td>{m}</td><td>{sp}</td><td>{e['runs']}</td>"
                    f"<td>{e['validation_violations']}</td>{cells}</tr>")
    return ("<div class=scroll><table><tr><th>strategy</th><th>moving objects</th><th>speed</th><th>runs</th>"
            "<th>order violations</th>" + head + "</tr>" + "".join(rows) + "</table></div>")


def dynamic_section(report, out_dir):
    cases = dynamic_cases(report)
    if not cases:
        return "", ""
    parts = ["<h2 id='dynamic'>Dynamic scenes: when does updating beat rebuilding?</h2>"
             "<p>Each run moves spheres through a static scene for a number of frames and keeps one tree with an "
             "update strategy: rebuild (a full build per frame), reinsert and reinsert-each (Chrysanthou and "
             "Slater's removal and reinsertion), merge (Naylor's per-frame merge of the objects' trees into the "
             "static tree) and torres (object trees in cells, separating planes, moved in place while they stay). "
             "Checked frames pass the tree invariants and the Embree order check. The plots give each strategy's "
             "median update time over rebuild's at the same objects and speed (below the dashed line it wins); "
             "the table says where each stops winning. Drift compares the last drift frame's tree with a fresh "
             "build of the same frame.</p>"]
    for (scene, n), runs in cases.items():
        png = f"dynamic-{slug(scene)}-{n}.png"
        plot_dynamic(scene, n, runs, os.path.join(out_dir, png))
        parts.append(f"<h3 id='dynamic-{slug(scene)}-{n}'>{html.escape(scene)}, n = {n}</h3>"
                     "<table><tr><th>strategy</th><th>speed</th><th>crossover with rebuild</th>"
                     "<th>time ratios, by moving fraction</th></tr>" + "".join(crossover_rows(runs)) + "</table>"
                     f"<img src='{png}' alt='update time over rebuild for {html.escape(scene)}'>"
                     f"<h4>Drift and work</h4>{drift_table(runs)}")
    return "<li><a href='#dynamic'>dynamic scenes</a></li>", "".join(parts)


OCCLUSION_COLUMNS = (("metrics", "emitted", "fragments emitted, all views"),
                     ("metrics", "seen_by_embree", "fragments some Embree ray sees first, all views"),
                     ("metrics", "frustum_culled", "fragments frustum culling alone emits, all views"),
                     ("metrics", "emitted_per_seen_mean", "emitted / seen, mean over views (1 = exact)"),
                     ("metrics", "emitted_per_frustum_culled_mean", "emitted / frustum-culled, mean over views"),
                     ("metrics", "beam_nodes", "beam tree nodes at the end, all views"),
                     ("metrics", "beam_merges", "OUT leaves replaced by a piece's beam, all views"),
                     ("metrics", "subtrees_culled", "subtrees skipped whole, all views"),
                     ("metrics", "views_covered", "views where the beam covered the view and the walk stopped"),
                     ("timings", "occlude_cpu_seconds", "culling one view, thread CPU seconds"))


def occlusion_section(report, out_dir):
    scenes = {}
    for agg in report["aggregates"]:
        if kind(agg) == "occlude":
            scenes.setdefault(agg["scene"], []).append(agg)
    if not scenes:
        return "", ""
    parts = ["<h2 id='occlusion'>Occlusion culling by beam tracing</h2>"
             "<p>The scene tree is walked front to back in the view frustum while a beam tree of the directions "
             "already covered grows by merging each drawn fragment's cone; hidden fragments and subtrees are "
             "skipped [Naylor1992]. Every view is proved conservative by Embree primary rays (proof violations "
             "count rays whose first hit was culled). Emitted / seen says how tight the output is (seen: the "
             "fragments rays meet first, a lower bound of the visible set); emitted / frustum-culled what occlusion "
             "adds to frustum culling.</p>"]
    for scene, aggs in sorted(scenes.items()):
        png = f"occlusion-{slug(scene)}.png"
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
        for agg in sorted(aggs, key=lambda a: a["heuristic"]):
            for ax, field in zip(axes, ("emitted_per_seen_mean", "emitted_per_frustum_culled_mean")):
                pts = [(e["n_polygons"]["mean"], value(e, "metrics", field)) for e in agg["by_n"]]
                pts = [(x, y) for x, y in pts if y]
                if pts:
                    ax.plot(*zip(*pts), marker="o", label=agg["heuristic"])
        for ax, title in zip(axes, ("emitted / seen by Embree", "emitted / frustum-culled")):
            ax.set_xscale("log")
            ax.set_xlabel("polygons (n)")
            ax.set_ylabel(title)
            ax.set_title(f"{scene}: {title}", fontsize=9)
            ax.grid(True, which="both", alpha=0.3)
        handles, labels = axes[0].get_legend_handles_labels()
        if handles:
            fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 9), fontsize=8)
        fig.tight_layout(rect=(0, 0.1, 1, 1))
        fig.savefig(os.path.join(out_dir, png), dpi=DPI)
        plt.close(fig)
        head = "".join(f"<th title='{html.escape(doc)}'>{html.escape(k)}</th>" for _, k, doc in OCCLUSION_COLUMNS)
        rows = "".join(
            f"<tr><td>{html.escape(g['heuristic'])}</td><td>{e['n']}</td><td>{e['runs']}</td>"
            f"<td>{e['validation_violations']}</td>" + "".join(f"<td>{cell(e[s].get(k))}</td>" for s, k, _ in OCCLUSION_COLUMNS)
            + "</tr>" for g in sorted(aggs, key=lambda a: a["heuristic"]) for e in g["by_n"])
        parts.append(f"<h3 id='occlusion-{slug(scene)}'>{html.escape(scene)}</h3>"
                     f"<img src='{png}' alt='occlusion tightness for {html.escape(scene)}'>"
                     "<div class=scroll><table><tr><th>heuristic</th><th>n</th><th>runs</th><th>proof violations</th>"
                     + head + "</tr>" + rows + "</table></div>")
    return "<li><a href='#occlusion'>occlusion culling</a></li>", "".join(parts)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--in", dest="input", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    report = load(args.input)
    try:
        os.makedirs(args.out, exist_ok=True)
    except OSError as e:
        fail(f"{args.out}: cannot create the output directory ({e})")
    scenes = by_scene(report)
    toc = "".join(f"<li><a href='#{slug(s)}'>{html.escape(s)}</a></li>" for s in scenes)
    body = "".join(scene_section(s, aggs, args.out) for s, aggs in scenes.items())
    for section in (merge_section, dynamic_section, occlusion_section):
        more_toc, more_body = section(report, args.out)
        toc += more_toc
        body += more_body
    page = (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>bspbench report</title>{STYLE}</head>"
            f"<body>{header(report)}<ul>{toc}</ul>{body}</body></html>\n")
    tmp = os.path.join(args.out, "index.html.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(page)
    os.replace(tmp, os.path.join(args.out, "index.html"))


if __name__ == "__main__":
    main()
