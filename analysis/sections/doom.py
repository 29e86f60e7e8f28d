"""Doom runs: our heuristics beside the external node builders and the shipped nodes. Totals per
builder over all maps, the presets' targets judged, splits against depth and against CPU time
(doom.png), splits and depth per map, and the structural check's findings per builder.
"""
import html
import math
import os
import statistics

import matplotlib.pyplot as plt

from sections.common import DPI, Section
from sections.verdicts import non_dominated
from tables import Cell, Column, Table

# The doom-splits preset's target: ZokumBSP 1.1.1 with -na=s (fewest splits), built from source and
# run on this machine on the 68 Freedoom maps (both IWADs), made 23,491 splits in total.
ZOKUM = {"splits": 23491, "iwads": {"freedoom1.wad", "freedoom2.wad"}, "maps": 68}
# The doom-search preset may spend this many times ZDBSP's CPU time on the same maps.
SEARCH_CPU_FACTOR = 10
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


def num_cell(x, digits=4):
    return Cell(x, num(x, digits))


def builder_cell(total):
    """Ours in bold, the others in italics and said what they are."""
    ours = total["kind"] == "heuristic"
    return Cell(total["name"], total["name"] + KIND_MARK[total["kind"]], bold=ours, italic=not ours)


def maps_cell(total):
    """The maps built, and of how many when some failed."""
    built, maps = total["built"], total["maps"]
    return Cell(built, str(built) if built == maps else f"{built} of {maps}")


def totals_table(totals):
    rows = [[builder_cell(t), maps_cell(t)]
            + [num_cell(t[k]) for k in ("cpu", "splits", "segs", "subsectors", "nodes", "max_depth", "mean_depth")]
            + [t["failed"]] for t in totals]
    return Table("doom-totals", "Doom maps: totals per builder over the maps it built",
                 [Column("builder", left=True), Column("maps"),
                  Column("CPU s", title="sum over maps of the median CPU seconds of the timed builds"),
                  Column("splits"), Column("segs"), Column("subsectors"), Column("nodes"),
                  Column("mean max depth", title="mean over maps of the maximum depth"),
                  Column("mean subsector depth", title="mean over maps of the mean subsector depth"),
                  Column("maps failing the structural check (or not built)")], rows)


def margin(measured, reference, unit=""):
    """How far under (or over) the reference, absolute and relative."""
    diff = reference - measured
    amount = f"{abs(diff):,}" if isinstance(diff, int) else f"{abs(diff):.3g}"
    side = "under" if diff > 0 else "over" if diff < 0 else "exactly at"
    relative = f" ({abs(diff) / reference:.1%})" if reference else ""
    return f"{amount}{unit} {side}{relative}" if diff else side


def target_rows(totals):
    """The presets' targets, each condition measured: (builder, condition, measured, reference, met, by)."""
    zdbsp = next((t for t in totals if t["name"] == "zdbsp"), None)
    shipped = next((t for t in totals if t["name"] == "shipped"), None)
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
        if preset == "doom-search":
            comparable = on_zokum_maps(t)
            rows.append((t["name"], f"fewer splits than ZokumBSP 1.1.1 -na=s's {ZOKUM['splits']:,} (the "
                         f"{ZOKUM['maps']} Freedoom maps, measured on this machine)", t["splits"], ZOKUM["splits"],
                         t["splits"] < ZOKUM["splits"] if comparable else None,
                         margin(t["splits"], ZOKUM["splits"]) if comparable
                         else f"not comparable: {t['built']} maps built, not the {ZOKUM['maps']}"))
            if shipped:
                rows.append(against(t, shipped, "shipped nodes", "fewer splits than the shipped nodes", "splits",
                                    lambda a, b: a < b))
            if zdbsp and t["cpu"] is not None and zdbsp["cpu"] is not None:
                rows.append(against_zdbsp(t, {**zdbsp, "cpu": SEARCH_CPU_FACTOR * zdbsp["cpu"]},
                                          f"CPU time at most {SEARCH_CPU_FACTOR}× ZDBSP's in the same run", "cpu",
                                          lambda a, b: a <= b, " s"))
        if preset == "doom-depth" and zdbsp:
            rows.append(against_zdbsp(t, zdbsp, "mean max depth at most ZDBSP's", "max_depth", lambda a, b: a <= b))
            rows.append(against_zdbsp(t, zdbsp, "fewer splits than ZDBSP", "splits", lambda a, b: a < b))
    return rows


