"""The report's statistics and research sections on data whose answer is known (analysis/stats.py,
analysis/sections/*.py).

Run: /usr/bin/python3 -m unittest discover -s tests/report -p 'test_*.py' (ctest: report_analysis).
Each test also shows its check can fail: the same code on data with the opposite answer.
"""
import os
import random
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "analysis"))

import stats  # noqa: E402
import tables  # noqa: E402
from sections import cost_model, csg, draw, kernel, optimal, scoreboard, theory, verdicts  # noqa: E402


def draw_run(scene, heuristic, n, seed, metrics, shape="strict", timings=None):
    return {"id": {"kind": "draw", "scene": scene, "heuristic": heuristic, "shape": shape, "n": n,
                   "n_polygons": n, "seed": seed},
            "metrics": metrics, "timings": timings or {}}


class Statistics(unittest.TestCase):
    def test_student_p_matches_tables(self):
        self.assertAlmostEqual(stats.student_p(2.7764451, 4), 0.05, places=5)
        self.assertAlmostEqual(stats.student_p(1.0, 1), 0.5, places=9)

    def test_paired_t_of_a_textbook_sample(self):
        # differences 1..5: mean 3, sd sqrt(2.5), t = 3 / (sqrt(2.5)/sqrt(5)) = 4.2426, df 4: p = 0.01324
        mean, p = stats.paired_t([1, 2, 3, 4, 5])
        self.assertEqual(mean, 3)
        self.assertAlmostEqual(p, 0.013236, places=5)
        self.assertEqual(stats.paired_t([2, 2, 2])[1], 0.0)
        self.assertEqual(stats.paired_t([0, 0, 0])[1], 1.0)
        self.assertIsNone(stats.paired_t([1])[1])

    def test_holm_steps_down_and_stays_monotone(self):
        # sorted 0.01, 0.03, 0.04 of 3: 0.03, max(0.06, ...) = 0.06, max(0.06, 0.04) = 0.06
        self.assertEqual(stats.holm([0.01, 0.04, 0.03, None]), [0.03, 0.06, 0.06, None])
        self.assertEqual(stats.holm([0.5, 0.9]), [1.0, 1.0])

    def test_spearman_with_ties_and_without_spread(self):
        self.assertAlmostEqual(stats.spearman([1, 2, 3, 4], [10, 20, 30, 40]), 1.0)
        self.assertAlmostEqual(stats.spearman([1, 2, 3, 4], [4, 3, 2, 1]), -1.0)
        self.assertAlmostEqual(stats.spearman([1, 2, 2, 3], [1, 2, 3, 4]), 0.9486833, places=6)
        self.assertIsNone(stats.spearman([1, 1, 1], [1, 2, 3]))

    def test_bootstrap_resamples_whole_clusters_at_known_percentiles(self):
        # Three clusters of one pair each, x = 1, 2, 3: a resample's mean x is (a + b + c) / 3 over the 27
        # equally likely draws, whose sums 3..9 have cumulative counts 1, 4, 10, 17, 23, 26, 27. The 25th
        # and 75th percentiles are therefore 5/3 and 7/3 (a min-max interval would be 1 and 3).
        def mean_x(xs, ys):
            return sum(xs) / len(xs)
        clusters = [[(1, 0)], [(2, 0)], [(3, 0)]]
        lo, hi = stats.bootstrap_interval(clusters, mean_x, reps=20000, level=0.5)
        self.assertAlmostEqual(lo, 5 / 3)
        self.assertAlmostEqual(hi, 7 / 3)
        self.assertEqual((lo, hi), stats.bootstrap_interval(clusters, mean_x, reps=20000, level=0.5))
        # Clusters of two identical pairs: the same percentiles, a resample still draws three clusters.
        doubled = [[(x, 0), (x, 0)] for x in (1, 2, 3)]
        self.assertAlmostEqual(stats.bootstrap_interval(doubled, mean_x, reps=20000, level=0.5)[0], 5 / 3)


