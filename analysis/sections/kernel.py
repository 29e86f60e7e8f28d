"""Kernel runs (float against exact on the same snapped scene): per scene, what the float kernel's tolerance
changes — fragments it drops, pairs its order check leaves as ties, classifications that differ from the exact
decision — and what exactness costs in build time, per heuristic and size (kernel-SCENE.png). Then merges run in
both kernels (merge runs whose identity names the exact kernel, beside the float runs of the same pair, size,
heuristic, operation and seed): border edges, volume against CGAL and merge time, side by side. And the
drawing runs built in the exact kernel (drawing blocks with "kernels"), which the drawing sections leave out:
their trees' size, their exact order checks and how the predicates were decided, beside the float run's
fragments where the report has it.
"""
import html
import json
import os

import matplotlib.pyplot as plt

from sections.common import DPI, Section, aggregates_of, plain, slug, summary_cell, value
from tables import Column, Table

KERNEL_COLUMNS = (("metrics", "float_fragments", "fragments, float kernel"),
                  ("metrics", "exact_fragments", "fragments, exact kernel"),
                  ("metrics", "float_dropped", "inputs and split parts the float kernel dropped as slivers"),
                  ("metrics", "float_ties", "hit pairs (per ray) the float order check left to the tolerance"),
                  ("metrics", "exact_ties", "hit pairs (per ray) meeting the ray in one point (exact)"),
                  ("metrics", "float_hit_pairs", "hit pairs on all rays, float"),
                  ("metrics", "float_pairs_checked", "distinct fragment pairs judged, float"),
                  ("metrics", "exact_pairs_checked", "distinct fragment pairs judged, exact"),
                  ("metrics", "float_violations", "pairs the float tree draws in the wrong order"),
                  ("metrics", "classify_differences", "input polygon x node plane classifications that differ"),
                  ("metrics", "classify_tests", "classifications compared"),
                  ("metrics", "predicates_filter_rate", "side tests the floating-point filter decided"),
                  ("timings", "float_build_cpu_seconds", "float build, thread CPU seconds"),
                  ("timings", "exact_build_cpu_seconds", "exact build, thread CPU seconds"))


def ratio(entry, num, den):
    a, b = value(entry, "metrics", num), value(entry, "metrics", den)
    return a / b if a is not None and b else None


def plot_kernel(scene, aggs, path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for agg in aggs:
        entries = agg["by_n"]
        xs = [e["n_polygons"]["mean"] for e in entries]
        ties = [(x, ratio(e, "float_ties", "float_hit_pairs")) for x, e in zip(xs, entries)]
        cost = []
        for x, e in zip(xs, entries):
            exact, flt = value(e, "timings", "exact_build_cpu_seconds"), value(e, "timings", "float_build_cpu_seconds")
            if exact is not None and flt:
                cost.append((x, exact / flt))
        for ax, pts in zip(axes, (ties, cost)):
            pts = [(x, y) for x, y in pts if y is not None]
            if pts:
                ax.plot(*zip(*pts), marker="o", label=agg["heuristic"])
    for ax, title in zip(axes, ("float ties per hit pair (exact: none but true ties)", "exact build / float build")):
        ax.set_xscale("log")
        ax.set_xlabel("polygons (n)")
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
            + [summary_cell(e[s].get(k)) for s, k, _ in KERNEL_COLUMNS] for g in aggs for e in g["by_n"]]
    return Table(f"kernel-{slug(scene)}", f"{scene}: float against exact kernel per heuristic and size",
                 [("heuristic", ""), ("n", ""), ("runs", ""), ("exact order violations", "")]
                 + [Column(k, title=doc) for _, k, doc in KERNEL_COLUMNS], rows)


DEFAULT_EPS = 1e-9

# What "going wrong" means on a failure curve, each with the metric that shows it.
ONSETS = (("float_violations", "pairs drawn in the wrong order"),
          ("float_dropped", "fragments dropped as slivers"),
          ("classify_differences", "classifications unlike the exact one"))


def is_default(agg):
    return agg.get("plane_eps_relative", DEFAULT_EPS) == DEFAULT_EPS and agg.get("perturbation", 0) == 0


