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

2D drawing runs of random-segments get a section on the random autopartition against Paterson and
Yao's bound n + 2n ln n: median fragments over seeds (least to greatest) against the bound on
log-log axes and their ratio (segments-bound.png), a table of the ratio per n, and every heuristic
and shape at the other sizes. Doom runs get a section setting our heuristics beside the external
node builders and the shipped nodes: totals per builder over all maps, the two presets' targets
judged, splits against depth and against CPU time (doom.png), splits and depth per map, and the
structural check's findings per builder.

Each section names the commands that reproduce it: the sweep of the report's suite, then this page.

Needs matplotlib (Debian: python3-matplotlib; call /usr/bin/python3, a pyenv python3 may lack it).
Exit status: 0 written, 2 bad input (unreadable file, not a bspbench report, other version).
"""
import argparse
import html
import json
import math
import os
import re
import statistics
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)

import compare  # noqa: E402  (this script's own modules, beside it)
import cost_model  # noqa: E402
import theory  # noqa: E402
import verdicts  # noqa: E402
from tables import EXTENSIONS, Cell, Table  # noqa: E402

SCHEMA = "bspbench-report"
# Version 5 only added doom runs, so a version 4 report reads as one without them.
VERSIONS = (4, 5)
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
    if report.get("version") not in VERSIONS:
        fail(f"{path}: report version {report.get('version')}, this script reads versions "
             + " and ".join(map(str, VERSIONS)))
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


non_dominated = verdicts.non_dominated


MARKERS = "osD^vP*Xh<>p"


def plot_pareto(scene, aggs, path):
    """One marker per label, named in a legend beside the axes (names written at the points overlap
    where heuristics agree); the Pareto set is ringed in red and starred in the legend."""
    axes, rows = pareto_rows(aggs)
    front = non_dominated(rows)
    fig, ax = plt.subplots(figsize=(9, 5))
    colours = plt.get_cmap("tab20")
    for i, (name, v) in enumerate(sorted(rows)):
        on_front = name in front
        extra = f", {axes[2]} {v[2]:.3g}" if len(axes) == 3 else ""
        ax.scatter([v[0]], [v[1]], s=60, color=colours(i % 20), marker=MARKERS[i % len(MARKERS)], zorder=2,
                   label=("★ " if on_front else "") + name + extra)
        if on_front:
            ax.scatter([v[0]], [v[1]], s=220, facecolors="none", edgecolors="red", linewidths=1.5, zorder=3)
    sizes = sorted({g["by_n"][-1]["n"] for g in aggs if g["by_n"]})
    ax.set_xscale("log")
    ax.margins(x=0.1, y=0.1)
    ax.set_xlabel(axes[0] + " (mean over seeds)")
    ax.set_ylabel(axes[1] + " (mean over seeds)")
    ax.set_title(f"{scene}, {', '.join(verdicts.size_text(n) for n in sizes)}: ★ and red rings = not beaten on all of "
                 + ", ".join(axes), fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return axes, rows, front


def growth_text(agg, section, field):
    fits = agg.get("timing_growth" if section == "timings" else "growth", {})
    fit = fits.get(field)
    return "" if fit is None else f" (k={fit['exponent']:.2f}, R²={fit['r2']:.2f})"


def plot_scaling(scene, aggs, path):
    """Both panels share one legend below them, so no legend covers a line."""
    fig, axes = plt.subplots(1, len(SCALING_AXES), figsize=(12, 5.5))
    colours = plt.get_cmap("tab20")  # more labels than the default cycle's 10 colours
    for ax, (section, field, title) in zip(axes, SCALING_AXES):
        for i, agg in enumerate(aggs):
            pts = [(e["n_polygons"]["mean"], mean_of(e, section, field)) for e in agg["by_n"]]
            pts = [(x, y) for x, y in pts if y is not None and x > 0 and y > 0]
            if pts:
                ax.plot(*zip(*pts), marker=MARKERS[i % len(MARKERS)], color=colours(i % 20),
                        label=agg["label"] + growth_text(agg, section, field))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("polygons (n)")
        ax.set_ylabel(title)
        ax.set_title(f"{scene}: {title} against n, log-log", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=2, frameon=False)
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


def load_metric_docs():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "metric_docs.json")
    with open(path, encoding="utf-8") as f:
        return json.load(f)


METRIC_DOCS = load_metric_docs()


def doc_of(key):
    return METRIC_DOCS["metrics"].get(key, {"group": "other", "unit": "", "better": "", "meaning": ""})


def metric_tables(scene, aggs, command):
    """One table per metric group (size, shape, expected cost, measured cost, time), units in the
    headers; metrics without documentation (other run kinds) go to a last table."""
    keys = sorted({(s, k) for g in aggs for e in g["by_n"] for s in ("metrics", "timings") for k in e[s]})
    order = METRIC_DOCS["groups"] + ["other"]
    tables = []
    for group in order:
        if group == "settings":
            continue
        cols = [(s, k) for s, k in keys if doc_of(k)["group"] == group]
        if not cols:
            continue
        rows = []
        for g in aggs:
            for e in g["by_n"]:
                rows.append([g["label"], e["n"], e["runs"]] +
                            [Cell(e[s][k]["mean"], cell(e[s].get(k))) if e[s].get(k) else None for s, k in cols])
        tables.append(Table(f"metrics-{slug(scene)}-{slug(group)}", f"{scene}: {group}",
                            [("heuristic", ""), ("n", ""), ("runs", "")] + [(k, doc_of(k)["unit"]) for _, k in cols],
                            rows, command))
    return tables


def glossary():
    """The metrics' meanings, once, grouped as the tables are."""
    rows = "".join(
        f"<tr><td>{html.escape(d['group'])}</td><td style='text-align:left'><code>{html.escape(k)}</code></td>"
        f"<td>{html.escape(d['unit'])}</td><td>{html.escape(d['better'] or '—')}</td>"
        f"<td style='text-align:left'>{html.escape(d['meaning'])}</td></tr>"
        for g in METRIC_DOCS["groups"] for k, d in METRIC_DOCS["metrics"].items() if d["group"] == g)
    return ("<h2 id='glossary'>What the metrics mean</h2><table><tr><th>group</th><th>metric</th><th>unit</th>"
            f"<th>better</th><th>meaning</th></tr>{rows}</table>")


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


