"""Reproduces one table of the HTML report, "scoreboard: fragments, ratio to the best (1 = best)",
twice: from trees built here through the Python module, and from a sweep's report by the report's
own code (analysis/sections/scoreboard.py). The two must agree to the last digit: the module builds
the same trees as the sweep. Copy it as the start of your own analysis.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/scoreboard_fragments.py

Options: --size N (polygons per scene, default 300), --seeds K (default 3). Exit 1 if they differ.
"""
import argparse
import json
import os
import statistics
import sys
import tempfile

import bspbench

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "analysis"))
from sections import scoreboard  # noqa: E402  (the report's code, for the check)

SCENES = ["random-triangles", "city", "sphere-field"]
HEURISTICS = ["first", "balanced", "crystal", "naylor", "zennode"]


def by_python(size, seeds):
    """scene -> heuristic -> (mean fragments over seeds, ratio to the scene's best)."""
    table = {}
    for name in SCENES:
        means = {}
        for h in HEURISTICS:
            # A sweep's seed s makes the scene with seed s and seeds the heuristic with s.
            counts = [bspbench.build(bspbench.scene(name, n=size, seed=s), h, seed=s).fragments for s in seeds]
            means[h] = statistics.fmean(counts)
        best = min(means.values())
        table[name] = {h: (m, m / best) for h, m in means.items()}
    return table


def by_report(size, seeds, workdir):
    """The same table from a sweep's report, computed by the report's scoreboard section."""
    suite = os.path.join(workdir, "scoreboard.json")
    with open(suite, "w", encoding="utf-8") as f:
        json.dump({"name": "python-scoreboard", "blocks": [
            {"scenes": SCENES, "heuristics": HEURISTICS, "sizes": [size], "seeds": list(seeds),
             "validation": {"views": 1}}]}, f)
    report = bspbench.run_suite(suite, threads=0, journal_dir=os.path.join(workdir, "journal"), fresh=True)
    return scoreboard.ratios(report, "metrics", "fragments")


def markdown(table):
    scenes = sorted(table)
    lines = ["| heuristic | " + " | ".join(scenes) + " |", "|---" * (len(scenes) + 1) + "|"]
    for h in HEURISTICS:
        lines.append(f"| {h} | " + " | ".join(f"{table[s][h][1]:.3g}" for s in scenes) + " |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=300)
    parser.add_argument("--seeds", type=int, default=3)
    args = parser.parse_args()
    seeds = range(1, args.seeds + 1)
    ours = by_python(args.size, seeds)
    with tempfile.TemporaryDirectory() as workdir:
        theirs = by_report(args.size, seeds, workdir)
    print(f"fragments, ratio to the best (1 = best); n = {args.size}, seeds 1..{args.seeds}, bspbench {bspbench.__version__}\n")
    print(markdown(ours))
    differ = [(s, h) for s in SCENES for h in HEURISTICS if abs(ours[s][h][0] - theirs[s][h][0]) > 0]
    if differ:
        print(f"\nthe report's table differs at {differ}", file=sys.stderr)
        return 1
    print("\nthe report's scoreboard section computes the same table from the sweep")
    return 0


if __name__ == "__main__":
    sys.exit(main())
