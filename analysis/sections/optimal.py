"""Optimality gaps (optimal runs): each heuristic's value divided by the optimal autopartition's
(search/optimal.h) on small scenes of every family, per objective and tree shape. The first table
answers which heuristic is closest to optimal on which kind of scene: the geometric mean gap over the
family's instances (every size and seed) with a 95% bootstrap interval over instances; the best
autopartition heuristic of each family in bold. The second answers whether the gap grows with n: the
gap at the smallest and largest size and the slope of log gap against log n through the sizes'
geometric means. One plot per objective and shape draws the gaps against n (optimal-OBJECTIVE-SHAPE.png).

A heuristic cutting by free planes (halving, octree, sah) is no autopartition and can beat the
autopartition optimum (a gap below 1): it is marked †. Where the solver's budget ran out the optimum
is an interval; the gap is then the value over its upper end (a lower bound on the true gap), and the
table says on how many instances the optimum was proved.
"""
import html
import math
import os

import matplotlib.pyplot as plt

from sections.common import DPI, MARKERS, Section, slug
from stats import bootstrap_interval
from tables import Cell, Table

FREE_MARK = "†"
# A slope of log gap against log n within this of zero is called flat: over the sizes an optimal
# suite can solve (6 to 30), it moves the gap by less than 10%.
FLAT_SLOPE = 0.05


def optimal_runs(report):
    return [r for r in report["runs"] if r["id"].get("kind") == "optimal"]


def geomean(xs):
    xs = [x for x in xs if x > 0]
    return math.exp(sum(math.log(x) for x in xs) / len(xs)) if xs else None


def label(run):
    free = not run["metrics"].get("autopartition", 1)
    return run["id"]["heuristic"] + (FREE_MARK if free else "")


def interval_cell(gaps):
    """Geometric mean gap with its 95% bootstrap interval over instances."""
    mean = geomean(gaps)
    if mean is None:
        return None
    ci = bootstrap_interval([[(0.0, g)] for g in gaps], lambda _, ys: geomean(ys)) if len(gaps) > 2 else None
    text = f"{mean:.3f}" + (f" [{ci[0]:.3f}, {ci[1]:.3f}]" if ci else "")
    return Cell(mean, text)


