"""The statistics only the report needs: the verdicts' paired t-test and Holm's correction, the cost
model's rank correlations and their bootstrap intervals. Intervals over seeds, growth fits and the
regression gate's test are computed once, in C++ (src/metrics/statistics.h), and read from
report.json.

Standard library only, so the report needs nothing beyond matplotlib. Each function states the
test or estimator it computes; tests/report/test_analysis.py checks them against published tables
and hand-computed cases.

Notation: n values or pairs; df degrees of freedom; p a two-sided p-value.
"""
import math
import random
import statistics


# Two results this close (relative) are equal: the regression gate's kFloatRelative
# (src/gate/regress.h), since a sum's last bits may differ between builds of the same tree.
FLOAT_RELATIVE = 1e-9


def close(a, b):
    """Numbers equal within FLOAT_RELATIVE."""
    return abs(a - b) <= FLOAT_RELATIVE * max(abs(a), abs(b))


def _beta_continued_fraction(a, b, x):
    """The continued fraction of the incomplete beta function (modified Lentz), for x < (a+1)/(a+b+2)."""
    tiny, eps = 1e-300, 1e-15
    c, d = 1.0, 1.0 - (a + b) * x / (a + 1.0)
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 500):
        for numerator in (m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m)),
                          -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))):
            d = 1.0 + numerator * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + numerator / c
            c = c if abs(c) > tiny else tiny
            h *= c * d
        if abs(c * d - 1.0) < eps:
            break
    return h


def incomplete_beta(a, b, x):
    """The regularized incomplete beta function I_x(a, b), x in [0, 1]."""
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    front = math.exp(math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log1p(-x))
    if x < (a + 1.0) / (a + b + 2.0):
        return front * _beta_continued_fraction(a, b, x) / a
    return 1.0 - front * _beta_continued_fraction(b, a, 1.0 - x) / b


def student_p(t, df):
    """Two-sided p-value of Student's t with df degrees of freedom."""
    if math.isinf(t):
        return 0.0
    return incomplete_beta(df / 2.0, 0.5, df / (df + t * t))


def paired_t(diffs):
    """Student's paired t-test [Student1908] of mean(diffs) = 0: (mean difference, p). Needs two or more pairs.

    Identical differences have no spread: p is 0 when they are non-zero (every seed agrees exactly,
    as deterministic metrics of identical trees do) and 1 when they are all zero.
    """
    n = len(diffs)
    if n < 2:
        return (diffs[0] if diffs else 0.0), None
    mean = statistics.fmean(diffs)
    sd = statistics.stdev(diffs)
    if sd == 0.0:
        return mean, (1.0 if mean == 0.0 else 0.0)
    return mean, student_p(mean / (sd / math.sqrt(n)), n - 1)


def holm(pvalues):
    """Holm's step-down adjustment [Holm1979] of a family of p-values; None entries stay None.

    Controls the family-wise error rate: reject every hypothesis whose adjusted p is below alpha.
    """
    indexed = sorted((p, i) for i, p in enumerate(pvalues) if p is not None)
    adjusted = list(pvalues)
    running = 0.0
    m = len(indexed)
    for rank, (p, i) in enumerate(indexed):
        running = max(running, min(1.0, (m - rank) * p))
        adjusted[i] = running
    return adjusted


def ranks(values):
    """Ranks from 1, ties given their average rank."""
    order = sorted(range(len(values)), key=lambda i: values[i])
    out = [0.0] * len(values)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and values[order[j + 1]] == values[order[i]]:
            j += 1
        for k in range(i, j + 1):
            out[order[k]] = (i + j) / 2.0 + 1.0
        i = j + 1
    return out


def pearson(x, y):
    """Pearson's correlation; None when either side has no spread."""
    mx, my = statistics.fmean(x), statistics.fmean(y)
    sxy = sum((a - mx) * (b - my) for a, b in zip(x, y))
    sxx = sum((a - mx) ** 2 for a in x)
    syy = sum((b - my) ** 2 for b in y)
    if sxx == 0.0 or syy == 0.0:
        return None
    return sxy / math.sqrt(sxx * syy)


def spearman(x, y):
    """Spearman's rank correlation [Spearman1904]: Pearson's on the average ranks; None without spread."""
    return pearson(ranks(x), ranks(y))


def bootstrap_interval(clusters, statistic, reps=1000, seed=1, level=0.95):
    """Percentile bootstrap interval [Efron1979] of statistic(xs, ys), resampling whole clusters of
    (x, y) pairs with replacement: pairs that share a cluster (one heuristic's runs over seeds and
    shapes) are not independent, and resampling them one by one would make the interval too narrow.

    Seeded, so a report renders the same interval every time. Resamples where the statistic is
    undefined (no spread) are left out; None when fewer than half of them are defined.
    """
    rng = random.Random(seed)
    values = []
    for _ in range(reps):
        sample = [pair for _ in clusters for pair in clusters[rng.randrange(len(clusters))]]
        v = statistic([a for a, _ in sample], [b for _, b in sample])
        if v is not None:
            values.append(v)
    if len(values) < reps // 2:
        return None
    values.sort()
    tail = (1.0 - level) / 2.0
    return values[int(tail * (len(values) - 1))], values[int(math.ceil((1.0 - tail) * (len(values) - 1)))]

