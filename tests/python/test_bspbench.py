"""The Python module (src/python) under pytest: each test states a property that a wrong binding
breaks. Run by ctest (python_module) with PYTHONPATH=build/python, BSPBENCH_EXE and
BSPBENCH_TEST_PLUGIN_DIR set."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import bspbench

EXE = os.environ.get("BSPBENCH_EXE", "build/bspbench")


def cli_build(*args):
    out = subprocess.run([EXE, "build", *args, "--json"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def test_version_and_registry():
    assert bspbench.__version__.count(".") == 2
    names = {h["name"] for h in bspbench.heuristics()}
    assert {"first", "naylor", "weighted", "crystal"} <= names
    naylor = next(h for h in bspbench.heuristics() if h["name"] == "naylor")
    assert any(p["name"] == "model" for p in naylor["params"])


def test_build_matches_the_command_line():
    # The CLI's --seed seeds the scene, the heuristic and the metrics' rays; here each is given.
    scene = bspbench.scene("city", n=400, seed=3)
    ours = bspbench.build(scene, "weighted", params={"split_weight": 4}, seed=3).metrics(views=2, rays=200, seed=3)
    theirs = cli_build("--scene", "city", "--n", "400", "--seed", "3", "--heuristic", "weighted",
                       "--param", "split_weight=4", "--views", "2", "--rays", "200")
    for key in ("n_input", "nodes", "fragments", "max_depth", "splits", "e_point", "e_line", "ray_nodes_visited"):
        assert ours[key] == theirs[key], key
    other_seed = bspbench.build(scene, "weighted", params={"split_weight": 4}, seed=4).metrics(views=2, rays=200, seed=3)
    assert other_seed["nodes"] != ours["nodes"] or other_seed["fragments"] != ours["fragments"]


def test_array_scene_builds_the_same_tree_as_the_generated_one():
    scene = bspbench.scene("random-triangles", n=200, seed=5)
    polys = np.stack(scene.polygons)
    assert polys.shape == (200, 3, 3)
    again = bspbench.from_array(polys)
    a = bspbench.build(scene, "crystal").metrics(views=1, rays=10)
    b = bspbench.build(again, "crystal").metrics(views=1, rays=10)
    for key in ("nodes", "fragments", "max_depth", "splits"):
        assert a[key] == b[key], key


def test_order_is_a_permutation_and_validates():
    scene = bspbench.scene("architecture")
    tree = bspbench.build(scene, "naylor")
    order = tree.order(eye=(0.3, 0.4, 5.0))
    assert order.dtype == np.uint32
    assert np.array_equal(np.sort(order), np.arange(tree.fragments))
    front = tree.order(eye=(0.3, 0.4, 5.0), back_to_front=False)
    assert np.array_equal(np.sort(front), np.arange(tree.fragments)) and not np.array_equal(front, order)
    assert tree.validate(views=2)["ok"]
    assert tree.invariants()["ok"]
    sources = tree.fragment_sources()
    assert sources.max() < len(scene) and len(sources) == tree.fragments


def test_python_splitter_builds_the_builtin_first_tree():
    scene = bspbench.scene("random-triangles", n=150, seed=2)
    ours = bspbench.build_with(scene, lambda node: int(node.fragments[0]))
    builtin = bspbench.build(scene, "first")
    assert (ours.nodes, ours.fragments) == (builtin.nodes, builtin.fragments)
    eye = (0.5, 0.5, 3.0)
    assert np.array_equal(ours.order(eye), builtin.order(eye))


def test_python_splitter_sees_the_node():
    seen = []

    def fewest_splits(node):
        ids = node.fragments
        assert node.planes.shape == (len(ids), 4)
        assert node.points(int(ids[0])).shape[1] == 3
        best = min(ids[:8], key=lambda i: node.sides(int(i))["spanning"])
        seen.append(node.depth)
        return int(best)

    tree = bspbench.build_with(bspbench.scene("random-triangles", n=60, seed=1), fewest_splits)
    assert min(seen) == 1 and tree.invariants()["ok"]


def test_python_splitter_errors_are_raised():
    scene = bspbench.scene("random-triangles", n=50)

    def broken(node):
        if node.depth > 3:
            raise KeyError("planted")
        return int(node.fragments[0])

    with pytest.raises(KeyError, match="planted"):
        bspbench.build_with(scene, broken)
    with pytest.raises(ValueError, match="not in the node"):
        bspbench.build_with(scene, lambda node: 10**6)
    with pytest.raises(TypeError):
        bspbench.build_with(scene, lambda node: "plane")
    kept = []
    bspbench.build_with(scene, lambda node: kept.append(node) or int(node.fragments[0]))
    with pytest.raises(RuntimeError, match="valid only during"):
        kept[0].fragments


def test_bad_input_is_an_exception_not_a_crash():
    with pytest.raises(ValueError, match="unknown heuristic"):
        bspbench.build(bspbench.scene("architecture"), "no-such")
    with pytest.raises(bspbench.InputError):
        bspbench.from_array(np.full((2, 3, 3), np.nan))
    with pytest.raises(bspbench.InputError):
        bspbench.from_array(np.zeros((4, 3)))
    with pytest.raises(bspbench.InputError, match="no such file"):
        bspbench.load_mesh("/nonexistent/mesh.obj")


def test_merge_is_proved():
    a, b = bspbench.solid_pair("spheres", n=100, seed=1)
    out = bspbench.merge(a, b, "difference", "naylor", points=2000)
    assert out["check"]["ok"] and out["check"]["mismatches"] == 0, out["check"]
    assert out["merge"]["merge_nodes"] > 0 and out["result"]["nodes"] > 0


def test_suite_and_report(tmp_path):
    suite = tmp_path / "tiny.json"
    suite.write_text(json.dumps({"name": "py-tiny", "blocks": [
        {"scenes": ["random-triangles"], "sizes": [80], "heuristics": ["first", "naylor"],
         "validation": {"views": 1}}]}))
    report = bspbench.run_suite(str(suite), threads=1, journal_dir=str(tmp_path / "journal"), fresh=True)
    assert len(report["runs"]) == 2 and not report["failures"]
    path = tmp_path / "report.json"
    path.write_text(json.dumps(report))
    loaded = bspbench.load_report(str(path))
    assert [r["id"]["heuristic"] for r in bspbench.runs(loaded, heuristic="naylor")] == ["naylor"]
    (tmp_path / "bad.json").write_text("[1, 2]")
    with pytest.raises(bspbench.InputError):
        bspbench.load_report(str(tmp_path / "bad.json"))


def test_plugin_heuristic():
    plugin_dir = os.environ.get("BSPBENCH_TEST_PLUGIN_DIR")
    if not plugin_dir:
        pytest.skip("BSPBENCH_TEST_PLUGIN_DIR not set (ctest sets it)")
    identity = bspbench.load_plugin(os.path.join(plugin_dir, "good.so"))
    assert identity["name"] == "test_plugin"
    scene = bspbench.scene("random-triangles", n=100)
    assert bspbench.build(scene, "test_first_plugin").nodes == bspbench.build(scene, "first").nodes
    with pytest.raises(bspbench.PluginError, match="deep enough"):
        bspbench.build(scene, "test_throws", params={"depth": 3})


def test_example_reproduces_the_report_table():
    source = os.environ.get("BSPBENCH_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
    example = os.path.join(source, "examples", "python", "scoreboard_fragments.py")
    done = subprocess.run([sys.executable, example, "--size", "100", "--seeds", "2"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "| naylor |" in done.stdout and "computes the same table" in done.stdout
