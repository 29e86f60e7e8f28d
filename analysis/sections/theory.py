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
by exponents up to 1 + 1/ln(n), its local slope at the geometric mean of the sizes.

Every number judged here is report.json's: the exponents and their 95% t-intervals are the
aggregates' fits over the sizes' geometric means (growth_over_sizes, analysis/SCHEMA.md), the
intervals over seeds their by_n summaries; nothing is refitted here.

A contradiction is a measurement the bound rules out: an explicit bound exceeded by the lower end
of a size's 95% interval over seeds. Exponents are judged with an equivalence margin
[Schuirmann1987]: an exponent agrees with theory when its 95% interval holds the theoretical
exponent, or lies within EQUIVALENCE_MARGIN of it (for an O(n log n) bound, when its lower end is at
most the local slope plus the margin): a fit of 2.01 to 2.02 against Θ(n²) measures the theory,
bent by lower-order terms on a finite range of n. An exponent beyond the margin is a disagreement,
not a contradiction (asymptotic bounds say nothing about a finite range either); contradictions and
disagreements are listed at the top of the report, agreements within the margin in the table only.
"""
import html
import math
import statistics

from sections import verdicts
from sections.common import Section, aggregates_of, is_float
from tables import Cell, Table

# How far an exponent's interval may lie from the theoretical exponent and still count as agreeing:
# a twentieth of a power of n, over the two decades of n a suite fits, is a factor of about 1.26 —
# what the lower-order terms of the bounds (n log n beside n², n beside n^{3/2}) bend a fit by.
EQUIVALENCE_MARGIN = 0.05

# scene -> (heuristics it applies to (empty: all), kind, exponent or None, statement)
BOUNDS = {
    "saddle-grid": ((), "theta", 2.0, "Θ(n²) [PatersonYao1990]"),
    "orthogonal-stacks": ((), "theta", 1.5, "Θ(n^{3/2}) [PatersonYao1992]"),
    "random-disjoint": (("random",), "nlogn", None, "O(n log n) expected (hypothesis in 3D; theorem in 2D)"),
    "random-segments": (("random",), "nlogn", None, "n + 2n ln n expected [PatersonYao1990; deBerg2008]"),
}


def autopartition_bound(n):
    """Expected fragments of a random autopartition of n disjoint segments is at most n + 2n ln n
    [PatersonYao1990; deBerg2008 §12.2]."""
    return n + 2 * n * math.log(n)


def series(report):
    """(scene, heuristic, shape) -> the float kernel's drawing aggregate; a generator with several
    parameter sets in the report gives one scene per set."""
    name = verdicts.scene_namer(report)
    return dict(sorted(((name(a), a["heuristic"], a["shape"]), a) for a in aggregates_of(report, "draw") if is_float(a)))


def sizes(agg):
    """The polygon counts of the aggregate's sizes (means over seeds)."""
    return [e["n_polygons"]["mean"] for e in agg["by_n"]]


def fits(agg):
    """The splits, fragments and build CPU time fits over sizes; None each where the report has none."""
    over = agg.get("growth_over_sizes") or {}
    metrics, timings = over.get("growth") or {}, over.get("timing_growth") or {}
    return metrics.get("splits"), metrics.get("fragments"), timings.get("build_cpu_seconds")


def nlogn_slope(agg):
    return 1 + 1 / statistics.fmean(math.log(n) for n in sizes(agg) if n > 1)


def judge(scene, agg, f):
    """(theoretical exponent text, verdict) for a splits fit of a bounded scene: "yes" when the interval
    holds the theory, "within margin" when it lies within EQUIVALENCE_MARGIN of it, "no" otherwise;
    None without a fit."""
    _, kind, exponent, _ = BOUNDS[scene]
    if f is None:
        return "", None
    lo, hi = f["ci95"]
    if kind == "theta":
        text = f"{exponent:g}"
        if lo <= exponent <= hi:
            return text, "yes"
        near = exponent - EQUIVALENCE_MARGIN <= lo and hi <= exponent + EQUIVALENCE_MARGIN
        return text, "within margin" if near else "no"
    top = nlogn_slope(agg)
    text = f"≤ {top:.2f}"
    if lo <= top:
        return text, "yes"
    return text, "within margin" if lo <= top + EQUIVALENCE_MARGIN else "no"


def applies(scene, heuristic):
    if scene not in BOUNDS:
        return False
    only = BOUNDS[scene][0]
    return not only or heuristic.split(":")[0] in only


def fit_text(f):
    return "" if f is None else f"{f['exponent']:.2f} [{f['ci95'][0]:.2f}, {f['ci95'][1]:.2f}]"


def fit_cell(f):
    return Cell(f["exponent"] if f else None, fit_text(f))


def size_range(agg):
    """The least and greatest polygon count, whole (the means of equal counts)."""
    return round(min(sizes(agg))), round(max(sizes(agg)))