def curve(aggs, field, metric):
    """(x, mean of metric at the smallest size) per aggregate, sorted by x."""
    pts = []
    for a in aggs:
        entry = a["by_n"][0]
        y = value(entry, "metrics", metric)
        if y is not None:
            pts.append((a.get(field, 0), y))
    return sorted(pts)


def plot_curves(scene, aggs, field, label, path):
    metrics = [m for m, _ in ONSETS] + ["float_ties"]
    fig, axes = plt.subplots(1, len(metrics), figsize=(4 * len(metrics), 3.6))
    for heuristic in sorted({a["heuristic"] for a in aggs}):
        mine = [a for a in aggs if a["heuristic"] == heuristic]
        for ax, metric in zip(axes, metrics):
            pts = [(x, y) for x, y in curve(mine, field, metric) if x > 0]
            if pts:
                ax.plot(*zip(*pts), marker="o", label=heuristic)
    for ax, metric in zip(axes, metrics):
        ax.set_xscale("log")
        ax.set_yscale("symlog", linthresh=1)
        ax.set_ylim(bottom=0)
        ax.set_xlabel(label)
        ax.set_title(f"{scene}: {metric}", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 9), fontsize=8)
    fig.tight_layout(rect=(0, 0.12, 1, 1))
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def onset_rows(scene, aggs, field):
    """Per heuristic, the smallest value of `field` at which each kind of failure first shows."""
    rows = []
    for heuristic in sorted({a["heuristic"] for a in aggs}):
        mine = [a for a in aggs if a["heuristic"] == heuristic]
        cells = []
        for metric, _ in ONSETS:
            first = next((x for x, y in curve(mine, field, metric) if y > 0), None)
            cells.append(plain(first) if first is not None else "none")
        rows.append([scene, heuristic] + cells)
    return rows


def sweep_part(scene, aggs, field, label, ctx, tables, onsets):
    # The heuristics this field was swept for (others ran at one value only).
    values = {}
    for a in aggs:
        values.setdefault(a["heuristic"], set()).add(a.get(field))
    swept = [a for a in aggs if len(values[a["heuristic"]]) > 1]
    if not swept:
        return ""
    png = f"kernel-{slug(scene)}-{field}.png"
    plot_curves(scene, swept, field, label, os.path.join(ctx.out_dir, png))
    onsets.extend(onset_rows(scene, swept, field))
    return f"<img src='{png}' alt='{html.escape(scene)} against {html.escape(label)}'>"


def onset_table(name, title, field_title, rows):
    return Table(name, title, [("scene", ""), ("heuristic", "")]
                 + [(f"first {field_title} with {what}", "") for _, what in ONSETS], rows)


def merge_key(run_id):
    return (run_id["scene"], run_id["n"], run_id["heuristic"], run_id["operation"], run_id["seed"])


def merge_pairs(report):
    """(float run, exact run) of the same merge, for every exact merge run that has its float twin."""
    floats, exacts = {}, {}
    for run in report.get("runs", []):
        rid = run.get("id", {})
        if rid.get("kind") != "merge" or "metrics" not in run:
            continue
        (exacts if rid.get("kernel") == "exact" else floats)[merge_key(rid)] = run
    return [(floats[k], exacts[k]) for k in sorted(exacts, key=str) if k in floats]


def volume_error(run):
    got, want = run["metrics"].get("result_volume"), run["validation"].get("corefine_volume")
    return abs(got - want) / abs(want) if isinstance(got, (int, float)) and isinstance(want, (int, float)) and want else None


