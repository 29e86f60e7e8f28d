#pragma once
// Summary statistics over repeated runs (seeds), shared by `bspbench compare` and the sweeps:
// sample mean with a two-sided 95% confidence interval from Student's t distribution, and the
// least-squares fit of a power law y = c * x^k on log-log axes with its coefficient of
// determination R^2 and the t-interval of k. The HTML report reads these from report.json rather
// than computing its own (analysis/SCHEMA.md, AGGREGATE).
#include <cstddef>
#include <span>

#include <nlohmann/json_fwd.hpp>

namespace bsp {

// The 0.975 quantile of Student's t distribution with `dof` >= 1 degrees of freedom, so that
// mean ± t * s / sqrt(n) is a two-sided 95% interval for n = dof + 1 samples. Exact table (to 10
// digits) up to 30 degrees of freedom, the Cornish–Fisher expansion in 1/dof above (Abramowitz and
// Stegun 26.7.5; error below 1e-6 there).
double student_t_975(std::size_t dof);

struct Summary {
  std::size_t n = 0;        // number of samples
  double mean = 0;
  double stddev = 0;        // sample standard deviation (n - 1 in the denominator); 0 for n < 2
  double half_width = 0;    // of the 95% interval: t(n-1) * stddev / sqrt(n); 0 for n < 2
  bool has_interval() const { return n >= 2; }
  double lo() const { return mean - half_width; }
  double hi() const { return mean + half_width; }
};

Summary summarize(std::span<const double> samples);
// {n, mean, stddev, ci95: [lo, hi]}; ci95 is null when there is no interval (n < 2).
nlohmann::json to_json(const Summary& s);

// y = coefficient * x^exponent fitted by least squares on (log x, log y). Needs at least two
// samples with distinct x, all x and y positive (others throw std::invalid_argument). r2 is the
// coefficient of determination of the fit in log space: 1 for points exactly on a power law.
// half_width is that of the exponent's two-sided 95% interval, t(m-2) * sqrt(SSE / (m-2) / Sxx) for
// m points (Student's t on a least-squares slope [Student1908]); it needs a degree of freedom left,
// so m >= 3. The interval assumes independent points: give it one point per size, not replicates.
struct PowerFit {
  double exponent = 0;
  double coefficient = 0;
  double r2 = 0;
  std::size_t points = 0;
  double half_width = 0;  // 0 without an interval (two points)
  bool has_interval() const { return points >= 3; }
};

PowerFit fit_power_law(std::span<const double> x, std::span<const double> y);
nlohmann::json to_json(const PowerFit& f);

// The median (the mean of the middle two for an even count); 0 for no samples.
double median(std::span<const double> samples);

// The Mann–Whitney U test (Mann and Whitney 1947): are values of `a` systematically larger or
// smaller than those of `b`? Nonparametric, so one outlier (a timing hit by a context switch) moves
// it no more than any other value. u is U of `a`: the pairs with a_i > b_j plus half the ties. The
// two-sided p-value is exact when both samples have fewer than 8 values and nothing is tied
// (counting the rank arrangements); otherwise it is the normal approximation with tie and
// continuity corrections (Hollander and Wolfe, Nonparametric Statistical Methods, §4.1), as
// scipy.stats.mannwhitneyu and Google Benchmark's compare.py compute it. p = 1 when either sample
// is empty or every value is tied.
struct MannWhitney {
  double u = 0;
  double p = 1;
};
MannWhitney mann_whitney_u(std::span<const double> a, std::span<const double> b);

}  // namespace bsp