ENVIRONMENT_COLUMNS = (("date_utc", "date (UTC)"), ("git_revision", "revision"), ("build_type", "build"),
                       ("compiler", "compiler"), ("flags", "flags"), ("cpu_model", "CPU"),
                       ("hardware_threads", "hardware threads"), ("threads", "threads used"), ("host", "host"))
SUMMARY_ROWS = (("runs", "runs"), ("failures", "failed jobs"), ("invariant_violations", "invariant violations"),
                ("validation_violations", "order violations (Embree)"),
                ("ray_shoot_mismatches", "ray-shooting mismatches"),
                ("others_violations", "violations in nodes made by external builders or shipped with a WAD"),
                ("complete", "every job of the suite ran"))


def environment_table(report):
    """One row per shard: where and how it ran, and the calibration its timings are relative to."""
    head = "".join(f"<th>{label}</th>" for _, label in ENVIRONMENT_COLUMNS)
    rows = ""
    for s in report["shards"]:
        env = s.get("environment", {})
        cells = "".join(f"<td>{html.escape(str(env.get(key, '—')))}</td>" for key, _ in ENVIRONMENT_COLUMNS)
        rows += (f"<tr><td>{s['index']}/{s['count']}</td>{cells}"
                 f"<td>{s.get('calibration', {}).get('seconds', float('nan')):.4g}</td></tr>")
    return f"<table><tr><th>shard</th>{head}<th>calibration s</th></tr>{rows}</table>"


def summary_table(summary):
    rows = "".join(f"<tr><th style='text-align:left'>{label}</th><td>{html.escape(str(summary[key]))}</td></tr>"
                   for key, label in SUMMARY_ROWS if key in summary)
    return f"<table>{rows}</table>"


def header(report):
    suite = report["suite"]
    source = suite.get("source")
    text = ""
    if isinstance(source, dict):
        text = (f"<details><summary>suite file {html.escape(str(source.get('path', '')))} "
                f"({html.escape(str(source.get('hash', '')))})</summary>"
                f"<pre>{html.escape(str(source.get('text', '')))}</pre></details>")
    return (f"<h1>bspbench report: suite {html.escape(suite['name'])}</h1>"
            f"<p>definition {html.escape(suite['definition_hash'])}, {suite['jobs']} jobs</p>{text}"
            f"{summary_table(report.get('summary', {}))}<h3>Environment</h3>{environment_table(report)}"
            "<p>Intervals are 95% Student-t intervals over seeds (± half-width). The scene sections' growth "
            "exponents k fit y = c·n^k by least squares on log-log axes over every run; the theory check fits "
            "the sizes' geometric means over seeds and gives each exponent its interval.</p>")


STYLE = ("<style>body{font-family:sans-serif;margin:1em 2em}table{border-collapse:collapse;font-size:12px}"
         "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}th{background:#eee}"
         ".scroll{overflow-x:auto}img{max-width:100%}.alert{border:2px solid #c00;background:#fee;padding:4px 12px}"
         ".ok{border:1px solid #393;background:#efe;padding:4px 12px}.note{font-size:12px;color:#444}"
         ".cmd{font-size:12px}</style>")


