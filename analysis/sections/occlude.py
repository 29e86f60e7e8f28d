"""Occlude runs (occlusion culling by beam tracing): per scene, what culling emits against what Embree
sees and against frustum culling alone, and its cost, per heuristic and size (occlusion-SCENE.png).
"""
import html
import os

import matplotlib.pyplot as plt

from sections.common import DPI, Section, aggregates_of, plain, slug, summary_cell, value
from tables import Column, Table

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


def plot_occlusion(scene, aggs, path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for agg in aggs:
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
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def scene_table(scene, aggs):
    rows = [[g["heuristic"], plain(e["n"]), e["runs"], e["validation_violations"]]
            + [summary_cell(e[s].get(k)) for s, k, _ in OCCLUSION_COLUMNS] for g in aggs for e in g["by_n"]]
    return Table(f"occlusion-{slug(scene)}", f"{scene}: occlusion culling per heuristic and size",
                 [("heuristic", ""), ("n", ""), ("runs", ""), ("proof violations", "")]
                 + [Column(k, title=doc) for _, k, doc in OCCLUSION_COLUMNS], rows)


def render(report, ctx):
    scenes = {}
    for agg in aggregates_of(report, "occlude"):
        scenes.setdefault(agg["scene"], []).append(agg)
    if not scenes:
        return None
    parts = ["<h2 id='occlusion'>Occlusion culling by beam tracing</h2>"
             "<p>The scene tree is walked front to back in the view frustum while a beam tree of the directions "
             "already covered grows by merging each drawn fragment's cone; hidden fragments and subtrees are "
             "skipped [Naylor1992]. Every view is proved conservative by Embree primary rays (proof violations "
             "count rays whose first hit was culled). Emitted / seen says how tight the output is (seen: the "
             "fragments rays meet first, a lower bound of the visible set); emitted / frustum-culled what occlusion "
             "adds to frustum culling.</p>" + ctx.how]
    tables = []
    for scene, aggs in sorted(scenes.items()):
        aggs = sorted(aggs, key=lambda a: a["heuristic"])
        png = f"occlusion-{slug(scene)}.png"
        plot_occlusion(scene, aggs, os.path.join(ctx.out_dir, png))
        t = scene_table(scene, aggs)
        tables.append(t)
        parts.append(f"<h3 id='occlusion-{slug(scene)}'>{html.escape(scene)}</h3>"
                     f"<img src='{png}' alt='occlusion tightness for {html.escape(scene)}'>{t.html(scroll=True)}")
    return Section([("occlusion", "occlusion culling")], "".join(parts), tables)