class Verdicts(unittest.TestCase):
    def report(self, gap):
        """Heuristic 'a' beats 'b' on fragments by `gap` per seed (with seed noise shared by both)."""
        rng = random.Random(1)
        runs = []
        for seed in range(1, 6):
            base = 100 + 10 * rng.random()
            runs.append(draw_run("s", "a", 100, seed, {"fragments": base}))
            runs.append(draw_run("s", "b", 100, seed, {"fragments": base + gap[seed - 1]}))
            runs.append(draw_run("s", "c", 100, seed, {"fragments": base + 50}))
        return {"runs": runs}

    def test_a_consistent_gap_is_significant_and_noise_is_not(self):
        found = verdicts.all_verdicts(self.report([3, 4, 2, 3, 5]))[("s", 100)]
        name, key, v = found[0]
        self.assertEqual((v["best"], v["second"]), ("a", "b"))
        self.assertTrue(v["significant"])
        noise = verdicts.all_verdicts(self.report([3, -4, 2, -3, 1]))[("s", 100)][0][2]
        self.assertFalse(noise["significant"])

    def test_equal_means_are_a_tie_naming_both(self):
        v = verdicts.all_verdicts(self.report([0, 0, 0, 0, 0]))[("s", 100)][0][2]
        self.assertTrue(v["tie"])
        self.assertEqual(v["best"], "a = b")
        self.assertFalse(v["significant"])

    def test_one_generator_with_two_parameter_sets_is_two_scenes(self):
        def runs(height, fragments):
            out = [draw_run("city", h, 100, 1, {"fragments": f}) for h, f in zip("ab", fragments)]
            for r in out:
                r["id"]["scene_params"] = {"n": 100, "seed": 1, "max_height": height}
            return out
        low, tall = runs(6, (1, 2)), runs(12, (9, 2))
        self.assertEqual(sorted(verdicts.groups({"runs": low + tall})),
                         [("city [max_height=12]", 100), ("city [max_height=6]", 100)])
        self.assertEqual(sorted(verdicts.groups({"runs": low})), [("city", 100)])

    def test_pareto_front_keeps_only_the_unbeaten(self):
        labels = {"a": {1: draw_run("s", "a", 1, 1, {"fragments": 1, "max_depth": 5, "e_line": 3})},
                  "b": {1: draw_run("s", "b", 1, 1, {"fragments": 2, "max_depth": 4, "e_line": 3})},
                  "c": {1: draw_run("s", "c", 1, 1, {"fragments": 2, "max_depth": 5, "e_line": 3})}}
        self.assertEqual(verdicts.pareto_front(labels), ["a", "b"])


class CostModel(unittest.TestCase):
    def report(self, scramble):
        rng = random.Random(3)
        runs = []
        for h in range(8):
            for seed in range(1, 6):
                e = 10 + h + rng.random()
                measured = rng.random() * 20 if scramble else 2 * e
                runs.append(draw_run("s", f"h{h}", 100, seed, {"e_line": e, "e_point": e, "ray_nodes_visited": measured,
                                                               "point_plane_tests": measured, "culled_nodes_visited": measured,
                                                               "fragments": 10, "nodes": 10}))
        return {"runs": runs}

    def test_a_monotone_measurement_is_predicted_and_a_random_one_fails(self):
        good = cost_model.correlations(self.report(False))
        self.assertTrue(all(r[8] == "predicts" for r in good))
        bad = cost_model.correlations(self.report(True))
        self.assertTrue(all(r[8] == "fails" for r in bad), [r[5:] for r in bad])
        self.assertIn("The model fails", cost_model.failing_text(bad, cost_model.scene_traits(self.report(True))))
        self.assertNotIn("The model fails", cost_model.failing_text(good, {}))


def draw_aggregate(scene, heuristic, sizes, fragments=None, splits_fit=None):
    """A drawing aggregate as report.json has it: sizes with their fragments' STAT, and the splits
    fit over sizes (C++ computes it: tests/test_sweep.cpp)."""
    by_n = [{"n": n, "n_polygons": {"mean": float(n)},
             "metrics": {} if fragments is None else {"fragments": fragments(n)}} for n in sizes]
    return {"kind": "draw", "scene": scene, "heuristic": heuristic, "shape": "strict", "scene_params": {},
            "by_n": by_n, "growth_over_sizes": {"growth": {"splits": splits_fit}, "timing_growth": {}}}


