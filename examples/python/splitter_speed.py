"""The cost of a splitter written in Python (docs/results/python.md): the built-in `first` beside
the same rule as a Python function, and a Python rule that counts splits for 8 candidates per node,
on random triangles; medians of 5 builds (3 for the last).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/splitter_speed.py
"""
import statistics
import time

import bspbench


def median_seconds(build, repeats):
    """Median seconds of `repeats` calls of build(), and the last tree."""
    seconds = []
    for _ in range(repeats):
        start = time.perf_counter()
        tree = build()
        seconds.append(time.perf_counter() - start)
    return statistics.median(seconds), tree


def first(node):
    return int(node.fragments[0])


def fewest_splits_of_eight(node):
    return int(min(node.fragments[:8], key=lambda i: node.sides(int(i))["spanning"]))


def main():
    for n in (500, 2000, 8000):
        scene = bspbench.scene("random-triangles", n=n, seed=1)
        builtin, a = median_seconds(lambda: bspbench.build(scene, "first"), 5)
        python, b = median_seconds(lambda: bspbench.build_with(scene, first), 5)
        rule, c = median_seconds(lambda: bspbench.build_with(scene, fewest_splits_of_eight), 3)
        print(f"n={n}: {a.nodes} nodes; built-in first {builtin * 1e3:.1f} ms, Python first {python * 1e3:.1f} ms "
              f"(x{python / builtin:.1f}, same tree: {(a.nodes, a.fragments) == (b.nodes, b.fragments)}); "
              f"Python fewest splits of 8: {rule * 1e3:.0f} ms, {c.nodes} nodes")


if __name__ == "__main__":
    main()