def scene_section(scene, aggs, out_dir, how, command, exported):
    pareto_png, scaling_png = f"pareto-{slug(scene)}.png", f"scaling-{slug(scene)}.png"
    axes, _, front = plot_pareto(scene, aggs, os.path.join(out_dir, pareto_png))
    plot_scaling(scene, aggs, os.path.join(out_dir, scaling_png))
    tables = metric_tables(scene, aggs, command)
    exported += tables
    grouped = "".join(f"<h4>{html.escape(t.title.split(': ', 1)[1])}</h4>" + t.html(scroll=True) for t in tables)
    return (f"<h2 id='{slug(scene)}'>{html.escape(scene)}</h2>{how}"
            f"<p>Not beaten on all of {', '.join(axes)} at "
            f"{verdicts.size_text(max(g['by_n'][-1]['n'] for g in aggs if g['by_n']))}: "
            f"<b>{html.escape(', '.join(sorted(front)))}</b> (every size: <a href='#verdicts-{slug(scene)}'>verdicts</a>)</p>"
            f"<img src='{pareto_png}' alt='Pareto view for {html.escape(scene)}'>"
            f"<img src='{scaling_png}' alt='log-log scaling for {html.escape(scene)}'>"
            f"<h3>Growth</h3>{growth_table(aggs)}<h3>Every metric, by group</h3>"
            f"<p>Mean ± half the 95% interval over seeds; units in the headers; meanings in "
            f"<a href='#glossary'>the glossary</a>.</p>{grouped}")


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


def merge_section(report, out_dir, how):
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
             "of the same operands (its wall time in the same run). Column headers explain themselves on hover.</p>"
             + how]
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


def dynamic_section(report, out_dir, how):
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
             "build of the same frame.</p>" + how]
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


def occlusion_section(report, out_dir, how):
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
             "adds to frustum culling.</p>" + how]
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


def sweep_command(report, source):
    suite, shards = report["suite"]["name"], len(report["shards"])
    source_file = report["suite"].get("source")
    if isinstance(source_file, dict) and source_file.get("path"):
        suite = source_file["path"]  # a user's suite file; its text is in the report (suite.source)
    if shards > 1:
        return (f"bspbench sweep --suite {suite} --shard I/{shards} --out shard-I.json (I = 0 to {shards - 1}); "
                f"bspbench merge-reports --out {source} shard-*.json")
    return f"bspbench sweep --suite {suite} --out {source}"


def command_text(report, source, out_dir, extra=""):
    """The commands that remake a table or plot: the sweep, then this page."""
    return f"{sweep_command(report, source)}; bspbench report --in {source} --out {out_dir}{extra}"


def reproduce(report, source, out_dir):
    """The commands that remake a section's tables and plots: the sweep (as shards merged, when it
    ran so) and this page."""
    return (f"<p class=cmd>Reproduce: <code>{html.escape(sweep_command(report, source))}</code>, then "
            f"<code>{html.escape(f'bspbench report --in {source} --out {out_dir}')}</code></p>")


# The setting of Paterson and Yao's bound: n pairwise disjoint segments (generators/random_segments.cpp).
SEGMENT_SCENE = "random-segments"


def autopartition_bound(n):
    """Expected fragments of a random autopartition of n disjoint segments is at most n + 2n ln n
    [PatersonYao1990; deBerg2008 §12.2]."""
    return n + 2 * n * math.log(n)


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


def bound_table(sizes):
    """The ratio table and one sentence: does every size stay under the bound, and how close it comes."""
    rows, ratios = [], []
    for n in sorted(sizes):
        med, lo, hi = spread(sizes[n], "fragments")
        bound = autopartition_bound(n)
        ratios.append((med / bound, hi / bound, n))
        rows.append(f"<tr><td>{n:,}</td><td>{len(sizes[n])}</td><td>{med:,.0f}</td><td>{lo:,}</td><td>{hi:,}</td>"
                    f"<td>{bound:,.0f}</td><td>{med / bound:.3f}</td><td>{hi / bound:.3f}</td>"
                    f"<td>{violations(sizes[n])}</td></tr>")
    worst_median, worst_run = max(ratios), max(ratios, key=lambda r: r[1])
    under = all(hi < 1 for _, hi, _ in ratios)
    verdict = (f"Every size stays under the bound, every seed included: the largest ratio of the median to the "
               f"bound is {worst_median[0]:.3f} (n = {worst_median[2]:,}), of a single run {worst_run[1]:.3f} "
               f"(n = {worst_run[2]:,})." if under else
               "Not every size stays under the bound: over it at n = "
               + ", ".join(f"{n:,} (median ratio {m:.3f}, largest run {h:.3f})" for m, h, n in ratios if h >= 1)
               + f"; the largest ratio of the median to the bound is {worst_median[0]:.3f} (n = {worst_median[2]:,}).")
    return (f"<p><b>{html.escape(verdict)}</b></p>"
            "<table><tr><th>n</th><th>seeds</th><th>median fragments</th><th>least</th><th>greatest</th>"
            "<th>bound n + 2n ln n</th><th>median / bound</th><th>greatest / bound</th>"
            "<th>invariant + order violations</th></tr>" + "".join(rows) + "</table>")