class Theory(unittest.TestCase):
    def report(self, exponent):
        fit = {"exponent": exponent, "ci95": [exponent - 0.05, exponent + 0.05], "r2": 0.99, "sizes": 4}
        return {"runs": [], "aggregates": [draw_aggregate("saddle-grid", "crystal", (30, 60, 120, 180),
                                                          splits_fit=fit)]}

    def test_quadratic_splits_agree_and_a_slower_growth_is_listed(self):
        rows, contradictions, disagreements = theory.analyse(self.report(2.0))
        self.assertEqual(disagreements, [])
        self.assertEqual(tables.text_of(rows[0][5]), "yes")
        self.assertEqual(tables.text_of(rows[0][3]), "2.00 [1.95, 2.05]")
        _, _, disagreements = theory.analyse(self.report(1.5))
        self.assertEqual(len(disagreements), 1)
        self.assertIn("saddle-grid, crystal", disagreements[0])
        self.assertIn("n = 30 to 180", disagreements[0])

    def test_the_2d_bound_is_contradicted_only_when_exceeded(self):
        def segments(factor):
            def fragments(n):
                mean = factor * theory.autopartition_bound(n)
                return {"mean": mean, "ci95": [0.99 * mean, 1.01 * mean]}
            return {"runs": [], "aggregates": [draw_aggregate("random-segments", "random", (100, 1000), fragments)]}
        self.assertEqual(theory.analyse(segments(0.5))[1], [])
        self.assertEqual(len(theory.analyse(segments(1.5))[1]), 2)

    def test_an_exponent_a_hair_off_agrees_within_the_margin_and_raises_no_alarm(self):
        report = self.report(2.0)
        report["aggregates"][0]["growth_over_sizes"]["growth"]["splits"]["ci95"] = [2.005, 2.03]
        rows, contradictions, disagreements = theory.analyse(report)
        self.assertEqual(tables.text_of(rows[0][5]), "within margin")
        self.assertEqual(disagreements, [])
        self.assertNotIn("class=alert", theory.top_list(contradictions, disagreements))
        report["aggregates"][0]["growth_over_sizes"]["growth"]["splits"]["ci95"] = [2.04, 2.07]
        rows, contradictions, disagreements = theory.analyse(report)
        self.assertEqual(tables.text_of(rows[0][5]), "no")
        self.assertEqual(len(disagreements), 1)
        self.assertIn("class=notice", theory.top_list(contradictions, disagreements))
        self.assertNotIn("class=alert", theory.top_list(contradictions, disagreements))
        self.assertIn("class=alert", theory.top_list(["a bound exceeded"], disagreements))

    def test_a_report_without_fits_over_sizes_says_its_exponents_are_not_judged(self):
        report = self.report(2.0)
        self.assertTrue(theory.fitted(report))
        del report["aggregates"][0]["growth_over_sizes"]
        self.assertFalse(theory.fitted(report))
        self.assertIn("not judged", theory.top_list([], [], theory.fitted(report)))


class ExactDrawings(unittest.TestCase):
    """Drawing runs of the exact kernel stay out of the float sections and go to the kernel section."""
    def report(self):
        runs = []
        for seed in (1, 2):
            for h, fragments, exact_fragments in (("a", 10, 30), ("b", 20, 5)):
                runs.append(draw_run("s", h, 100, seed, {"fragments": fragments}))
                e = draw_run("s", h, 100, seed, {"fragments": exact_fragments, "max_depth": 4,
                                                 "exact": {"predicates": {"filter_rate": 0.9}}})
                e["id"]["kernel"] = "exact"
                e["invariants"], e["validation"] = {"violations": 0}, {"violations": 0, "ties": 3}
                runs.append(e)
        exact_agg = dict(draw_aggregate("s", "a", (100,)), kernel="exact")
        return {"runs": runs, "aggregates": [draw_aggregate("s", "a", (100,)), exact_agg]}

    def test_float_verdicts_and_tables_leave_exact_runs_out(self):
        report = self.report()
        verdict = verdicts.all_verdicts(report)[("s", 100)][0][2]
        self.assertEqual(verdict["best"], "a")  # the exact runs, mixed in, would make it b
        self.assertEqual(len(cost_model.groups(report)[("s", 100)]), 4)
        self.assertEqual([len(aggs) for aggs in draw.by_scene(report).values()], [1])
        self.assertEqual(len(theory.series(report)), 1)
        for r in report["runs"]:
            r["id"].pop("kernel", None)
        self.assertEqual(verdicts.all_verdicts(report)[("s", 100)][0][2]["best"], "b")

    def test_the_kernel_section_lists_each_exact_run_beside_its_float_twin(self):
        pairs = kernel.exact_drawings(self.report())
        self.assertEqual(len(pairs), 4)
        self.assertTrue(all(e["id"]["kernel"] == "exact" and "kernel" not in f["id"] for e, f in pairs))
        self.assertEqual(sorted((e["metrics"]["fragments"], f["metrics"]["fragments"]) for e, f in pairs),
                         [(5, 20), (5, 20), (30, 10), (30, 10)])
        row = kernel.drawing_table(pairs).rows[0]
        self.assertEqual(row[-1], 0.9)
        self.assertEqual(kernel.drawing_part({"runs": []}), ("", []))


