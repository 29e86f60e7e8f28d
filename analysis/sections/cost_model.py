"""Does Naylor's cost model predict? Per scene and size, Spearman's rank correlation [Spearman1904] between an
expected cost [Naylor1993] and the cost measured on the same tree, across every heuristic and seed
of the group, with a seeded percentile-bootstrap interval [Efron1979] that resamples whole heuristics (a label's
runs over seeds and shapes are not independent of each other).

A rank correlation answers the question a user of the model asks: does the tree the model calls
cheaper measure cheaper? The model predicts a group when the interval's lower end is at least
PREDICTS, fails when its upper end is below PREDICTS, and is undecided otherwise.

Notation: ρ Spearman's rank correlation; CI its 95% bootstrap interval.
"""
import html
import os
import statistics

import matplotlib.pyplot as plt

import stats
from sections import verdicts
from sections.common import DPI, Section, is_float, slug
from tables import Cell, Table

PREDICTS = 0.8
BOOTSTRAP_REPS = 1000
MIN_RUNS = 4  # fewer runs in a group give no rank correlation worth an interval
# A failing scene's fragments per node count as many when they exceed the others' by this factor.
MANY_PER_NODE = 1.2
# (model metric, measured metric, what is measured)
PAIRINGS = (
    ("e_line", "ray_nodes_visited", "nodes visited per ray"),
    ("e_point", "point_plane_tests", "plane tests per point location"),
    ("e_line", "culled_nodes_visited", "nodes of a culled traversal"),
)


def groups(report):
    """(scene, n) -> the float kernel's drawing runs of that scene and size, every heuristic, shape and seed."""
    name = verdicts.scene_namer(report)
    out = {}
    for r in report["runs"]:
        rid = r["id"]
        if rid.get("kind", "draw") == "draw" and is_float(rid):
            out.setdefault((name(rid), rid["n"]), []).append(r)
    return dict(sorted(out.items()))


def clusters_of(runs, model, measured):
    """The runs' (model, measured) pairs, one cluster per heuristic."""
    by_heuristic = {}
    for r in runs:
        by_heuristic.setdefault(r["id"]["heuristic"], []).append(r)
    return [c for c in (pairs_of(rs, model, measured) for rs in by_heuristic.values()) if c]


def pairs_of(runs, model, measured):
    return [(r["metrics"][model], r["metrics"][measured]) for r in runs
            if isinstance(r["metrics"].get(model), (int, float)) and isinstance(r["metrics"].get(measured), (int, float))]


def status(ci):
    if ci is None:
        return "undecided"
    if ci[0] >= PREDICTS:
        return "predicts"
    if ci[1] < PREDICTS:
        return "fails"
    return "undecided"


def correlations(report):
    """[(scene, n, model, measured, what, rho, ci, points, status)] for every group and pairing with data."""
    out = []
    for (scene, n), runs in groups(report).items():
        for model, measured, what in PAIRINGS:
            pairs = pairs_of(runs, model, measured)
            clusters = clusters_of(runs, model, measured)
            if len(pairs) < MIN_RUNS or len(clusters) < 2:
                continue
            rho = stats.spearman([a for a, _ in pairs], [b for _, b in pairs])
            if rho is None:
                continue
            ci = stats.bootstrap_interval(clusters, stats.spearman, reps=BOOTSTRAP_REPS)
            out.append((scene, n, model, measured, what, rho, ci, len(pairs), status(ci)))
    return out


def table(rows, command):
    body = []
    for scene, n, model, measured, what, rho, ci, points, verdict in rows:
        body.append([scene, n, f"{model} vs {what}", rho, Cell(ci[0] if ci else None), Cell(ci[1] if ci else None),
                     points, Cell(verdict, bold=verdict == "fails")])
    return Table("cost-model", "Rank correlation of Naylor's expected costs with measured costs",
                 [("scene", ""), ("n", ""), ("model vs measured", ""), ("ρ", ""), ("CI low", ""), ("CI high", ""),
                  ("runs", ""), ("verdict", "")], body, command,
                 f"Spearman's ρ over every heuristic, shape and seed of a scene and size; 95% percentile bootstrap "
                 f"interval ({BOOTSTRAP_REPS} seeded resamples of whole heuristics). Predicts: interval at or above "
                 f"{PREDICTS}; fails: interval below it.")


def scene_traits(report):
    """scene -> (median fragments per node, spread of e_line across labels as max/min of the means at the
    largest size): what a failing scene may have in common."""
    per_scene = {}
    for (scene, n), runs in groups(report).items():
        per_scene.setdefault(scene, {})[n] = runs
    traits = {}
    for scene, sizes in per_scene.items():
        runs = sizes[max(sizes)]
        ratios = [r["metrics"]["fragments"] / r["metrics"]["nodes"] for r in runs
                  if r["metrics"].get("nodes") and r["metrics"].get("fragments") is not None]
        by_label = {}
        for r in runs:
            if isinstance(r["metrics"].get("e_line"), (int, float)):
                by_label.setdefault((r["id"]["heuristic"], r["id"]["shape"]), []).append(r["metrics"]["e_line"])
        means = [statistics.fmean(v) for v in by_label.values()]
        spread = max(means) / min(means) if means and min(means) > 0 else None
        traits[scene] = (statistics.median(ratios) if ratios else None, spread)
    return traits