def merge_table(pairs):
    rows = []
    for f, e in pairs:
        fid = f["id"]
        ft, et = f["timings"].get("merge_cpu_seconds"), e["timings"].get("merge_cpu_seconds")
        rows.append([fid["scene"], plain(fid["n"]), fid["heuristic"], fid["operation"], plain(fid["seed"]),
                     f["invariants"].get("border_edges"), e["invariants"].get("border_edges"),
                     volume_error(f), e["validation"].get("volume_equal"),
                     f["validation"].get("mismatches"), e["validation"].get("mismatches"),
                     f["metrics"].get("a_nodes"), e["metrics"].get("a_nodes"),
                     f["metrics"].get("after_nodes"), e["metrics"].get("after_nodes"),
                     ft, et, et / ft if ft and et else None])
    return Table("kernel-merges", "merges in both kernels: what the tolerance leaves open, and what exactness costs",
                 [("pair", ""), ("n", ""), ("heuristic", ""), ("operation", ""), ("seed", ""),
                  Column("float border edges", title="edges of the welded float boundary used once"),
                  Column("exact border edges", title="pieces of lines where the exact boundary's edges do not cancel"),
                  Column("float volume error", title="|IN cells' volume - CGAL corefinement's| / CGAL's"),
                  Column("exact volume = CGAL's", title="the boundary's volume equals CGAL's exact corefinement (Epeck) "
                                                        "of the same snapped operands, as rationals"),
                  Column("float mismatches", title="points the float tree classifies unlike CGAL"),
                  Column("exact mismatches", title="grid points the exact tree classifies unlike CGAL"),
                  Column("float operand nodes", title="nodes of the first operand's solid tree, float"),
                  Column("exact operand nodes", title="the same, exact: snapping tilts faces that were coplanar "
                                                      "(a quad's two triangles, a cap's fan) onto planes of their own"),
                  Column("float result nodes", title="the merged tree's nodes after reduction, float"),
                  Column("exact result nodes", title="the same, exact"),
                  Column("float merge s", title="merge and reduce, thread CPU seconds"),
                  Column("exact merge s", title="the same in the exact kernel"),
                  Column("exact / float", title="merge time ratio")], rows)


def subsection(anchor, title, table, text):
    """A part of the section: its heading, a paragraph and its table; with the table for the report's index."""
    return f"<h3 id='{anchor}'>{title}</h3><p>{text}</p>" + table.html(scroll=True), [table]


def merge_part(report):
    pairs = merge_pairs(report)
    if not pairs:
        return "", []
    t = merge_table(pairs)
    exact_ok = sum(1 for _, e in pairs if e["invariants"].get("border_edges") == 0 and e["validation"].get("volume_equal")
                   and e["validation"].get("mismatches") == 0)
    float_open = sum(1 for f, _ in pairs if f["invariants"].get("border_edges"))
    return subsection("kernel-merges", "Merges in both kernels", t,
                      f"{len(pairs)} merges ran in both kernels on the "
                      f"same operands. Exact: {exact_ok} of {len(pairs)} closed, with the volume equal to CGAL's exact "
                      f"corefinement of the snapped operands and every grid point agreeing. Float: {float_open} left border "
                      f"edges in the welded boundary. Where the operands' faces were coplanar (a quad's two triangles, a "
                      f"cap's fan), snapping each vertex to the grid tilts them onto planes of their own: the exact trees then "
                      f"have more nodes than the float ones, and their merges cost more for that reason (compare the node "
                      f"columns before the times).")


def drawing_key(run_id):
    return (run_id["scene"], json.dumps(run_id.get("scene_params"), sort_keys=True), run_id["n"], run_id["heuristic"],
            run_id["shape"], run_id["seed"])


def exact_drawings(report):
    """(exact drawing run, its float twin or None), for every drawing run of the exact kernel."""
    floats, exacts = {}, []
    for run in report.get("runs", []):
        rid = run.get("id", {})
        if rid.get("kind") != "draw" or "metrics" not in run:
            continue
        if rid.get("kernel") == "exact":
            exacts.append(run)
        elif "kernel" not in rid:
            floats[drawing_key(rid)] = run
    exacts.sort(key=lambda r: str(drawing_key(r["id"])))
    return [(e, floats.get(drawing_key(e["id"]))) for e in exacts]


def drawing_table(runs):
    rows = []
    for e, f in runs:
        rid, m, v = e["id"], e["metrics"], e.get("validation") or {}
        rows.append([rid["scene"], plain(rid["n"]), rid["heuristic"], rid["shape"], plain(rid["seed"]),
                     m.get("fragments"), f["metrics"].get("fragments") if f else None, m.get("max_depth"),
                     e["invariants"].get("violations"), v.get("violations"), v.get("ties"),
                     m.get("exact", {}).get("predicates", {}).get("filter_rate")])
    return Table("kernel-drawings", "drawing runs in the exact kernel",
                 [("scene", ""), ("n", ""), ("heuristic", ""), ("shape", ""), ("seed", ""),
                  Column("fragments", title="fragments of the exact tree"),
                  Column("float fragments", title="the float run's of the same scene, heuristic, shape and seed"),
                  Column("depth", title="maximum depth of the exact tree"),
                  Column("invariant violations", title="check_exact_invariants, decided exactly"),
                  Column("order violations", title="pairs drawn in the wrong order, every hit decided exactly"),
                  Column("ties", title="hit pairs meeting the ray in one point (coplanar or touching fragments)"),
                  Column("filter rate", title="side tests the floating-point filter decided")], rows)