def heuristics_table(groups, sizes):
    """Every heuristic and shape at the given sizes: median fragments (and over the bound) and depths."""
    def medians(runs):
        if not runs:
            return "<td></td>" * 4
        frags = statistics.median(r["metrics"]["fragments"] for r in runs)
        return (f"<td>{frags:,.0f}</td><td>{frags / autopartition_bound(runs[0]['id']['n_polygons']):.3f}</td>"
                f"<td>{statistics.median(r['metrics']['max_depth'] for r in runs):g}</td>"
                f"<td>{statistics.median(r['metrics']['mean_depth'] for r in runs):.2f}</td>")
    largest = sizes[-1]
    ranked = sorted((g for g in groups.items() if largest in g[1]),
                    key=lambda g: statistics.median(r["metrics"]["fragments"] for r in g[1][largest]))
    head = "".join(f"<th colspan=4>n = {n:,}</th>" for n in sizes)
    sub = "<th>fragments</th><th>/ bound</th><th>max depth</th><th>mean depth</th>" * len(sizes)
    def row(heuristic, shape, runs):
        at = [runs.get(n, []) for n in sizes]
        return (f"<tr><td>{html.escape(heuristic)}</td><td>{html.escape(shape)}</td><td>{sum(map(len, at))}</td>"
                f"<td>{sum(map(violations, at))}</td>" + "".join(map(medians, at)) + "</tr>")
    rows = "".join(row(h, shape, runs) for (h, shape), runs in ranked)
    return ("<div class=scroll><table><tr><th rowspan=2>heuristic</th><th rowspan=2>shape</th><th rowspan=2>runs</th>"
            f"<th rowspan=2>invariant + order violations</th>{head}</tr><tr>{sub}</tr>{rows}</table></div>")


def segments_section(report, out_dir, how):
    groups = segment_groups(report)
    if not groups:
        return "", ""
    parts = ["<h2 id='segments'>2D segments: random autopartitions against the Paterson–Yao bound</h2>"
             f"<p>{SEGMENT_SCENE} holds n pairwise disjoint segments in the unit square. A random autopartition "
             "(heuristic random, strict shape: each node splits along the line of a segment chosen uniformly "
             "from its cell) makes at most n + 2n ln n fragments in expectation [PatersonYao1990; deBerg2008 "
             "§12.2]. Medians and least–greatest over seeds; 2D trees get size and shape metrics and the order "
             "check on extruded walls, not the 3D query costs.</p>" + how + failing_runs(groups)]
    bound_sizes = groups.get(("random", "strict"))
    if bound_sizes:
        png = "segments-bound.png"
        plot_bound(bound_sizes, os.path.join(out_dir, png))
        parts.append(f"<img src='{png}' alt='random autopartition fragments against the Paterson–Yao bound'>"
                     + bound_table(bound_sizes))
    # The sizes where more than the bound's series ran: there every heuristic and shape sit side by side.
    sizes = sorted({n for key, runs in groups.items() if key != ("random", "strict") for n in runs})
    if sizes:
        parts.append("<h3>Every heuristic and shape (medians over seeds, ranked by fragments at the largest "
                     "size)</h3>" + heuristics_table(groups, sizes))
    return "<li><a href='#segments'>2D segments</a></li>", "".join(parts)


# The doom-splits preset's target: ZokumBSP 1.1.1 with -na=s (fewest splits), built from source and
# run on this machine on the 68 Freedoom maps (both IWADs), made 23,491 splits in total.
ZOKUM = {"splits": 23491, "iwads": {"freedoom1.wad", "freedoom2.wad"}, "maps": 68}
KIND_MARK = {"heuristic": "", "external": " (external)", "shipped": " (the WAD's own nodes)"}
KIND_MARKER = {"heuristic": "o", "external": "s", "shipped": "D"}


def doom_records(report):
    """The doom records, jobs that threw included (as records with an error and nothing measured)."""
    return [r for r in report["runs"] + report.get("failures", []) if r["id"].get("kind") == "doom"]


def on_zokum_maps(total):
    """Whether a builder built exactly the maps ZokumBSP's split count is for."""
    return total["built"] == ZOKUM["maps"] and {iwad for iwad, _ in total["mapset"]} == ZOKUM["iwads"]


def builder_name(rid):
    """The preset, else the heuristic's label (which names external builders and "shipped" too)."""
    return rid.get("preset") or rid.get("heuristic") or rid["builder"]


def per_builder(records):
    """Builder -> its records, one per map; a builder run with several seeds is one builder per seed."""
    seeds = {}
    for r in records:
        seeds.setdefault(builder_name(r["id"]), set()).add(r["id"].get("seed"))
    builders = {}
    for r in records:
        name = builder_name(r["id"])
        if len(seeds[name]) > 1:
            name += f" (seed {r['id']['seed']})"
        builders.setdefault(name, []).append(r)
    return builders


def doom_cpu(record):
    """Median CPU seconds of a map's timed builds; None for the shipped nodes, which nobody timed here."""
    t = record.get("timings") or {}
    if "doom_cpu_seconds" in t:
        return t["doom_cpu_seconds"]
    samples = t.get("builder_cpu_samples") or t.get("doom_cpu_samples")
    return statistics.median(samples) if samples else None


def doom_failed(record):
    """Not built, or its nodes fail the structural check."""
    return "error" in record or record["invariants"]["violations"] > 0