def failing_text(rows, traits):
    """The scenes where the model fails on some pairing, and what sets them apart, in numbers."""
    failing = sorted({r[0] for r in rows if r[8] == "fails"})
    if not failing:
        return ("<p>The model predicts or is undecided everywhere: no scene's interval lies below "
                f"ρ = {PREDICTS}.</p>")
    others = sorted({r[0] for r in rows} - set(failing))
    items = []
    for scene in failing:
        bad = [f"{r[2]} vs {r[4]} at n = {r[1]} (ρ = {r[5]:.2f})" for r in rows if r[0] == scene and r[8] == "fails"]
        items.append(f"<li><b>{html.escape(scene)}</b>: {html.escape('; '.join(bad))}</li>")

    def median_of(scenes, i):
        vals = [traits[s][i] for s in scenes if traits.get(s) and traits[s][i] is not None]
        return statistics.median(vals) if vals else None

    def each(i, digits):
        return ", ".join(f"{s} {traits[s][i]:.{digits}f}" for s in failing if traits.get(s) and traits[s][i] is not None)
    o_ratio, o_spread = median_of(others, 0), median_of(others, 1)
    common = []
    if o_ratio is not None and each(0, 2):
        shared = all(traits[s][0] is not None and traits[s][0] > MANY_PER_NODE * o_ratio for s in failing if traits.get(s))
        common.append(f"fragments per node: {each(0, 2)}, against {o_ratio:.2f} in median elsewhere"
                      + (" — every one of them stores coplanar fragments together, which the model counts once "
                         "while a ray or a traversal pays for each" if shared else ""))
    if o_spread is not None and each(1, 2):
        narrow = all(traits[s][1] is not None and traits[s][1] < o_spread for s in failing if traits.get(s))
        common.append(f"how much their heuristics' E_line differ (largest over smallest mean): {each(1, 2)}, against "
                      f"{o_spread:.2f} in median elsewhere" + (" — where the model sees the trees as nearly equal, "
                                                                "the ranking is decided by what it leaves out"
                                                                if narrow else ""))
    return (f"<p><b>The model fails</b> (interval below ρ = {PREDICTS}) on:</p><ul>{''.join(items)}</ul>"
            + (f"<p>What sets these scenes apart, measured at their largest size: {html.escape('; '.join(common))}."
               "</p>" if common else ""))


def plot_scene(scene, rows_runs, path):
    """One panel per pairing: measured against model, one point per run, coloured by size."""
    fig, axes = plt.subplots(1, len(PAIRINGS), figsize=(13, 4.4))
    sizes = sorted(rows_runs)
    cmap = plt.get_cmap("viridis")
    for ax, (model, measured, what) in zip(axes, PAIRINGS):
        for i, n in enumerate(sizes):
            pairs = pairs_of(rows_runs[n], model, measured)
            if pairs:
                ax.scatter([a for a, _ in pairs], [b for _, b in pairs], s=12, alpha=0.7,
                           color=cmap(i / max(1, len(sizes) - 1)), label=f"n = {n}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(model + " (model)")
        ax.set_ylabel(what + " (measured)")
        ax.grid(True, which="both", alpha=0.3)
    # One legend of the sizes below the panels, so it covers no point.
    handles, labels = axes[0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=len(handles), fontsize=8)
    fig.suptitle(f"{scene}: Naylor's expected costs against measured costs, every heuristic and seed", fontsize=10)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def render(report, ctx):
    rows = correlations(report)
    if not rows:
        return None
    t = table(rows, ctx.command)
    medians = []
    for model, measured, what in PAIRINGS:
        rhos = [r[5] for r in rows if r[2] == model and r[3] == measured]
        if rhos:
            medians.append(f"{model} against {what}: median ρ {statistics.median(rhos):.2f} over {len(rhos)} "
                           "scene–size groups")
    plots = ""
    by_scene = {}
    for (scene, n), runs in groups(report).items():
        by_scene.setdefault(scene, {})[n] = runs
    for scene, sizes in by_scene.items():
        if not any(r[0] == scene for r in rows):
            continue
        png = f"costmodel-{slug(scene)}.png"
        plot_scene(scene, sizes, os.path.join(ctx.out_dir, png))
        plots += f"<img src='{png}' alt='expected against measured costs for {html.escape(scene)}'>"
    body = (f"<h2 id='costmodel'>Does the cost model predict?</h2><p>{'; '.join(medians)}.</p>"
            + failing_text(rows, scene_traits(report)) + t.html(scroll=True)
            + f"<h3>Scatter plots</h3><p class=cmd>Remake: <code>{html.escape(ctx.command)}</code></p>{plots}")
    return Section([("costmodel", "does the cost model predict?")], body, [t])