def drawing_part(report):
    runs = exact_drawings(report)
    if not runs:
        return "", []
    t = drawing_table(runs)
    wrong = sum(1 for e, _ in runs if (e.get("validation") or {}).get("violations") or e["invariants"].get("violations"))
    return subsection("kernel-drawings", "Drawing runs in the exact kernel", t,
                      f"{len(runs)} drawing runs were built "
                      f"in the exact kernel (as <code>bspbench build --kernel exact</code>) and their orders checked exactly "
                      f"(as <code>bspbench validate --kernel exact</code>); {wrong} had an invariant or order violation. "
                      f"The drawing sections show the float runs only.")


def render(report, ctx):
    merges_html, merge_tables = merge_part(report)
    drawings_html, drawing_tables = drawing_part(report)
    scenes = {}
    for agg in aggregates_of(report, "kernel"):
        scenes.setdefault(agg["scene"], []).append(agg)
    if not scenes and not merges_html and not drawings_html:
        return None
    parts = ["<h2 id='kernel'>What the tolerance costs: float against exact geometry</h2>"
             "<p>Each scene is snapped to its integer grid and built twice with the same heuristic and seed: by the "
             "float kernel, which decides sides within plane_eps of a plane and drops slivers narrower than it, and by "
             "the exact kernel, which decides every side as the sign of a determinant [Sugihara1989] "
             "[BernsteinFussell2009] and drops nothing. Both trees' back-to-front orders are checked by Embree ray "
             "casts; the float check leaves pairs closer than its tolerance as ties, the exact check decides every "
             "pair. A column of differences is what the tolerance decided differently from the geometry. Where a "
             "suite sweeps plane_eps (of the scene's diagonal) or perturbs the input, the failure curves and the "
             "onset tables say at which value each scene starts to go wrong, and how.</p>" + ctx.how]
    tables, eps_onsets, noise_onsets = [], [], []
    for scene, aggs in sorted(scenes.items()):
        aggs = sorted(aggs, key=lambda a: a["heuristic"])
        parts.append(f"<h3 id='kernel-{slug(scene)}'>{html.escape(scene)}</h3>")
        default = [a for a in aggs if is_default(a)]
        if default:
            png = f"kernel-{slug(scene)}.png"
            plot_kernel(scene, default, os.path.join(ctx.out_dir, png))
            t = scene_table(scene, default)
            tables.append(t)
            parts.append(f"<img src='{png}' alt='float against exact for {html.escape(scene)}'>{t.html(scroll=True)}")
        parts.append(sweep_part(scene, [a for a in aggs if a.get("perturbation", 0) == 0], "plane_eps_relative",
                                "plane_eps / diagonal", ctx, tables, eps_onsets))
        parts.append(sweep_part(scene, [a for a in aggs if a.get("plane_eps_relative", DEFAULT_EPS) == DEFAULT_EPS],
                                "perturbation", "perturbation / diagonal", ctx, tables, noise_onsets))
    for name, title, field_title, rows in (("kernel-eps-onset", "where each scene starts to go wrong as plane_eps grows",
                                            "plane_eps", eps_onsets),
                                           ("kernel-noise-onset", "where each scene starts to go wrong as the input is perturbed (plane_eps 1e-9)",
                                            "perturbation", noise_onsets)):
        if rows:
            t = onset_table(name, title, field_title, rows)
            tables.append(t)
            parts.append(f"<h3 id='{name}'>{html.escape(title[0].upper() + title[1:])}</h3>{t.html(scroll=True)}")
    parts.append(merges_html)
    tables.extend(merge_tables)
    parts.append(drawings_html)
    tables.extend(drawing_tables)
    return Section([("kernel", "float against exact")], "".join(parts), tables)