def against(total, other, other_name, condition, field, holds, unit=""):
    """A target row against another builder's total, judged only when both built the same maps."""
    mine, ref = total[field], other[field]
    if total["mapset"] != other["mapset"]:
        return total["name"], condition, mine, ref, None, f"not comparable: not the maps the {other_name} cover"
    return total["name"], condition, mine, ref, holds(mine, ref), margin(mine, ref, unit)


def against_zdbsp(total, zdbsp, condition, field, holds, unit=""):
    """A target row against ZDBSP's total, judged only when both built the same maps."""
    return against(total, zdbsp, "ZDBSP run", condition, field, holds, unit)


def targets_table(rows):
    cells = [[p, cond, num_cell(m, 5), num_cell(ref, 5),
              Cell(ok, "—" if ok is None else "met" if ok else "missed", bold=ok is False), by]
             for p, cond, m, ref, ok, by in rows]
    return Table("doom-targets", "Doom maps: the presets' targets",
                 [Column("preset"), Column("condition", left=True), Column("measured"), Column("reference"),
                  Column("verdict"), Column("by")], cells)


def targets_html(totals):
    rows = target_rows(totals)
    if not rows:
        return "<p>Targets not judged: no preset (doom-splits, doom-depth, doom-search) ran, or ZDBSP did not.</p>", []
    verdicts = []
    for preset in dict.fromkeys(r[0] for r in rows):
        met = [r[4] for r in rows if r[0] == preset]
        word = "missed" if False in met else "not judged" if None in met else "met"
        verdicts.append(f"<b>{html.escape(preset)}: target {word}</b>")
    t = targets_table(rows)
    return "<p>" + "; ".join(verdicts) + ".</p>" + t.html(), [t]


def plot_doom(totals, path):
    """Splits against mean max depth and against CPU seconds, a point per builder, the front ringed."""
    rows = math.ceil(len(totals) / 5)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5 + 0.25 * rows))
    colours = plt.get_cmap("tab20").colors  # up to 20 builders: distinct colours
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


def map_cells(record):
    """A builder's two cells of one map: splits (✗ when it fails the check) and max depth; hovering
    either names the command that repeats the run."""
    if record is None:
        return [None, None]
    title = record["id"].get("command", "")
    if "error" in record:
        return [Cell("error", title=title, span=2)]
    m = record["metrics"]
    mark = " ✗" if doom_failed(record) else ""
    return [Cell(m["splits"], f"{m['splits']:,}{mark}", title=title), m["max_depth"]]


def per_map_table(builders, totals):
    names = [t["name"] for t in totals]
    maps = sorted({(r["id"]["iwad"], r["id"]["map"]) for recs in builders.values() for r in recs})
    by_map = {(name, r["id"]["iwad"], r["id"]["map"]): r for name, recs in builders.items() for r in recs}
    rows = [[iwad, m] + [c for n in names for c in map_cells(by_map.get((n, iwad, m)))] for iwad, m in maps]
    t = Table("doom-per-map", "Doom maps: splits and max depth per map and builder",
              [("IWAD", ""), ("map", "")] + [(head, "") for _ in names for head in ("splits", "max depth")], rows,
              groups=[(None, 2)] + [(n, 2) for n in names])
    return ("<details><summary>Per map: splits and max depth per builder (hover a splits cell for the command "
            f"that repeats the run; ✗ fails the structural check)</summary>{t.html(scroll=True)}</details>"), t


