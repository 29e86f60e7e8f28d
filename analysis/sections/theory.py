"""Does the theory hold? Growth exponents of fragments and build time against n, with intervals,
beside the exponents the literature proves for the scenes built to show them.

The bounds:
  * saddle-grid: Theta(n^2): every BSP of it has Omega(n^2) fragments, and a random autopartition
    of any n triangles O(n^2) in expectation [PatersonYao1990];
  * orthogonal-stacks: Theta(n^{3/2}): every BSP of it has Omega(n^{3/2}) fragments and n
    orthogonal rectangles always have a BSP of O(n^{3/2}) [PatersonYao1992]; the construction's
    autopartition through its 3k layer planes makes k^3 = (n/3)^{3/2};
  * random-disjoint with `random`: O(n log n) expected. For disjoint segments in the plane this is
    Paterson and Yao's theorem; for disjoint triangles in space their proven bound is O(n^2), and
    n log n is the hypothesis this report tests on a scene of small, evenly spread triangles;
  * random-segments with `random`: at most n + 2n ln n fragments in expectation [PatersonYao1990;
    deBerg2008], an explicit bound each size is checked against.
The exponents are fitted to splits = fragments - n + dropped, the part of the count the bounds are
about (fragments add the linear n, which bends a short log-log range). An O(n log n) bound is met
by exponents up to 1 + 1/ln(n), its local slope at the geometric mean of the sizes fitted.

A contradiction is a measurement the bound rules out: an explicit bound exceeded by the lower end
of a size's 95% interval over seeds. An exponent whose interval excludes the theoretical one is a
disagreement, not a contradiction: asymptotic bounds say nothing about a finite range of n, and
constants and lower-order terms bend short fits; both are listed at the top of the report.
"""
import html
import math
import statistics

import stats
from sections import verdicts
from sections.common import Section
from tables import Cell, Table

# scene -> (heuristics it applies to (empty: all), kind, exponent or None, statement)
BOUNDS = {
    "saddle-grid": ((), "theta", 2.0, "Θ(n²) [PatersonYao1990]"),
    "orthogonal-stacks": ((), "theta", 1.5, "Θ(n^{3/2}) [PatersonYao1992]"),
    "random-disjoint": (("random",), "nlogn", None, "O(n log n) expected (hypothesis in 3D; theorem in 2D)"),
    "random-segments": (("random",), "nlogn", None, "n + 2n ln n expected [PatersonYao1990; deBerg2008]"),
}


def autopartition_bound(n):
    return n + 2 * n * math.log(n)


def series(report):
    """(scene, heuristic, shape) -> [(n_polygons, splits, fragments, build CPU s, seed, n)] of drawing
    runs; a generator with several parameter sets in the report gives one scene per set."""
    name = verdicts.scene_namer(report)
    out = {}
    for r in report["runs"]:
        rid = r["id"]
        if rid.get("kind", "draw") != "draw":
            continue
        m, t = r["metrics"], r.get("timings") or {}
        out.setdefault((name(rid), rid["heuristic"], rid["shape"]), []).append(
            (rid["n_polygons"], m.get("splits"), m.get("fragments"), t.get("build_cpu_seconds"), rid["seed"], rid["n"]))
    return dict(sorted(out.items()))


def fit(points, i):
    """The log-log fit of field i over the sizes' geometric means: seeds are replicates of one size,
    not independent points of the curve (pooling them would shrink the interval with every seed)."""
    by_n = {}
    for p in points:
        if p[i] is not None and p[i] > 0 and p[0] > 0:
            by_n.setdefault(p[0], []).append(math.log(p[i]))
    ns = sorted(by_n)
    return stats.loglog_fit(ns, [math.exp(statistics.fmean(by_n[n])) for n in ns])


def nlogn_slope(points):
    ns = [p[0] for p in points if p[0] > 1]
    return 1 + 1 / statistics.fmean(math.log(n) for n in ns)


def judge(scene, points, f):
    """(theoretical exponent text, agrees?) for a splits fit of a bounded scene."""
    _, kind, exponent, _ = BOUNDS[scene]
    if f is None:
        return "", None
    lo, hi = f[1]
    if kind == "theta":
        return f"{exponent:g}", lo <= exponent <= hi
    top = nlogn_slope(points)
    return f"≤ {top:.2f}", lo <= top


def applies(scene, heuristic):
    if scene not in BOUNDS:
        return False
    only = BOUNDS[scene][0]
    return not only or heuristic.split(":")[0] in only


def fit_text(f):
    return "" if f is None else f"{f[0]:.2f} [{f[1][0]:.2f}, {f[1][1]:.2f}]"