def csg_run(program, engine, seconds, volume, status="ok", kernel="exact", violations=0):
    ours = engine == "bspbench"
    run = {"id": {"kind": "csg", "program": program, "engine": engine, "seed": 1,
                  "heuristic": "octree" if ours else "peer:" + engine, "kernel": kernel if ours else "none"},
           "metrics": {"volume": volume, "merges": 4, "result_faces" if ours else "result_triangles": 100},
           "invariants": {"violations": 0},
           "timings": {"seconds": seconds} if ours else {"peer_seconds": seconds}}
    run["validation"] = ({"violations": violations, "volume_ok": violations == 0, "reference_volume": 10.0}
                         if ours else {"status": status, "note": "killed after 60 s" if status == "timeout" else ""})
    return run


class Csg(unittest.TestCase):
    """Every engine of a program is a row; a peer that did not finish shows its status, never a time ratio."""
    def report(self):
        return {"runs": [csg_run("p", "bspbench", 0.5, 10.0), csg_run("p", "cgal", 2.0, 10.0),
                         csg_run("p", "manifold", 0.25, 10.0 + 1e-8), csg_run("p", "openscad", 60.0, 0.0, "timeout")],
                "aggregates": []}

    def test_who_wins_and_the_ratios_to_each_peer(self):
        programs = csg.by_program(csg.csg_runs(self.report()))
        [row] = csg.winners({p: {1: s[1]} for p, s in programs.items()})
        self.assertEqual(row[1], "manifold")
        self.assertEqual(row[3], 0.25)  # bspbench / cgal
        self.assertEqual(row[4].text, "timeout")  # openscad: its status, not a ratio
        self.assertEqual(row[5], 2.0)  # bspbench / manifold

    def test_rows_compare_volumes_with_cgal_and_flag_our_violations(self):
        report = self.report()
        rows = csg.program_rows("p", csg.csg_runs(report))
        by_engine = {r[1]: r for r in rows}
        self.assertAlmostEqual(by_engine["manifold"][7], 1e-9)
        self.assertIsNone(by_engine["openscad"][7])  # no volume from a peer that timed out
        self.assertEqual(by_engine["octree (exact)"][4], 0.5 / 4)  # per binary operation
        report["runs"][0]["validation"]["violations"] = 1
        rows = csg.program_rows("p", csg.csg_runs(report))
        self.assertEqual({r[1]: r[2].value for r in rows}["octree (exact)"], "VIOLATION")


def optimal_run(scene, heuristic, n, seed, gap, autopartition=1, optimal_proved=1):
    return {"id": {"kind": "optimal", "scene": scene, "heuristic": heuristic, "shape": "strict", "n": n,
                   "n_polygons": n, "seed": seed, "objective": "fragments"},
            "metrics": {"gap": gap, "autopartition": autopartition, "optimal": optimal_proved, "solver_states": 10},
            "timings": {}}


