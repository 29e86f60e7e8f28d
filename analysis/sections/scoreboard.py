"""The scoreboard: which heuristic for my scene, in one picture. For each key metric (fragments, max
depth, E_line, the measured ray cost, build time, merge cost) a heat map of heuristics × scenes
coloured by each heuristic's ratio to the best heuristic on that scene (1 = best, the colour's log
scale saturating at SATURATION), and, where the report has optimal runs, heat maps of the ratio to
the optimal autopartition (the optimality gap) per objective. Each scene is read at its largest
size every heuristic of it reached (means over seeds); the gap maps, whose scenes are small by
necessity, at every size (geometric means over instances). Strict float-kernel trees only, so one
label is one heuristic. The numbers behind the colours are the tables below the picture (and in
--format exports); every other section of the page breaks them down by size, seed and shape.
"""
import html
import math
import os
import statistics

import matplotlib.pyplot as plt
from matplotlib.colors import LogNorm

from sections import verdicts
from sections.common import DPI, Section, is_float, slug
from tables import Cell, Table

# (section, key, what the reader calls it), lower is better for each; verdicts' metrics minus the
# ones a reader finds in the sections that follow (E_point, culled traversal).
SCORE_METRICS = (
    ("metrics", "fragments", "fragments"),
    ("metrics", "max_depth", "max depth"),
    ("metrics", "e_line", "E_line"),
    ("metrics", "ray_nodes_visited", "measured ray cost"),
    ("timings", "build_cpu_seconds", "build time"),
    ("timings", "merge_cpu_seconds", "merge cost"),
)
# Ratios at or above this are drawn in the darkest colour: past 4× the best, a heuristic is out of
# the running, and a wider scale would wash out the differences near 1 that matter.
SATURATION = 4.0


def largest_common(by_n):
    """The largest size at which every label of the scene has a value; None when there is none."""
    labels = set().union(*(set(v) for v in by_n.values()))
    for n in sorted(by_n, reverse=True):
        if set(by_n[n]) == labels:
            return n
    return max(by_n) if by_n else None


def ratios(report, section, key):
    """scene -> label -> (mean at the scene's largest common size, ratio to the scene's best)."""
    name = verdicts.scene_namer(report)
    means = {}
    for r in report["runs"]:
        rid = r["id"]
        if rid.get("kind", "draw") not in ("draw", "merge") or not is_float(rid) or rid["shape"] != "strict":
            continue
        v = verdicts.value(r, section, key)
        if v is None:
            continue
        means.setdefault(name(rid), {}).setdefault(rid["n"], {}).setdefault(rid["heuristic"], []).append(v)
    out = {}
    for scene, by_n in means.items():
        n = largest_common(by_n)
        values = {lab: statistics.fmean(vs) for lab, vs in by_n[n].items()}
        best = min(values.values())
        if best > 0:
            out[scene] = {lab: (v, v / best) for lab, v in values.items()}
    return out


def gaps(report):
    """objective -> scene -> label -> geometric mean gap to the optimum over every instance (strict trees)."""
    name = verdicts.scene_namer(report)
    out = {}
    for r in report["runs"]:
        rid = r["id"]
        if rid.get("kind") != "optimal" or rid["shape"] != "strict" or not r["metrics"].get("gap"):
            continue
        out.setdefault(rid["objective"], {}).setdefault(name(rid), {}).setdefault(rid["heuristic"], []).append(
            math.log(r["metrics"]["gap"]))
    return {o: {s: {lab: (math.exp(statistics.fmean(v)),) * 2 for lab, v in labs.items()} for s, labs in scenes.items()}
            for o, scenes in out.items()}


def panels(report):
    """(title, scene -> label -> (value, ratio)) for every metric the report has."""
    found = [(title, ratios(report, section, key)) for section, key, title in SCORE_METRICS]
    found += [(f"gap to the optimum: {objective}", scenes) for objective, scenes in sorted(gaps(report).items())]
    return [(title, grid) for title, grid in found if grid]


def draw(found, path):
    cols = min(3, len(found))
    rows = math.ceil(len(found) / cols)
    labels = sorted({lab for _, grid in found for labs in grid.values() for lab in labs})
    fig, axes = plt.subplots(rows, cols, figsize=(6.2 * cols, 0.22 * len(labels) * rows + 2.4 * rows), squeeze=False)
    # Room between the maps for the next map's heuristic names.
    fig.subplots_adjust(wspace=0.75, hspace=0.6)
    norm = LogNorm(vmin=1.0, vmax=SATURATION)
    image = None
    for ax, (title, grid) in zip(axes.flat, found):
        scenes = sorted(grid)
        data = [[min(grid[s][lab][1], SATURATION) if lab in grid[s] else float("nan") for s in scenes] for lab in labels]
        image = ax.imshow(data, cmap="RdYlGn_r", norm=norm, aspect="auto")
        ax.set_xticks(range(len(scenes)))
        ax.set_xticklabels(scenes, rotation=60, ha="right", fontsize=6)
        ax.set_yticks(range(len(labels)))
        ax.set_yticklabels(labels, fontsize=6)
        ax.set_title(title, fontsize=9)
        for i, row in enumerate(data):
            for j, x in enumerate(row):
                if not math.isnan(x):
                    ax.text(j, i, f"{x:.2g}", ha="center", va="center", fontsize=4.5)
    for ax in list(axes.flat)[len(found):]:
        ax.axis("off")
    fig.colorbar(image, ax=axes.ravel().tolist(), shrink=0.6, label=f"ratio to the best (saturates at {SATURATION:g})")
    fig.savefig(path, dpi=DPI, bbox_inches="tight")
    plt.close(fig)


def table(title, grid, command):
    scenes = sorted(grid)
    labels = sorted({lab for labs in grid.values() for lab in labs})
    rows = [[lab] + [Cell(grid[s][lab][1], f"{grid[s][lab][1]:.3g}", bold=grid[s][lab][1] == 1.0) if lab in grid[s]
                     else None for s in scenes] for lab in labels]
    return Table(f"scoreboard-{slug(title)}", f"scoreboard: {title}, ratio to the best (1 = best)",
                 [("heuristic", "")] + [(s, "") for s in scenes], rows, command)


def render(report, ctx):
    found = panels(report)
    if not found:
        return None
    png = "scoreboard.png"
    draw(found, os.path.join(ctx.out_dir, png))
    tables = [table(title, grid, ctx.command) for title, grid in found]
    body = ("<h2 id='scoreboard'>Scoreboard: which heuristic for my scene?</h2>"
            "<p>Each map: heuristics × scenes, coloured by the ratio to the best heuristic on that scene (green = best, "
            f"red = {SATURATION:g}× or worse), at each scene's largest size every heuristic reached, strict trees, "
            "means over seeds. The gap maps divide by the optimal autopartition instead (below 1: a free-plane "
            "heuristic beat it). The numbers are in the tables under the picture.</p>"
            f"<img src='{png}' alt='scoreboard heat maps'>"
            "<details><summary>the numbers</summary>" + "".join(t.html(scroll=True) for t in tables) + "</details>")
    return Section([("scoreboard", "scoreboard: which heuristic for my scene?")], body, tables, lead=True)
