"""The drawing runs, one section per scene: per scene, two PNG plots and the tables of every metric.
  * pareto-SCENE.png: fragments against maximum depth at the largest size, coloured by E_line,
    one point per heuristic (and shape); the heuristics no other beats on all three (lower is
    better on each) are ringed and named in the page;
  * scaling-SCENE.png: build time and fragments against the polygon count on log-log axes, with
    each heuristic's fitted growth exponent (report.json's growth fits) in the legend.
Then the growth exponents and a table per metric group: mean and 95% interval over seeds, per
heuristic and size.
"""
import html
import json
import os

import matplotlib.pyplot as plt

from sections import verdicts
from sections.common import (DPI, MARKERS, METRIC_DOCS, Section, aggregates_of, doc_of, is_float, slug, summary_cell,
                             value)
from tables import Cell, Table

SCALING_AXES = (("timings", "build_cpu_seconds", "build CPU time (s)"), ("metrics", "fragments", "fragments"))


def label(agg, params_vary=False):
    """The heuristic, with the shape when not strict and the scene parameters when they vary."""
    extra = "" if agg["shape"] == "strict" else f" ({agg['shape']})"
    params = agg.get("scene_params") or {}
    if params_vary and params:
        extra += " [" + ",".join(f"{k}={v}" for k, v in sorted(params.items())) + "]"
    return agg["heuristic"] + extra


def by_scene(report):
    """Scene -> its drawing aggregates (the float kernel's; exact runs are the kernel section's), each
    given a "label" that tells it from the others of the scene."""
    scenes = {}
    for agg in filter(is_float, aggregates_of(report, "draw")):
        scenes.setdefault(agg["scene"], []).append(agg)
    for aggs in scenes.values():
        vary = len({json.dumps(a.get("scene_params"), sort_keys=True) for a in aggs}) > 1
        for a in aggs:
            a["label"] = label(a, vary)
    return dict(sorted(scenes.items()))


def pareto_rows(aggs):
    """(label, values) at each group's largest size, for the axes every group has."""
    axes = [a for a in verdicts.PARETO_AXES if all(value(g["by_n"][-1], "metrics", a) is not None for g in aggs)]
    rows = [(g["label"], [value(g["by_n"][-1], "metrics", a) for a in axes]) for g in aggs if g["by_n"]]
    return axes, rows


def plot_pareto(scene, aggs, path):
    """One marker per label, named in a legend beside the axes (names written at the points overlap
    where heuristics agree); the Pareto set is ringed in red and starred in the legend."""
    axes, rows = pareto_rows(aggs)
    front = verdicts.non_dominated(rows)
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
    return axes, front


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
            pts = [(e["n_polygons"]["mean"], value(e, section, field)) for e in agg["by_n"]]
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


def metric_tables(scene, aggs, command):
    """One table per metric group (size, shape, expected cost, measured cost, time), units in the
    headers; metrics without documentation (other run kinds) go to a last table."""
    keys = sorted({(s, k) for g in aggs for e in g["by_n"] for s in ("metrics", "timings") for k in e[s]})
    tables = []
    for group in METRIC_DOCS["groups"] + ["other"]:
        if group == "settings":
            continue
        cols = [(s, k) for s, k in keys if doc_of(k)["group"] == group]
        if not cols:
            continue
        rows = [[g["label"], e["n"], e["runs"]] + [summary_cell(e[s].get(k)) for s, k in cols]
                for g in aggs for e in g["by_n"]]
        tables.append(Table(f"metrics-{slug(scene)}-{slug(group)}", f"{scene}: {group}",
                            [("heuristic", ""), ("n", ""), ("runs", "")] + [(k, doc_of(k)["unit"]) for _, k in cols],
                            rows, command))
    return tables


def fit_cell(fit):
    return None if fit is None else Cell(fit["exponent"], f"{fit['exponent']:.3f} (R² {fit['r2']:.3f})")


def time_vs_n(agg):
    """Against n, build time measures the heuristic only where the scene keeps its density as n grows;
    elsewhere each polygon meets more others at larger n, so the exponent mixes in the scene."""
    if not agg.get("constant_density", False):
        return Cell(None, "— (density grows with n)")
    return fit_cell(agg["timing_growth"].get("build_cpu_seconds"))


def growth_table(scene, aggs):
    rows = [[g["label"], time_vs_n(g), fit_cell(g.get("timing_growth_vs_fragments", {}).get("build_cpu_seconds")),
             fit_cell(g["growth"].get("fragments")), fit_cell(g["growth"].get("nodes"))] for g in aggs]
    return Table(f"growth-{slug(scene)}", f"{scene}: growth exponents over every run",
                 [("heuristic", ""), ("build CPU time exponent against n", ""),
                  ("build CPU time exponent against fragments", ""), ("fragments exponent", ""),
                  ("nodes exponent", "")], rows)


def scene_section(scene, aggs, ctx):
    """The scene's HTML and its tables."""
    pareto_png, scaling_png = f"pareto-{slug(scene)}.png", f"scaling-{slug(scene)}.png"
    axes, front = plot_pareto(scene, aggs, os.path.join(ctx.out_dir, pareto_png))
    plot_scaling(scene, aggs, os.path.join(ctx.out_dir, scaling_png))
    growth = growth_table(scene, aggs)
    metrics = metric_tables(scene, aggs, ctx.command)
    grouped = "".join(f"<h4>{html.escape(t.title.split(': ', 1)[1])}</h4>" + t.html(scroll=True) for t in metrics)
    body = (f"<h2 id='{slug(scene)}'>{html.escape(scene)}</h2>{ctx.how}"
            f"<p>Not beaten on all of {', '.join(axes)} at "
            f"{verdicts.size_text(max(g['by_n'][-1]['n'] for g in aggs if g['by_n']))}: "
            f"<b>{html.escape(', '.join(sorted(front)))}</b> (every size: <a href='#verdicts-{slug(scene)}'>verdicts</a>)</p>"
            f"<img src='{pareto_png}' alt='Pareto view for {html.escape(scene)}'>"
            f"<img src='{scaling_png}' alt='log-log scaling for {html.escape(scene)}'>"
            f"<h3>Growth</h3>{growth.html()}<h3>Every metric, by group</h3>"
            f"<p>Mean ± half the 95% interval over seeds; units in the headers; meanings in "
            f"<a href='#glossary'>the glossary</a>.</p>{grouped}")
    return body, [growth] + metrics


def render(report, ctx):
    scenes = by_scene(report)
    if not scenes:
        return None
    parts = [scene_section(scene, aggs, ctx) for scene, aggs in scenes.items()]
    return Section([(slug(s), s) for s in scenes], "".join(body for body, _ in parts),
                   [t for _, tables in parts for t in tables])
