"""CSG runs (programs evaluated by merging solid trees, beside the peer engines on the same program): per
program, every engine's time mesh in to mesh out and per step, its result's size, its volume against
CGAL's exact one, and its status (a peer's timeout or error is shown, never hidden); then who wins where:
per program the fastest engine and bspbench's best time as a multiple of each peer's (csg-times.png);
and what the float kernel loses against the exact one on the same programs.
"""
import html
import os

import matplotlib.pyplot as plt

from sections.common import DPI, Section
from tables import Cell, Table

PEERS = ("cgal", "openscad", "manifold")


def csg_runs(report):
    return [r for r in report["runs"] if r["id"].get("kind") == "csg"]


def engine_label(run):
    i = run["id"]
    return f"{i['heuristic']} ({i['kernel']})" if i["engine"] == "bspbench" else i["engine"]


def seconds_of(run):
    t = run["timings"]
    return t.get("seconds") if run["id"]["engine"] == "bspbench" else t.get("peer_seconds")


def status_of(run):
    if run["id"]["engine"] != "bspbench":
        return run["validation"].get("status", "ok")
    return "ok" if run["validation"]["violations"] == 0 and run["invariants"]["violations"] == 0 else "VIOLATION"


def by_program(runs):
    """Program label -> seed -> its runs, programs in the order first seen."""
    out = {}
    for r in runs:
        out.setdefault(r["id"]["program"], {}).setdefault(r["id"]["seed"], []).append(r)
    return out


def reference_volume(runs):
    """CGAL's exact volume of the program: a bspbench run's proof, or the cgal peer's."""
    for r in runs:
        if r["id"]["engine"] == "bspbench" and r["validation"].get("volume_ok"):
            return r["validation"]["reference_volume"]
    for r in runs:
        if r["id"]["engine"] == "cgal" and r["validation"].get("status") == "ok":
            return r["metrics"]["volume"]
    return None


def steps_of(runs):
    """Binary operations of the program, as bspbench's evaluation counts them."""
    for r in runs:
        if r["id"]["engine"] == "bspbench":
            return r["metrics"]["merges"]
    return None


def program_rows(program, runs):
    ref, steps = reference_volume(runs), steps_of(runs)
    ok_times = [seconds_of(r) for r in runs if status_of(r) == "ok" and seconds_of(r)]
    fastest = min(ok_times) if ok_times else None
    rows = []
    for r in sorted(runs, key=lambda r: (r["id"]["engine"] != "bspbench", engine_label(r))):
        s, status = seconds_of(r), status_of(r)
        ours = r["id"]["engine"] == "bspbench"
        size = r["metrics"].get("result_faces") if ours else r["metrics"].get("result_triangles")
        volume = r["metrics"].get("volume")
        rel = abs(volume - ref) / abs(ref) if ref and volume is not None and status == "ok" else None
        bound = r["metrics"].get("volume_rounding_bound") or None
        note = r["validation"].get("note", "") if not ours else ""
        rows.append([Cell(program, code=True), engine_label(r), Cell(status, title=note, bold=status != "ok"),
                     s, s / steps if s and steps else None, s / fastest if s and fastest and status == "ok" else None,
                     size, rel, bound / abs(ref) if bound and ref else None])
    return rows


def winners(programs):
    """Per program: the fastest engine that finished, and bspbench's best time over each peer's."""
    rows = []
    for program, seeds in programs.items():
        runs = next(iter(seeds.values()))
        done = [r for r in runs if status_of(r) == "ok" and seconds_of(r)]
        ours = [r for r in done if r["id"]["engine"] == "bspbench"]
        if not done:
            continue
        best = min(done, key=seconds_of)
        row = [Cell(program, code=True), engine_label(best), seconds_of(best)]
        mine = min(seconds_of(r) for r in ours) if ours else None
        for peer in PEERS:
            theirs = [r for r in runs if r["id"]["engine"] == peer]
            if not theirs:
                row.append(None)
            elif status_of(theirs[0]) != "ok":
                row.append(Cell(None, status_of(theirs[0]), italic=True))
            else:
                row.append(mine / seconds_of(theirs[0]) if mine else None)
        rows.append(row)
    return rows


