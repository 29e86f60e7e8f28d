"""Two reports of the same suite side by side (bspbench report --baseline OLD.json): per run group,
what changed.

Deterministic fields come from the runs themselves, paired by command (a job key also covers the
heuristic's resolved parameters, so a changed default would unpair them): a group (scene, label,
size) is listed when any of its runs changed a metric or its heuristic's parameters, with the
metric's means over seeds before and after. Values count as equal within the regression gate's
relative tolerance (kFloatRelative, src/gate/regress.h), so a last-bit difference of a sum is no
change. Timings are the gate's own test (comparison.json, written by bspbench report from
src/gate/regress.h): each group's calibrated build samples, Mann–Whitney, and the ratio of medians.
"""
import html
import json
import statistics

import stats
from sections.common import Section
from tables import Cell, Table


def same(a, b):
    if isinstance(a, bool) or isinstance(b, bool) or not isinstance(a, (int, float)) or not isinstance(b, (int, float)):
        return a == b
    if isinstance(a, int) and isinstance(b, int):
        return a == b
    return stats.close(a, b)


def group_of(rid):
    label = rid.get("heuristic", "?") + ("" if rid.get("shape", "strict") == "strict" else f" ({rid.get('shape')})")
    label += f" {rid['kernel']}" if "kernel" in rid else ""
    where = rid.get("map") if rid.get("kind") == "doom" else rid.get("n")
    scene = rid.get("scene", "?") + (f" {rid['operation']}" if rid.get("kind") == "merge" else "")
    return (rid.get("kind", "draw"), scene, label, where)


def pairing(rid):
    """How the gate pairs runs for this comparison (command_key in src/gate/regress.cpp)."""
    return rid["command"], json.dumps(rid.get("validation_views"))


def sort_key(group):
    kind, scene, label, where = group
    return kind, scene, label, (0, where, "") if isinstance(where, (int, float)) else (1, 0, str(where))


def param_changes(b, c):
    pb, pc = b["id"].get("heuristic_params") or {}, c["id"].get("heuristic_params") or {}
    return [f"{k}: {pb.get(k)} → {pc.get(k)}" for k in sorted(set(pb) | set(pc)) if not same(pb.get(k), pc.get(k))]


def deterministic_rows(baseline, current):
    base = {pairing(r["id"]): r for r in baseline["runs"]}
    groups = {}
    for c in current["runs"]:
        b = base.get(pairing(c["id"]))
        if b is not None:
            groups.setdefault(group_of(c["id"]), []).append((b, c))
    rows = []
    for g, pairs in sorted(groups.items(), key=lambda kv: sort_key(kv[0])):
        params = sorted({p for b, c in pairs for p in param_changes(b, c)})
        keys = sorted({k for b, c in pairs for k in (c.get("metrics") or {})})
        for k in keys:
            vals = [(b["metrics"].get(k), c["metrics"].get(k)) for b, c in pairs]
            if all(same(x, y) for x, y in vals):
                continue
            nums = [(x, y) for x, y in vals if isinstance(x, (int, float)) and isinstance(y, (int, float))]
            if not nums:
                continue
            mb, mc = statistics.fmean(x for x, _ in nums), statistics.fmean(y for _, y in nums)
            change = (mc / mb - 1) * 100 if mb else None
            rows.append([g[1], g[2], g[3], "; ".join(params) or "—", k, mb, mc,
                         Cell(change, "" if change is None else f"{change:+.3g}%"),
                         sum(not same(x, y) for x, y in vals), len(vals)])
    return rows


def timing_rows(comparison):
    rows = []
    for t in comparison.get("timing_tests", []):
        rows.append([t["group"], t["field"], t["baseline_samples"], t["current_samples"],
                     Cell(t["ratio"], f"×{t['ratio']:.3g}"), Cell(t["p"], f"{t['p']:.2g}"),
                     Cell(t["verdict"], bold=t["verdict"] == "slower")])
    rows.sort(key=lambda r: -abs(r[4].value - 1))
    return rows


def render(current, ctx):
    """Placed before the contents: with --baseline, what changed is the page's first question."""
    if ctx.baseline is None:
        return None
    baseline_path, baseline, comparison_path = ctx.baseline
    command = ctx.command + f" --baseline {baseline_path}"
    with open(comparison_path, encoding="utf-8") as f:
        comparison = json.load(f)
    det = Table("changes-deterministic", "Deterministic metrics that changed, per run group",
                [("scene", ""), ("label", ""), ("n or map", ""), ("parameters changed", ""), ("metric", ""),
                 ("baseline mean", ""), ("current mean", ""), ("change", ""), ("runs changed", ""), ("runs", "")],
                deterministic_rows(baseline, current), command)
    tim = Table("changes-timings", "Build times per group: the regression gate's test",
                [("group", ""), ("timing", ""), ("baseline samples", ""), ("current samples", ""),
                 ("median ratio", "current / baseline"), ("p (Mann–Whitney)", ""), ("verdict", "")],
                timing_rows(comparison), command,
                "Samples are thread CPU times divided by their run's calibration and by the baseline job's median, "
                "so sizes and seeds pool; 'slower' fails the gate (p < 0.05 and at least ×1.5), 'faster' is the same "
                "the other way, 'within' is neither.")
    others = [c for c in comparison.get("changes", []) if c["what"] not in ("changed", "slower", "faster")]
    notes = "".join(f"<li>{html.escape(c['what'])}: {html.escape(c['run'] or c['field'])}</li>" for c in others[:50])
    verdict = "fails" if comparison.get("failed") else "passes"
    body = (f"<h2 id='changes'>Changes against {html.escape(baseline_path)}</h2>"
            f"<p>{comparison.get('runs_compared', 0)} runs and {comparison.get('values_compared', 0)} values compared, "
            f"{comparison.get('timing_groups', 0)} timing groups tested; the regression gate <b>{verdict}</b>. "
            f"{len(det.rows)} metric rows changed.</p>"
            + (f"<ul>{notes}</ul>" if notes else "")
            + "<h3>Deterministic metrics</h3>"
            + (det.html(scroll=True) if det.rows else "<p>No deterministic metric changed.</p>")
            + "<h3>Timings</h3>" + tim.html(scroll=True))
    return Section([("changes", "changes against the baseline")], body, [det, tim], lead=True)