def doom_totals(builders):
    """One row per builder summed over the maps it built, sorted by splits."""
    rows = []
    for name, recs in builders.items():
        built = [r for r in recs if "error" not in r]
        cpus = [doom_cpu(r) for r in built]
        total = {k: sum(r["metrics"][k] for r in built) for k in ("splits", "segs", "subsectors", "nodes")}
        rows.append(dict(total, name=name, kind=recs[0]["id"]["builder_kind"], maps=len(recs), built=len(built),
                         mapset={(r["id"]["iwad"], r["id"]["map"]) for r in built},
                         cpu=sum(cpus) if cpus and None not in cpus else None,
                         max_depth=statistics.mean(r["metrics"]["max_depth"] for r in built) if built else None,
                         mean_depth=statistics.mean(r["metrics"]["mean_depth"] for r in built) if built else None,
                         failed=sum(doom_failed(r) for r in recs)))
    return sorted(rows, key=lambda t: t["splits"])


def num(x, digits=4):
    return "—" if x is None else f"{x:,}" if isinstance(x, int) else f"{x:.{digits}g}"


def builder_cell(total):
    """Ours in bold, the others in italics and said what they are."""
    tag = "b" if total["kind"] == "heuristic" else "i"
    return f"<td style='text-align:left'><{tag}>{html.escape(total['name'])}</{tag}>{KIND_MARK[total['kind']]}</td>"


def totals_table(totals):
    rows = "".join(
        f"<tr>{builder_cell(t)}<td>{t['built']}{'' if t['built'] == t['maps'] else ' of ' + str(t['maps'])}</td>"
        f"<td>{num(t['cpu'])}</td>"
        f"<td>{t['splits']:,}</td><td>{t['segs']:,}</td><td>{t['subsectors']:,}</td><td>{t['nodes']:,}</td>"
        f"<td>{num(t['max_depth'])}</td><td>{num(t['mean_depth'])}</td><td>{t['failed']}</td></tr>" for t in totals)
    return ("<table><tr><th>builder</th><th>maps</th><th title='sum over maps of the median CPU seconds of the "
            "timed builds'>CPU s</th><th>splits</th><th>segs</th><th>subsectors</th><th>nodes</th>"
            "<th title='mean over maps of the maximum depth'>mean max depth</th>"
            "<th title='mean over maps of the mean subsector depth'>mean subsector depth</th>"
            "<th>maps failing the structural check (or not built)</th></tr>" + rows + "</table>")


def margin(measured, reference, unit=""):
    """How far under (or over) the reference, absolute and relative."""
    diff = reference - measured
    amount = f"{abs(diff):,}" if isinstance(diff, int) else f"{abs(diff):.3g}"
    side = "under" if diff > 0 else "over" if diff < 0 else "exactly at"
    relative = f" ({abs(diff) / reference:.1%})" if reference else ""
    return f"{amount}{unit} {side}{relative}" if diff else side


def target_rows(totals):
    """The two presets' targets, each condition measured: (builder, condition, measured, reference, met, by)."""
    zdbsp = next((t for t in totals if t["name"] == "zdbsp"), None)
    rows = []
    for t in totals:
        preset = t["name"].partition(" (seed ")[0]  # every seed of a preset is judged
        if preset == "doom-splits":
            comparable = on_zokum_maps(t)
            rows.append((t["name"], f"splits at most ZokumBSP 1.1.1 -na=s's {ZOKUM['splits']:,} (the "
                         f"{ZOKUM['maps']} Freedoom maps, measured on this machine)", t["splits"], ZOKUM["splits"],
                         t["splits"] <= ZOKUM["splits"] if comparable else None,
                         margin(t["splits"], ZOKUM["splits"]) if comparable
                         else f"not comparable: {t['built']} maps built, not the {ZOKUM['maps']}"))
            if zdbsp and t["cpu"] is not None and zdbsp["cpu"] is not None:
                rows.append(against_zdbsp(t, zdbsp, "CPU time no more than ZDBSP's in the same run", "cpu",
                                          lambda a, b: a <= b, " s"))
        if preset == "doom-depth" and zdbsp:
            rows.append(against_zdbsp(t, zdbsp, "mean max depth at most ZDBSP's", "max_depth", lambda a, b: a <= b))
            rows.append(against_zdbsp(t, zdbsp, "fewer splits than ZDBSP", "splits", lambda a, b: a < b))
    return rows


def against_zdbsp(total, zdbsp, condition, field, holds, unit=""):
    """A target row against ZDBSP's total, judged only when both built the same maps."""
    mine, ref = total[field], zdbsp[field]
    if total["mapset"] != zdbsp["mapset"]:
        return total["name"], condition, mine, ref, None, "not comparable: not the maps ZDBSP built"
    return total["name"], condition, mine, ref, holds(mine, ref), margin(mine, ref, unit)