def slope(points):
    """Least-squares slope of log gap against log n through one point per size; None below two sizes."""
    if len(points) < 2:
        return None
    xs = [math.log(n) for n, _ in points]
    ys = [math.log(g) for _, g in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return None if sxx == 0 else sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def groups_of(runs):
    """(objective, shape) -> scene -> heuristic label -> n -> gaps over seeds."""
    out = {}
    for r in runs:
        rid = r["id"]
        key = (rid["objective"], rid["shape"])
        by_n = out.setdefault(key, {}).setdefault(rid["scene"], {}).setdefault(label(r), {})
        by_n.setdefault(rid["n_polygons"], []).append(r["metrics"]["gap"])
    return out


def proved_text(runs, objective, shape):
    mine = [r for r in runs if r["id"]["objective"] == objective and r["id"]["shape"] == shape]
    instances = {(r["id"]["scene"], r["id"]["n_polygons"], r["id"]["seed"]): r["metrics"]["optimal"] for r in mine}
    proved = sum(1 for v in instances.values() if v)
    states = max((r["metrics"]["solver_states"] for r in mine), default=0)
    return (f"The optimum was proved on {proved} of {len(instances)} instances (largest search: {states:,} "
            f"subproblems); elsewhere the gap is over the upper end of the optimum's interval.")


def closest_table(key, scenes, command):
    objective, shape = key
    heuristics = sorted({h for hs in scenes.values() for h in hs})
    rows = []
    for scene, hs in sorted(scenes.items()):
        cells = [interval_cell([g for gs in hs[h].values() for g in gs]) if h in hs else None for h in heuristics]
        auto = [c.value for h, c in zip(heuristics, cells) if c is not None and not h.endswith(FREE_MARK)]
        best = min(auto) if auto else None
        for h, c in zip(heuristics, cells):
            if c is not None and c.value == best and not h.endswith(FREE_MARK):
                c.bold = True
        rows.append([scene] + cells)
    return Table(f"optimal-closest-{slug(objective)}-{slug(shape)}",
                 f"{objective}, {shape} trees: geometric mean gap to the optimum per family (95% interval over instances)",
                 [("scene", "")] + [(h, "") for h in heuristics], rows, command,
                 note="gap = value / optimum (1 = optimal); bold: the autopartition heuristic closest to optimal; "
                      f"{FREE_MARK}: free planes, may beat the autopartition optimum")


def growth_table(key, scenes, command):
    objective, shape = key
    rows = []
    for scene, hs in sorted(scenes.items()):
        for h, by_n in sorted(hs.items()):
            points = [(n, geomean(gs)) for n, gs in sorted(by_n.items()) if geomean(gs)]
            if not points:
                continue
            s = slope(points)
            verdict = "" if s is None else ("grows" if s > FLAT_SLOPE else "shrinks" if s < -FLAT_SLOPE else "flat")
            rows.append([scene, h, points[0][0], points[0][1], points[-1][0], points[-1][1],
                         None if s is None else Cell(s, f"{s:+.3f}"), verdict])
    return Table(f"optimal-growth-{slug(objective)}-{slug(shape)}",
                 f"{objective}, {shape} trees: does the gap grow with n?",
                 [("scene", ""), ("heuristic", ""), ("smallest n", ""), ("gap there", ""), ("largest n", ""),
                  ("gap there", ""), ("slope of log gap against log n", ""), ("", "")], rows, command,
                 note=f"gaps are geometric means over seeds; 'flat' within ±{FLAT_SLOPE:g} of zero slope")


def plot_gaps(key, scenes, path):
    families = sorted(scenes)
    cols = min(4, len(families))
    rows = math.ceil(len(families) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols, 3.0 * rows), squeeze=False)
    colours = plt.get_cmap("tab20")
    names = sorted({h for hs in scenes.values() for h in hs})
    for ax, scene in zip(axes.flat, families):
        for h, by_n in sorted(scenes[scene].items()):
            i = names.index(h)
            pts = [(n, geomean(gs)) for n, gs in sorted(by_n.items()) if geomean(gs)]
            ax.plot(*zip(*pts), marker=MARKERS[i % len(MARKERS)], color=colours(i % 20), label=h,
                    linestyle="--" if h.endswith(FREE_MARK) else "-")
        ax.axhline(1.0, color="black", linewidth=0.8)
        ax.set_title(scene, fontsize=9)
        ax.set_xlabel("polygons (n)", fontsize=8)
        ax.set_ylabel("value / optimum", fontsize=8)
        ax.grid(True, alpha=0.3)
    for ax in list(axes.flat)[len(families):]:
        ax.axis("off")
    legend = {}
    for ax in axes.flat:
        for handle, text in zip(*ax.get_legend_handles_labels()):
            legend.setdefault(text, handle)
    if legend:
        fig.legend(list(legend.values()), list(legend), loc="lower center", ncol=min(len(legend), 7), fontsize=7)
    fig.suptitle(f"{key[0]}, {key[1]} trees: gap to the optimal autopartition against n", fontsize=10)
    fig.tight_layout(rect=(0, 0.08, 1, 0.96))
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def answer(scenes):
    """One sentence per family: the autopartition heuristic closest to optimal and its gap."""
    items = []
    for scene, hs in sorted(scenes.items()):
        gaps = {h: geomean([g for gs in by_n.values() for g in gs]) for h, by_n in hs.items()
                if not h.endswith(FREE_MARK)}
        gaps = {h: g for h, g in gaps.items() if g}
        if gaps:
            best = min(gaps, key=gaps.get)
            items.append(f"<li>{html.escape(scene)}: <b>{html.escape(best)}</b> ({gaps[best]:.3f}× the optimum)</li>")
    return f"<ul>{''.join(items)}</ul>"


def render(report, ctx):
    runs = optimal_runs(report)
    if not runs:
        return None
    parts, tables = ["<h2 id='optimal'>How far from optimal?</h2>", ctx.how,
                     "<p>Each heuristic's tree beside the optimal autopartition of the same scene, solved by branch "
                     "and bound and checked like any tree (invariants, Embree's order check, its value measured "
                     "again by the metrics). Every run repeats with the <code>bspbench optimal</code> command in its "
                     "record.</p>"], []
    for key, scenes in sorted(groups_of(runs).items()):
        objective, shape = key
        png = f"optimal-{slug(objective)}-{slug(shape)}.png"
        plot_gaps(key, scenes, os.path.join(ctx.out_dir, png))
        closest, growth = closest_table(key, scenes, ctx.command), growth_table(key, scenes, ctx.command)
        tables += [closest, growth]
        parts.append(f"<h3 id='optimal-{slug(objective)}-{slug(shape)}'>{html.escape(objective)}, "
                     f"{html.escape(shape)} trees</h3><p>{proved_text(runs, objective, shape)}</p>"
                     f"<p>Closest to optimal, per family:</p>{answer(scenes)}{closest.html(scroll=True)}"
                     f"<img src='{png}' alt='gaps against n, {html.escape(objective)}'>{growth.html(scroll=True)}")
    return Section([("optimal", "How far from optimal?")], "".join(parts), tables)