class Scoreboard(unittest.TestCase):
    def test_each_scene_is_read_at_its_largest_common_size_as_a_ratio_to_its_best(self):
        runs = [draw_run("city", "a", n, s, {"fragments": f}) for n, f in ((100, 10), (300, 30)) for s in (1, 2)]
        runs += [draw_run("city", "b", n, s, {"fragments": f}) for n, f in ((100, 20), (300, 45)) for s in (1, 2)]
        runs += [draw_run("city", "c", 100, s, {"fragments": 5}) for s in (1, 2)]  # only at 100
        grid = scoreboard.ratios({"runs": runs}, "metrics", "fragments")
        self.assertEqual(grid["city"]["a"], (10, 2.0))  # n = 100: the largest size all three reached
        self.assertEqual(grid["city"]["c"], (5, 1.0))
        runs = [r for r in runs if r["id"]["heuristic"] != "c"]
        grid = scoreboard.ratios({"runs": runs}, "metrics", "fragments")
        self.assertEqual(grid["city"]["b"], (45, 1.5))  # n = 300 once c is gone
        self.assertEqual(grid["city"]["a"], (30, 1.0))

    def test_the_gap_maps_hold_geometric_means_of_the_gaps(self):
        runs = [optimal_run("sphere", "first", 6, 1, 1.0), optimal_run("sphere", "first", 6, 2, 4.0)]
        self.assertAlmostEqual(scoreboard.gaps({"runs": runs})["fragments"]["sphere"]["first"][1], 2.0)


class Optimal(unittest.TestCase):
    def runs(self, growing):
        out = []
        for n in (6, 10, 16):
            for seed in (1, 2, 3):
                out.append(optimal_run("random-triangles", "first", n, seed, 1.0 + (n / 6 if growing else 0.3)))
                out.append(optimal_run("random-triangles", "crystal", n, seed, 1.1))
                out.append(optimal_run("random-triangles", "halving", n, seed, 0.9, autopartition=0))
        return out

    def test_the_closest_autopartition_heuristic_is_named_and_free_planes_are_marked(self):
        scenes = optimal.groups_of(self.runs(True))[("fragments", "strict")]
        self.assertIn("halving" + optimal.FREE_MARK, scenes["random-triangles"])
        self.assertIn("<b>crystal</b>", optimal.answer(scenes))  # halving's 0.9 is not an autopartition
        t = optimal.closest_table(("fragments", "strict"), scenes, "cmd")
        bold = [c for c in t.rows[0][1:] if isinstance(c, tables.Cell) and c.bold]
        self.assertEqual([round(c.value, 6) for c in bold], [1.1])

    def test_a_growing_gap_grows_and_a_constant_one_is_flat(self):
        def verdicts_of(growing):
            t = optimal.growth_table(("fragments", "strict"), optimal.groups_of(self.runs(growing))[("fragments", "strict")], "")
            return {row[1]: row[7] for row in t.rows}
        self.assertEqual(verdicts_of(True)["first"], "grows")
        self.assertEqual(verdicts_of(False)["first"], "flat")
        self.assertEqual(verdicts_of(True)["crystal"], "flat")


class Exports(unittest.TestCase):
    def test_every_format_carries_every_cell(self):
        t = tables.Table("t", "A & B", [("name", ""), ("value", "s")],
                         [["x_1", 0.123456789], [tables.Cell("y", bold=True), None]], "cmd")
        self.assertIn("0.123456789", t.csv())
        self.assertIn("| **y** |", t.markdown())
        self.assertIn(r"x\_1", t.latex())
        self.assertIn(r"\textbf{y}", t.latex())
        self.assertIn(r"A \& B", t.latex())
        self.assertIn("<b>y</b>", t.html())

    def test_groups_spans_and_titles_keep_the_flat_formats_aligned(self):
        t = tables.Table("g", "G", [("map", ""), tables.Column("splits", title="it's hover text"), ("depth", "")],
                         [["E1M1", tables.Cell("error", title="cmd", span=2)], ["E1M2", 5, 3]],
                         groups=[(None, 1), ("zdbsp", 2)])
        page = t.html()
        self.assertIn("<th rowspan=2>map</th><th colspan=2>zdbsp</th></tr><tr><th title='it&#x27;s hover text'>", page)
        self.assertIn("<td colspan=2 title='cmd'>error</td>", page)
        self.assertEqual(t.csv().splitlines(), ["map,zdbsp: splits,zdbsp: depth", "E1M1,error,", "E1M2,5,3"])
        self.assertIn("| E1M1 | error |  |", t.markdown())
        named = tables.Table("s", "S", [tables.Column("what", left=True), ("value", "")], [["runs", 3]], row_heads=True)
        self.assertEqual(named.html(), "<table id='table-s'><tr><th style='text-align:left'>runs</th><td>3</td></tr>"
                                       "</table>")
        self.assertIn("what,value", named.csv())


if __name__ == "__main__":
    unittest.main()
