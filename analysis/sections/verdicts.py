"""Who wins where: per scene and size, the best heuristic on each metric, its margin over the
runner-up, and whether the margin is real.

The test: seed s of every heuristic builds the same scene instance, so the two heuristics' values
are paired by seed and compared with Student's paired t-test [Student1908], two-sided. The p-values of every
comparison in the report form one family, adjusted by Holm's step-down method [Holm1979], so "significant"
(adjusted p < ALPHA) holds for all verdicts of the page at once, not one by one. A metric on which
best and runner-up have equal means (within stats.FLOAT_RELATIVE) is a tie and names both; one seed gives
no test. Best and runner-up are chosen by the same means the test then compares, the usual reading
of a benchmark table; the margin it reports is the observed one.

Pareto: the labels no other label beats on all of (fragments, max_depth, e_line) at once, each
lower-is-better, on the means over seeds.

Notation: label = heuristic (with its shape when not strict); group = one scene at one size.
"""
import html
import statistics

import stats
from sections.common import METRIC_DOCS, Section, is_float, slug
from tables import Cell, Table

ALPHA = 0.05
# (section, key, what the reader calls it); lower is better for each.
VERDICT_METRICS = (
    ("metrics", "fragments", "fragments"),
    ("metrics", "max_depth", "depth"),
    ("metrics", "e_point", "E_point"),
    ("metrics", "e_line", "E_line"),
    ("metrics", "culled_nodes_visited", "culled traversal"),
    ("metrics", "ray_nodes_visited", "ray cost"),
    ("timings", "build_cpu_seconds", "build time"),
    ("timings", "merge_cpu_seconds", "merge cost"),
)
PARETO_AXES = ("fragments", "max_depth", "e_line")


def run_label(rid):
    return rid["heuristic"] + ("" if rid["shape"] == "strict" else f" ({rid['shape']})")


def scene_params(rid):
    """The scene's parameters but its size and seed, as text: what makes two scenes of one generator differ."""
    params = {k: v for k, v in (rid.get("scene_params") or {}).items() if k not in ("n", "seed")}
    return ",".join(f"{k}={v}" for k, v in sorted(params.items()))


def scene_namer(report):
    """A function from a drawing or merge run's id to its scene's name: the generator, with its
    parameters when the report has that generator with several parameter sets (a user's suite may)."""
    sets = {}
    for r in report["runs"]:
        rid = r["id"]
        sets.setdefault(rid["scene"], set()).add(scene_params(rid))

    def name(rid):
        base = rid["scene"] + (f" [{scene_params(rid)}]" if len(sets.get(rid["scene"], ())) > 1 else "")
        return f"{base} {rid['operation']}" if rid.get("kind") == "merge" else base
    return name


def groups(report):
    """(scene name, n) -> label -> seed -> run, for the float kernel's drawing and merge runs."""
    name = scene_namer(report)
    out = {}
    for r in report["runs"]:
        rid = r["id"]
        if rid.get("kind", "draw") not in ("draw", "merge") or not is_float(rid):
            continue
        out.setdefault((name(rid), rid["n"]), {}).setdefault(run_label(rid), {})[rid["seed"]] = r
    return dict(sorted(out.items(), key=lambda kv: (kv[0][0], kv[0][1])))


def value(run, section, key):
    v = (run.get(section) or {}).get(key)
    return v if isinstance(v, (int, float)) and not isinstance(v, bool) else None


def per_seed(by_seed, section, key):
    return {s: v for s, r in by_seed.items() if (v := value(r, section, key)) is not None}


def compare(labels, section, key):
    """The verdict of one metric in one group, before the family's correction."""
    values = {lab: per_seed(by_seed, section, key) for lab, by_seed in labels.items()}
    values = {lab: v for lab, v in values.items() if v}
    if len(values) < 2:
        return None
    means = sorted((statistics.fmean(v.values()), lab) for lab, v in values.items())
    (best_mean, best), (second_mean, second) = means[0], means[1]
    tied = [lab for m, lab in means if stats.close(m, best_mean)]
    seeds = sorted(set(values[best]) & set(values[second]))
    diffs = [values[second][s] - values[best][s] for s in seeds]
    _, p = stats.paired_t(diffs) if len(diffs) >= 2 else (None, None)
    return {"best": " = ".join(sorted(tied)) if len(tied) > 1 else best, "best_mean": best_mean,
            "second": second if len(tied) == 1 else "", "second_mean": second_mean, "pairs": len(seeds),
            "p": p if len(tied) == 1 else 1.0, "tie": len(tied) > 1}