def analyse(report):
    """The exponent rows, the explicit-bound contradictions and the exponent disagreements."""
    rows, contradictions, disagreements = [], [], []
    for (scene, heuristic, shape), agg in series(report).items():
        if len(set(sizes(agg))) < 2:
            continue
        fs, ff, ft = fits(agg)
        theory, agrees = ("", None)
        if applies(scene, heuristic) and shape != "leafy":
            theory, agrees = judge(scene, agg, fs)
            if agrees == "no":
                off, (lo, hi) = distance(scene, agg, fs), size_range(agg)
                disagreements.append((off, f"{scene}, {heuristic} ({shape}): splits grow as n^{fit_text(fs)}, "
                                           f"theory {theory}, off by {off:.2g} ({BOUNDS[scene][3]}; n = {lo} to {hi})"))
            if scene == "random-segments":
                contradictions += bound_contradictions(scene, heuristic, shape, agg)
        label = heuristic + ("" if shape == "strict" else f" ({shape})")
        verdict = Cell(agrees or "", bold=agrees == "no")
        rows.append([scene, label, "–".join(map(str, size_range(agg))), fit_cell(fs), Cell(theory or "—"), verdict,
                     fit_cell(ff), fit_cell(ft)])
    return rows, contradictions, [text for _, text in sorted(disagreements, key=lambda d: -d[0])]


def distance(scene, agg, f):
    """How far the exponent's interval lies from the theory's exponent (0 when it holds it)."""
    target = BOUNDS[scene][2] if BOUNDS[scene][1] == "theta" else nlogn_slope(agg)
    lo, hi = f["ci95"]
    return max(lo - target, target - hi, 0.0) if BOUNDS[scene][1] == "theta" else max(lo - target, 0.0)


def bound_contradictions(scene, heuristic, shape, agg):
    """Sizes where the interval over seeds of mean fragments lies above n + 2n ln n."""
    out = []
    for e in agg["by_n"]:
        n, fragments = round(e["n_polygons"]["mean"]), e["metrics"].get("fragments")
        if fragments is None or fragments["ci95"] is None:
            continue  # one seed: no interval
        lo, hi = fragments["ci95"]
        if lo > autopartition_bound(n):
            out.append(f"{scene}, {heuristic} ({shape}), n = {n}: mean fragments {fragments['mean']:.1f} ± "
                       f"{(hi - lo) / 2:.1f} exceed the bound n + 2n ln n = {autopartition_bound(n):.1f}")
    return out


def table(rows, command):
    return Table("theory", "Growth exponents against n, with 95% intervals, beside theory",
                 [("scene", ""), ("heuristic", ""), ("n", "polygons"), ("splits exponent", ""),
                  ("theory", ""), ("agrees", ""), ("fragments exponent", ""), ("build CPU time exponent", "")],
                 rows, command,
                 "Least squares of log y against log n over the sizes' geometric means over seeds, 95% t-interval "
                 "on the slope. Theory applies to the splits exponent; 'agrees': yes when the interval holds it, "
                 f"'within margin' when the interval lies within ±{EQUIVALENCE_MARGIN:g} of it, no otherwise.")


def top_list(contradictions, disagreements, fitted=True):
    """The box at the top of the page: red only for contradictions of an explicit bound; exponents
    beyond the equivalence margin in a notice; green when neither."""
    if fitted and not contradictions and not disagreements:
        return ("<div class=ok><b>Theory:</b> no run contradicts its bound, and every bounded exponent agrees "
                f"with the theoretical one (its interval holds it or lies within ±{EQUIVALENCE_MARGIN:g} of it).</div>")
    parts = []
    if contradictions:
        parts.append(f"<div class=alert><b>Contradictions of an explicit bound ({len(contradictions)}):</b><ul>"
                     + "".join(f"<li>{html.escape(c)}</li>" for c in contradictions) + "</ul></div>")
    notice = []
    if not fitted:
        notice.append("<p><b>Exponents not judged:</b> this report's aggregates predate their growth fits over "
                      "sizes (see <a href='#theory'>the theory section</a>).</p>")
    if not contradictions:
        notice.append("<b>No run contradicts an explicit bound.</b>")
    if disagreements:
        notice.append(f"<p><b>Exponents more than {EQUIVALENCE_MARGIN:g} from theory ({len(disagreements)}, farthest "
                      "first)</b> — not contradictions: asymptotic bounds allow this on a finite range of n, where "
                      "lower-order terms bend the fit; see <a href='#theory'>the theory section</a>:</p><ul>"
                      + "".join(f"<li>{html.escape(d)}</li>" for d in disagreements) + "</ul>")
    if notice:
        parts.append("<div class=notice>" + "".join(notice) + "</div>")
    return "".join(parts)


def fitted(report):
    """Whether the aggregates carry their fits over sizes: a report written before they did has no
    exponents to judge."""
    return all("growth_over_sizes" in a for a in aggregates_of(report, "draw"))


MISSING_FITS = ("<p class=alert>This report's aggregates predate their growth fits over sizes, so it has no "
                "exponents to judge; <code>bspbench merge-reports --out NEW.json REPORT.json</code> recomputes the "
                "aggregates from its runs.</p>")


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
            "local slope 1 + 1/ln n at the sizes fitted. An explicit bound (n + 2n ln n) is checked size by size. "
            f"An exponent within ±{EQUIVALENCE_MARGIN:g} of theory agrees (an equivalence margin).</p>"
            + ("" if fitted(report) else MISSING_FITS) + t.html(scroll=True))
    return Section([("theory", "does the theory hold?")], body, [t],
                   alert=top_list(contradictions, disagreements, fitted(report)))