def targets_html(totals):
    rows = target_rows(totals)
    if not rows:
        return "<p>Targets not judged: neither preset (doom-splits, doom-depth) ran, or ZDBSP did not.</p>"
    verdicts = []
    for preset in dict.fromkeys(r[0] for r in rows):
        met = [r[4] for r in rows if r[0] == preset]
        word = "missed" if False in met else "not judged" if None in met else "met"
        verdicts.append(f"<b>{html.escape(preset)}: target {word}</b>")
    cells = "".join(
        f"<tr><td>{html.escape(p)}</td><td style='text-align:left'>{html.escape(cond)}</td><td>{num(m, 5)}</td>"
        f"<td>{num(ref, 5)}</td>"
        f"<td>{'—' if ok is None else 'met' if ok else '<b>missed</b>'}</td><td>{html.escape(by)}</td></tr>"
        for p, cond, m, ref, ok, by in rows)
    return ("<p>" + "; ".join(verdicts) + ".</p><table><tr><th>preset</th><th>condition</th><th>measured</th>"
            "<th>reference</th><th>verdict</th><th>by</th></tr>" + cells + "</table>")


def plot_doom(totals, path):
    """Splits against mean max depth and against CPU seconds, a point per builder, the front ringed."""
    rows = math.ceil(len(totals) / 5)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5 + 0.25 * rows))
    colours = plt.get_cmap("tab20").colors  # 14 builders: distinct colours
    for ax, field, title in ((axes[0], "max_depth", "mean max depth over maps"),
                             (axes[1], "cpu", "CPU seconds, all maps")):
        pts = [(t, t["splits"], t[field]) for t in totals if t[field] is not None and t["built"]]
        front = non_dominated([(t["name"], (x, y)) for t, x, y in pts])
        for i, t in enumerate(totals):
            point = next(((x, y) for u, x, y in pts if u is t), None)
            if point is None:
                continue
            ax.scatter(*point, marker=KIND_MARKER[t["kind"]], s=70, color=colours[i % len(colours)], zorder=2,
                       label=t["name"] + KIND_MARK[t["kind"]])
            if t["name"] in front:
                ax.scatter(*point, s=240, facecolors="none", edgecolors="red", linewidths=1.5, zorder=3)
        if any(on_zokum_maps(t) for t in totals):
            ax.axvline(ZOKUM["splits"], color="grey", linestyle="--", linewidth=1)
            ax.annotate("ZokumBSP -na=s", (ZOKUM["splits"], 0), xycoords=("data", "axes fraction"),
                        xytext=(3, 4), textcoords="offset points", fontsize=7, color="grey")
        ax.set_xlabel("splits, all maps")
        ax.set_ylabel(title)
        ax.set_title(f"{title} against splits", fontsize=9)
        ax.grid(True, alpha=0.3)
    # One legend for both panels, below them, so no name covers a point.
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=5, fontsize=8,
               title="● ours, ■ external, ◆ shipped; red rings: not beaten on both axes", title_fontsize=8)
    fig.tight_layout(rect=(0, 0.05 + 0.05 * rows, 1, 1))
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def per_map_table(builders, totals):
    names = [t["name"] for t in totals]
    maps = sorted({(r["id"]["iwad"], r["id"]["map"]) for recs in builders.values() for r in recs})
    by_map = {(name, r["id"]["iwad"], r["id"]["map"]): r for name, recs in builders.items() for r in recs}

    def cells(record):
        if record is None:
            return "<td></td><td></td>"
        title = html.escape(record["id"].get("command", ""), quote=True)
        if "error" in record:
            return f"<td colspan=2 title='{title}'>error</td>"
        mark = " ✗" if doom_failed(record) else ""
        m = record["metrics"]
        return f"<td title='{title}'>{m['splits']:,}{mark}</td><td>{m['max_depth']}</td>"
    head = "".join(f"<th colspan=2>{html.escape(n)}</th>" for n in names)
    rows = "".join(f"<tr><td>{html.escape(iwad)}</td><td>{html.escape(m)}</td>"
                   + "".join(cells(by_map.get((n, iwad, m))) for n in names) + "</tr>" for iwad, m in maps)
    return ("<details><summary>Per map: splits and max depth per builder (hover a splits cell for the command "
            "that repeats the run; ✗ fails the structural check)</summary><div class=scroll><table><tr>"
            f"<th rowspan=2>IWAD</th><th rowspan=2>map</th>{head}</tr>"
            f"<tr>{'<th>splits</th><th>max depth</th>' * len(names)}</tr>{rows}</table></div></details>")