def float_losses(programs):
    """Float against exact on the same program, heuristic and seed: volume error and points counted apart."""
    rows = []
    for program, seeds in programs.items():
        for seed, runs in seeds.items():
            exact = {r["id"]["heuristic"]: r for r in runs if r["id"]["engine"] == "bspbench" and r["id"]["kernel"] == "exact"}
            for r in runs:
                i = r["id"]
                if i["engine"] != "bspbench" or i["kernel"] != "float" or i["heuristic"] not in exact:
                    continue
                e = exact[i["heuristic"]]
                v = r["validation"]
                rows.append([Cell(program, code=True), i["heuristic"], v.get("volume_relative_error"),
                             v.get("within_plane_eps", 0), v.get("within_plane_eps_disagree", 0), r["metrics"].get("dropped_input"),
                             r["metrics"].get("result_faces"), e["metrics"].get("result_faces"),
                             seconds_of(r), seconds_of(e)])
    return rows


def plot_times(programs, path):
    names = list(programs)
    engines = sorted({engine_label(r) for seeds in programs.values() for runs in seeds.values() for r in runs},
                     key=lambda e: (e in PEERS, e))
    fig, ax = plt.subplots(figsize=(max(8, 0.5 * len(names) * max(1, len(engines)) / 2), 4.6))
    width = 0.8 / max(1, len(engines))
    for k, engine in enumerate(engines):
        xs, ys = [], []
        for x, program in enumerate(names):
            runs = next(iter(programs[program].values()))
            t = [seconds_of(r) for r in runs if engine_label(r) == engine and status_of(r) == "ok" and seconds_of(r)]
            if t:
                xs.append(x + (k - len(engines) / 2) * width)
                ys.append(t[0])
        ax.bar(xs, ys, width=width, label=engine)
    ax.set_yscale("log")
    ax.set_xticks(range(len(names)))
    ax.set_xticklabels(names, rotation=60, ha="right", fontsize=7)
    ax.set_ylabel("seconds, mesh in to mesh out")
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=min(4, len(engines)))
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def render(report, ctx):
    runs = csg_runs(report)
    if not runs:
        return None
    programs = by_program(runs)
    first_seed = {p: {min(s): s[min(s)]} for p, s in programs.items()}
    rows = [row for p, seeds in first_seed.items() for row in program_rows(p, next(iter(seeds.values())))]
    times = Table("csg-programs", "every engine on every program (first seed)",
                  [("program", ""), ("engine", "heuristic (kernel) for bspbench"), ("status", "ok, timeout, error, missing"),
                   ("time", "s, mesh in to mesh out"), ("per step", "s per binary operation"), ("x fastest", ""),
                   ("result size", "faces (bspbench) or triangles (peers)"), ("volume error", "relative, against CGAL's exact volume"),
                   ("rounding bound", "relative: OpenSCAD's 6 digits")], rows, command=ctx.command)
    wins = Table("csg-winners", "who wins where: the fastest engine per program, and bspbench's best time over each peer's",
                 [("program", ""), ("fastest", ""), ("its time", "s"), ("bspbench / cgal", ""), ("bspbench / openscad", ""),
                  ("bspbench / manifold", "")], winners(first_seed), command=ctx.command,
                 note="Below 1: bspbench is faster. A peer that did not finish shows its status.")
    tables = [times, wins]
    losses = float_losses(programs)
    if losses:
        tables.append(Table("csg-float", "what the float kernel loses: float runs against exact runs of the same program",
                            [("program", ""), ("heuristic", ""), ("volume error", "relative, float"),
                             ("near points", "within plane_eps of a leaf"), ("of them wrong", ""), ("dropped faces", ""),
                             ("faces, float", ""), ("faces, exact", ""), ("time, float", "s"), ("time, exact", "s")],
                            losses, command=ctx.command))
    plot = "csg-times.png"
    plot_times(first_seed, os.path.join(ctx.out_dir, plot))
    failures = sum(1 for r in runs if status_of(r) not in ("ok", "missing"))
    violations = sum(1 for r in runs if status_of(r) == "VIOLATION")
    body = ("<h2 id='csg'>CSG programs: bspbench beside CGAL, OpenSCAD and Manifold</h2>"
            "<p>Each program is evaluated mesh in to mesh out by bspbench (every leaf a solid tree, merged step by "
            "step [Naylor1990], the boundary welded at the end) and by the peers on the same polyhedra: CGAL's "
            "corefinement applied step by step, OpenSCAD's render of the same file, Manifold under node. bspbench's "
            f"results are proved against CGAL (points, exact volume, closed boundary): {violations} runs with a "
            f"violation. Peers that timed out or failed: {failures - violations}, shown with their status. "
            "docs/csg.md says how each engine is timed.</p>"
            + ctx.how + f"<img src='{html.escape(plot)}' alt='seconds per program and engine'>"
            + "".join(t.html(scroll=True) for t in tables))
    return Section([("csg", "CSG programs")], body, tables)