def check_row(total, recs):
    built = [r for r in recs if "error" not in r]
    bad = sorted((r for r in built if r["invariants"]["violations"]), key=lambda r: (r["id"]["iwad"], r["id"]["map"]))
    order = [r["validation"] for r in built if r.get("validation")]
    first = next((f"{r['id']['map']}: {r['invariants']['first_problems'][0]}" for r in bad
                  if r["invariants"].get("first_problems")), "")
    errors = "; ".join(f"{r['id']['map']}: {r['error']}" for r in recs if "error" in r)
    worst = {k: max((r["invariants"].get(k, 0) for r in built), default=None)
             for k in ("worst_side_distance", "worst_convexity_distance")}
    return [builder_cell(total), len(bad), sum(r["invariants"]["violations"] for r in built),
            num_cell(worst["worst_side_distance"]), num_cell(worst["worst_convexity_distance"]),
            num_cell(sum(v["violations"] for v in order) if order else None),
            num_cell(sum(v.get("rays", 0) for v in order) if order else None), first, errors]


def check_table(builders, totals):
    return Table("doom-check", "Doom maps: the structural check per builder",
                 [Column("builder", left=True), Column("maps with violations"), Column("violations"),
                  Column("worst side distance", title="largest distance (map units, over maps) of a seg endpoint on "
                         "the wrong side of an ancestor's partition, within the tolerance or not"),
                  Column("worst convexity distance", title="largest distance (map units, over maps) of a seg "
                         "endpoint behind the line of another seg of its subsector, within the tolerance or not"),
                  Column("order-check violations"), Column("order-check rays"), Column("first problem", left=True),
                  Column("errors", left=True)],
                 [check_row(t, builders[t["name"]]) for t in totals])


def render(report, ctx):
    records = doom_records(report)
    if not records:
        return None
    builders = per_builder(records)
    totals = doom_totals(builders)
    plot_doom(totals, os.path.join(ctx.out_dir, "doom.png"))
    maps = {(r["id"]["iwad"], r["id"]["map"]) for r in records}
    # Sums over different maps are not comparable; say so rather than rank them silently.
    uneven = ("<p><b>Not every builder built every map (the maps column): compare totals only between builders "
              "with the same maps.</b></p>" if len({t["built"] for t in totals}) > 1 else "")
    totals_t, check_t = totals_table(totals), check_table(builders, totals)
    targets, target_tables = targets_html(totals)
    per_map, per_map_t = per_map_table(builders, totals)
    body = ("<h2 id='doom'>Doom maps: our heuristics beside the node builders</h2>"
            "<p>Each run builds one map's nodes: our heuristics as leafy trees with one sector per leaf, written "
            "as vanilla NODES/SEGS/SSECTORS, or an external node builder (ZDBSP, glBSP) run on the map alone, "
            "or the nodes the WAD shipped with. Every builder's nodes are read back by the same parser and "
            "proved by the same structural check; ours are also proved in back-to-front order against Embree "
            "from the map's first things. CPU time is thread CPU for ours (build and lumps, one thread) and the "
            "child's user + system time for the external builders, the median of the timed builds per map; "
            "the shipped nodes have none. Bold: ours; italic: external builders and the shipped nodes.</p>"
            + ctx.how
            + f"<h3>Totals over {len(maps)} maps of {html.escape(', '.join(sorted({i for i, _ in maps})))}</h3>"
            f"{uneven}{totals_t.html()}<h3>Targets</h3>{targets}"
            "<img src='doom.png' alt='splits against depth and CPU time, a point per builder'>"
            f"{per_map}<h3>Structural check</h3>{check_t.html()}"
            "<p>Violations in the nodes of ZDBSP, glBSP or the shipped nodes are facts about those nodes "
            "as the check reads them (a seg endpoint on the wrong side of a partition, or behind another "
            "seg of its subsector, farther than the tolerance kDoomSideTolerance of "
            "src/validate/doom_check.h; a subsector of two sectors), not failures of this benchmark; our "
            "builders must have none.</p>")
    return Section([("doom", "Doom maps")], body, [totals_t] + target_tables + [per_map_t, check_t])
