"""bspbench: which splitting planes build the best BSP tree, measured and checked (docs/python.md).

    import bspbench
    scene = bspbench.scene("city", n=1000, seed=2)
    tree = bspbench.build(scene, "naylor", params={"model": "area"})
    tree.metrics()["fragments"], tree.validate(views=4)["ok"]
    order = tree.order(eye=(0.5, 0.5, 4.0))          # NumPy array of fragment indices, back to front

A splitter in Python, for prototypes at small n (about 2.4 µs more per node than a built-in):

    def first(node):                                  # node.fragments, node.planes, node.sides(id)
        return int(node.fragments[0])                 # a fragment id, a plane (nx, ny, nz, d), or None
    tree = bspbench.build_with(scene, first)

The compiled part is _core; this file adds what is plain Python (reports are JSON).
"""
import json as _json

from ._core import (InputError, Node, PluginError, Scene, Tree, UsageError, __version__, build, build_with,
                    from_array, heuristics, load_mesh, load_plugin, merge, revision, run_suite, scene, solid_pair)

__all__ = ["InputError", "Node", "PluginError", "Scene", "Tree", "UsageError", "__version__", "build", "build_with",
           "from_array", "heuristics", "load_mesh", "load_plugin", "load_report", "merge", "revision", "run_suite",
           "runs", "scene", "solid_pair"]


def load_report(path):
    """A report written by `bspbench sweep` or `merge-reports` (analysis/SCHEMA.md), as a dict."""
    with open(path, encoding="utf-8") as f:
        report = _json.load(f)
    if not isinstance(report, dict) or "runs" not in report:
        raise InputError(f"{path}: not a bspbench report (no 'runs')")
    return report


def runs(report, kind="draw", **where):
    """The report's runs of one kind whose id matches every `where` (e.g. heuristic="naylor")."""
    return [r for r in report["runs"]
            if r["id"].get("kind", "draw") == kind and all(r["id"].get(k) == v for k, v in where.items())]