def all_verdicts(report):
    """(scene, n) -> [(metric name, verdict)], with Holm-adjusted p-values over the whole family."""
    found = []
    for (scene, n), labels in groups(report).items():
        for section, key, name in VERDICT_METRICS:
            v = compare(labels, section, key)
            if v is not None:
                found.append(((scene, n), name, key, v))
    adjusted = stats.holm([v["p"] for _, _, _, v in found])
    out = {}
    for (group, name, key, v), p in zip(found, adjusted):
        v["p_holm"] = p
        v["significant"] = p is not None and p < ALPHA and not v["tie"]
        out.setdefault(group, []).append((name, key, v))
    return out


def pareto_front(labels):
    rows = []
    for lab, by_seed in labels.items():
        means = []
        for key in PARETO_AXES:
            v = per_seed(by_seed, "metrics", key)
            means.append(statistics.fmean(v.values()) if v else None)
        if None not in means:
            rows.append((lab, means))

    return sorted(non_dominated(rows))


def non_dominated(rows):
    """Names of the (name, values) rows no other row beats: at most equal on every axis and lower on one."""
    def beats(a, b):
        return all(x <= y for x, y in zip(a, b)) and any(x < y for x, y in zip(a, b))
    return {name for name, v in rows if not any(beats(w, v) for other, w in rows if other != name)}


def size_text(n):
    """A mesh scene has no size parameter (n = 0): it is the file as read."""
    return f"n = {n}" if n else "the file"


def margin_text(v):
    if v["tie"]:
        return "tie"
    if v["best_mean"] == 0:
        return f"+{v['second_mean']:.3g}"
    return f"+{100 * (v['second_mean'] / v['best_mean'] - 1):.3g}%"


def p_text(v):
    if v["p_holm"] is None:
        return "one seed: no test"
    return f"{v['p_holm']:.2g}"


def scene_table(scene, verdicts, units, command, family):
    """Rows (n, metric) for one scene."""
    rows = []
    for (s, n), items in verdicts.items():
        if s != scene:
            continue
        for name, key, v in items:
            rows.append([n if n else "the file", f"{name} ({units.get(key, '')})" if units.get(key) else name,
                         Cell(v["best"], bold=v["significant"]), v["best_mean"], v["second"] or "—",
                         v["second_mean"] if v["second"] else None, Cell(margin_text(v)), Cell(p_text(v)),
                         v["significant"]])
    return Table(f"verdicts-{scene}", f"Verdicts for {scene}: the best label per metric and size",
                 [("n", ""), ("metric", ""), ("best", ""), ("its mean", ""), ("runner-up", ""), ("its mean", ""),
                  ("runner-up's excess", ""), ("p (paired t, Holm)", ""), ("significant", "")],
                 rows, command,
                 "Lower is better on every metric. Bold: the best is significantly better than the runner-up "
                 f"(paired t-test over seeds, Holm-adjusted over all {family} comparisons of this report, α = {ALPHA}).")


def pareto_sentences(scene, report_groups):
    parts = []
    for (s, n), labels in report_groups.items():
        if s == scene:
            front = pareto_front(labels)
            if front:
                parts.append(f"{size_text(n)}: {', '.join(front)}")
    if not parts:
        return ""
    return ("Not beaten on all of fragments, depth and E_line at once (the Pareto set, means over seeds) — "
            + "; ".join(parts) + ".")


def render(report, ctx):
    found = all_verdicts(report)
    if not found:
        return None
    family = sum(len(items) for items in found.values())
    units = {k: d["unit"] for k, d in METRIC_DOCS["metrics"].items()}
    units["merge_cpu_seconds"] = "s"
    report_groups = groups(report)
    significant = sum(v["significant"] for items in found.values() for _, _, v in items)
    parts = [f"<h2 id='verdicts'>Who wins where</h2><p>{family} comparisons (best against runner-up, per scene, "
             f"size and metric), {significant} significant after Holm's correction. Merge runs appear as their solid "
             "pair and operation.</p>"]
    tables = []
    for scene in sorted({s for s, _ in found}):
        t = scene_table(scene, found, units, ctx.command, family)
        tables.append(t)
        parts.append(f"<h3 id='verdicts-{slug(scene)}'>{html.escape(scene)}</h3>"
                     f"<p>{html.escape(pareto_sentences(scene, report_groups))}</p>{t.html(scroll=True)}")
    return Section([("verdicts", "who wins where (verdicts)")], "".join(parts), tables)