def check_table(builders, totals):
    rows = []
    for t in totals:
        recs = builders[t["name"]]
        built = [r for r in recs if "error" not in r]
        bad = sorted((r for r in built if r["invariants"]["violations"]),
                     key=lambda r: (r["id"]["iwad"], r["id"]["map"]))
        order = [r["validation"] for r in built if r.get("validation")]
        first = next((f"{r['id']['map']}: {r['invariants']['first_problems'][0]}" for r in bad
                      if r["invariants"].get("first_problems")), "")
        errors = "; ".join(f"{r['id']['map']}: {r['error']}" for r in recs if "error" in r)
        worst = {k: max((r["invariants"].get(k, 0) for r in built), default=None)
                 for k in ("worst_side_distance", "worst_convexity_distance")}
        rows.append(f"<tr>{builder_cell(t)}<td>{len(bad)}</td>"
                    f"<td>{sum(r['invariants']['violations'] for r in built)}</td>"
                    f"<td>{num(worst['worst_side_distance'])}</td><td>{num(worst['worst_convexity_distance'])}</td>"
                    f"<td>{num(sum(v['violations'] for v in order) if order else None)}</td>"
                    f"<td>{num(sum(v.get('rays', 0) for v in order) if order else None)}</td>"
                    f"<td style='text-align:left'>{html.escape(first)}</td>"
                    f"<td style='text-align:left'>{html.escape(errors)}</td></tr>")
    return ("<table><tr><th>builder</th><th>maps with violations</th><th>violations</th>"
            "<th title='largest distance (map units, over maps) of a seg endpoint on the wrong side of an "
            "ancestor&#39;s partition, within the tolerance or not'>worst side distance</th>"
            "<th title='largest distance (map units, over maps) of a seg endpoint behind the line of another seg "
            "of its subsector, within the tolerance or not'>worst convexity distance</th>"
            "<th>order-check violations</th><th>order-check rays</th><th>first problem</th><th>errors</th></tr>"
            + "".join(rows) + "</table>")


def doom_section(report, out_dir, how):
    records = doom_records(report)
    if not records:
        return "", ""
    parts = ["<h2 id='doom'>Doom maps: our heuristics beside the node builders</h2>"
             "<p>Each run builds one map's nodes: our heuristics as leafy trees with one sector per leaf, written "
             "as vanilla NODES/SEGS/SSECTORS, or an external node builder (ZDBSP, glBSP) run on the map alone, "
             "or the nodes the WAD shipped with. Every builder's nodes are read back by the same parser and "
             "proved by the same structural check; ours are also proved in back-to-front order against Embree "
             "from the map's first things. CPU time is thread CPU for ours (build and lumps, one thread) and the "
             "child's user + system time for the external builders, the median of the timed builds per map; "
             "the shipped nodes have none. Bold: ours; italic: external builders and the shipped nodes.</p>" + how]
    builders = per_builder(records)
    totals = doom_totals(builders)
    plot_doom(totals, os.path.join(out_dir, "doom.png"))
    maps = {(r["id"]["iwad"], r["id"]["map"]) for r in records}
    # Sums over different maps are not comparable; say so rather than rank them silently.
    uneven = ("<p><b>Not every builder built every map (the maps column): compare totals only between builders "
              "with the same maps.</b></p>" if len({t["built"] for t in totals}) > 1 else "")
    parts.append(f"<h3>Totals over {len(maps)} maps of {html.escape(', '.join(sorted({i for i, _ in maps})))}</h3>"
                 f"{uneven}{totals_table(totals)}<h3>Targets</h3>{targets_html(totals)}"
                 "<img src='doom.png' alt='splits against depth and CPU time, a point per builder'>"
                 f"{per_map_table(builders, totals)}<h3>Structural check</h3>{check_table(builders, totals)}"
                 "<p>Violations in the nodes of ZDBSP, glBSP or the shipped nodes are facts about those nodes "
                 "as the check reads them (a seg endpoint on the wrong side of a partition, or behind another "
                 "seg of its subsector, farther than the tolerance kDoomSideTolerance of "
                 "src/validate/doom_check.h; a subsector of two sectors), not failures of this benchmark; our "
                 "builders must have none.</p>")
    return "<li><a href='#doom'>Doom maps</a></li>", "".join(parts)


def verdict_section(report, command, exported):
    found = verdicts.all_verdicts(report)
    if not found:
        return "", ""
    family = sum(len(items) for items in found.values())
    units = {k: d["unit"] for k, d in METRIC_DOCS["metrics"].items()}
    units["merge_cpu_seconds"] = "s"
    report_groups = verdicts.groups(report)
    significant = sum(v["significant"] for items in found.values() for _, _, v in items)
    parts = [f"<h2 id='verdicts'>Who wins where</h2><p>{family} comparisons (best against runner-up, per scene, "
             f"size and metric), {significant} significant after Holm's correction. Merge runs appear as their solid "
             "pair and operation.</p>"]
    for scene in sorted({s for s, _ in found}):
        t = verdicts.scene_table(scene, found, units, command, family)
        exported.append(t)
        parts.append(f"<h3 id='verdicts-{slug(scene)}'>{html.escape(scene)}</h3>"
                     f"<p>{html.escape(verdicts.pareto_sentences(scene, report_groups))}</p>{t.html(scroll=True)}")
    return "<li><a href='#verdicts'>who wins where (verdicts)</a></li>", "".join(parts)