def analyse(report):
    """The exponent rows, the explicit-bound contradictions and the exponent disagreements."""
    rows, contradictions, disagreements = [], [], []
    for (scene, heuristic, shape), points in series(report).items():
        if len({p[0] for p in points}) < 2:
            continue
        fs, ff, ft = fit(points, 1), fit(points, 2), fit(points, 3)
        theory, agrees = ("", None)
        if applies(scene, heuristic) and shape != "leafy":
            theory, agrees = judge(scene, points, fs)
            if agrees is False:
                disagreements.append((distance(scene, points, fs),
                                      f"{scene}, {heuristic} ({shape}): splits grow as n^{fit_text(fs)}, "
                                      f"theory {theory}, off by {distance(scene, points, fs):.2g} "
                                      f"({BOUNDS[scene][3]}; n = {min(p[0] for p in points)} to "
                                      f"{max(p[0] for p in points)})"))
            if scene == "random-segments":
                contradictions += bound_contradictions(scene, heuristic, shape, points)
        rows.append([scene, heuristic + ("" if shape == "strict" else f" ({shape})"),
                     f"{min(p[0] for p in points)}–{max(p[0] for p in points)}", Cell(fs[0] if fs else None,
                                                                                     fit_text(fs)),
                     Cell(theory or "—"), Cell("" if agrees is None else ("yes" if agrees else "no"), bold=agrees is False),
                     Cell(ff[0] if ff else None, fit_text(ff)), Cell(ft[0] if ft else None, fit_text(ft))])
    return rows, contradictions, [text for _, text in sorted(disagreements, key=lambda d: -d[0])]


def distance(scene, points, f):
    """How far the exponent's interval lies from the theory's exponent (0 when it holds it)."""
    target = BOUNDS[scene][2] if BOUNDS[scene][1] == "theta" else nlogn_slope(points)
    lo, hi = f[1]
    return max(lo - target, target - hi, 0.0) if BOUNDS[scene][1] == "theta" else max(lo - target, 0.0)


def bound_contradictions(scene, heuristic, shape, points):
    """Sizes where the interval over seeds of mean fragments lies above n + 2n ln n."""
    out = []
    by_n = {}
    for p in points:
        if p[2] is not None:
            by_n.setdefault(p[0], []).append(p[2])
    for n, values in sorted(by_n.items()):
        if len(values) < 2:
            continue
        mean = statistics.fmean(values)
        half = stats.student_quantile(0.975, len(values) - 1) * statistics.stdev(values) / math.sqrt(len(values))
        if mean - half > autopartition_bound(n):
            out.append(f"{scene}, {heuristic} ({shape}), n = {n}: mean fragments {mean:.1f} ± {half:.1f} exceed "
                       f"the bound n + 2n ln n = {autopartition_bound(n):.1f}")
    return out


def table(rows, command):
    return Table("theory", "Growth exponents against n, with 95% intervals, beside theory",
                 [("scene", ""), ("heuristic", ""), ("n", "polygons"), ("splits exponent", ""),
                  ("theory", ""), ("agrees", ""), ("fragments exponent", ""), ("build CPU time exponent", "")],
                 rows, command,
                 "Least squares of log y against log n over the sizes' geometric means over seeds, 95% t-interval "
                 "on the slope. Theory applies to the splits exponent; 'agrees' says whether the interval holds it.")


def top_list(contradictions, disagreements):
    if not contradictions and not disagreements:
        return ("<div class=ok><b>Theory:</b> no run contradicts its bound, and every bounded exponent's "
                "interval holds the theoretical one.</div>")
    parts = ["<div class=alert>"]
    if contradictions:
        parts.append(f"<b>Contradictions of an explicit bound ({len(contradictions)}):</b><ul>"
                     + "".join(f"<li>{html.escape(c)}</li>" for c in contradictions) + "</ul>")
    else:
        parts.append("<b>No run contradicts an explicit bound.</b>")
    if disagreements:
        parts.append(f"<p><b>Exponents whose interval excludes theory ({len(disagreements)}, farthest first)</b> — "
                     "asymptotic bounds allow this on a finite range of n, where lower-order terms bend the fit; see "
                     "<a href='#theory'>the theory section</a>:</p><ul>"
                     + "".join(f"<li>{html.escape(d)}</li>" for d in disagreements) + "</ul>")
    parts.append("</div>")
    return "".join(parts)


def render(report, ctx):
    rows, contradictions, disagreements = analyse(report)
    if not rows:
        return None
    t = table(rows, ctx.command)
    bounds = "".join(f"<li><b>{html.escape(scene)}</b>: {html.escape(b[3])}"
                     + (f" (heuristics: {', '.join(b[0])})" if b[0] else " (every heuristic)") + "</li>"
                     for scene, b in BOUNDS.items())
    body = (f"<h2 id='theory'>Does the theory hold?</h2><p>The bounds checked:</p><ul>{bounds}</ul>"
            "<p>Exponents are fitted to splits (fragments − n): the bounds are about the fragments a partition "
            "adds, and the linear n bends a short log-log range. An O(n log n) bound is met by exponents up to its "
            "local slope 1 + 1/ln n at the sizes fitted. An explicit bound (n + 2n ln n) is checked size by size.</p>"
            + t.html(scroll=True))
    return Section([("theory", "does the theory hold?")], body, [t], alert=top_list(contradictions, disagreements))