def cost_model_section(report, out_dir, command, exported):
    rows = cost_model.correlations(report)
    if not rows:
        return "", ""
    t = cost_model.table(rows, command)
    exported.append(t)
    medians = []
    for model, measured, what in cost_model.PAIRINGS:
        rhos = [r[5] for r in rows if r[2] == model and r[3] == measured]
        if rhos:
            medians.append(f"{model} against {what}: median ρ {statistics.median(rhos):.2f} over {len(rhos)} "
                           "scene–size groups")
    plots = ""
    by_scene = {}
    for (scene, n), runs in cost_model.groups(report).items():
        by_scene.setdefault(scene, {})[n] = runs
    for scene, sizes in by_scene.items():
        if not any(r[0] == scene for r in rows):
            continue
        png = f"costmodel-{slug(scene)}.png"
        cost_model.plot_scene(scene, sizes, os.path.join(out_dir, png))
        plots += f"<img src='{png}' alt='expected against measured costs for {html.escape(scene)}'>"
    body = (f"<h2 id='costmodel'>Does the cost model predict?</h2><p>{'; '.join(medians)}.</p>"
            + cost_model.failing_text(rows, cost_model.scene_traits(report)) + t.html(scroll=True)
            + f"<h3>Scatter plots</h3><p class=cmd>Remake: <code>{html.escape(command)}</code></p>{plots}")
    return "<li><a href='#costmodel'>does the cost model predict?</a></li>", body


def theory_section(report, command, exported):
    rows, contradictions, disagreements = theory.analyse(report)
    if not rows:
        return "", "", ""
    t = theory.table(rows, command)
    exported.append(t)
    bounds = "".join(f"<li><b>{html.escape(scene)}</b>: {html.escape(b[3])}"
                     + (f" (heuristics: {', '.join(b[0])})" if b[0] else " (every heuristic)") + "</li>"
                     for scene, b in theory.BOUNDS.items())
    body = (f"<h2 id='theory'>Does the theory hold?</h2><p>The bounds checked:</p><ul>{bounds}</ul>"
            "<p>Exponents are fitted to splits (fragments − n): the bounds are about the fragments a partition "
            "adds, and the linear n bends a short log-log range. An O(n log n) bound is met by exponents up to its "
            "local slope 1 + 1/ln n at the sizes fitted. An explicit bound (n + 2n ln n) is checked size by size.</p>"
            + t.html(scroll=True))
    return "<li><a href='#theory'>does the theory hold?</a></li>", body, theory.top_list(contradictions, disagreements)


def write_exports(tables, out_dir, fmt):
    folder = os.path.join(out_dir, "tables")
    os.makedirs(folder, exist_ok=True)
    for t in tables:
        path = os.path.join(folder, f"{slug(t.name)}.{EXTENSIONS[fmt]}")
        with open(path + ".tmp", "w", encoding="utf-8") as f:
            f.write(t.render(fmt))
        os.replace(path + ".tmp", path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--in", dest="input", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--baseline", help="an earlier report of the same suite")
    parser.add_argument("--comparison", help="the regression gate's comparison of --baseline and --in (JSON)")
    parser.add_argument("--format", choices=sorted(EXTENSIONS), help="also export the tables into OUT/tables")
    args = parser.parse_args()
    report = load(args.input)
    baseline = load(args.baseline) if args.baseline else None
    if baseline is not None and not args.comparison:
        fail("--baseline needs --comparison (bspbench report --baseline writes it)")
    try:
        os.makedirs(args.out, exist_ok=True)
    except OSError as e:
        fail(f"{args.out}: cannot create the output directory ({e})")
    extra = f" --format {args.format}" if args.format else ""
    command = command_text(report, args.input, args.out, extra)
    exported = []
    top, toc, body = "", "", ""
    if baseline is not None:
        changes, tables = compare.section(args.baseline, baseline, report, args.comparison,
                                          command + f" --baseline {args.baseline}")
        exported += tables
        toc += "<li><a href='#changes'>changes against the baseline</a></li>"
        top += changes
    more_toc, more_body = verdict_section(report, command, exported)
    toc, body = toc + more_toc, body + more_body
    more_toc, more_body = cost_model_section(report, args.out, command, exported)
    toc, body = toc + more_toc, body + more_body
    more_toc, more_body, contradictions = theory_section(report, command, exported)
    toc, body = toc + more_toc, body + more_body
    toc += "<li><a href='#glossary'>what the metrics mean</a></li>"
    body += glossary()
    scenes = by_scene(report)
    toc += "".join(f"<li><a href='#{slug(s)}'>{html.escape(s)}</a></li>" for s in scenes)
    how = reproduce(report, args.input, args.out)
    body += "".join(scene_section(s, aggs, args.out, how, command, exported) for s, aggs in scenes.items())
    for section in (merge_section, dynamic_section, occlusion_section, segments_section, doom_section):
        more_toc, more_body = section(report, args.out, how)
        toc += more_toc
        body += more_body
    page = (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>bspbench report</title>{STYLE}</head>"
            f"<body>{header(report)}{contradictions}{top}<h2>Contents</h2><ul>{toc}</ul>{body}</body></html>\n")
    if args.format:
        write_exports(exported, args.out, args.format)
    tmp = os.path.join(args.out, "index.html.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(page)
    os.replace(tmp, os.path.join(args.out, "index.html"))


if __name__ == "__main__":
    main()
