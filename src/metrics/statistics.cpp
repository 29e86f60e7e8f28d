#include "metrics/statistics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>
#include <vector>

namespace bsp {

namespace {

// t_{0.975, dof} for dof = 1..30 (computed with scipy.stats.t.ppf, 10 digits).
constexpr std::array<double, 30> kT975 = {
    12.7062047364, 4.3026527299, 3.1824463053, 2.7764451052, 2.5705818366, 2.4469118488,
    2.3646242510,  2.3060041350, 2.2621571627, 2.2281388520, 2.2009851601, 2.1788128297,
    2.1603686565,  2.1447866879, 2.1314495456, 2.1199052992, 2.1098155778, 2.1009220402,
    2.0930240544,  2.0859634473, 2.0796138447, 2.0738730679, 2.0686576104, 2.0638985616,
    2.0595385528,  2.0555294386, 2.0518305165, 2.0484071418, 2.0452296421, 2.0422724563};

// The standard normal's 0.975 quantile.
constexpr double kZ975 = 1.959963984540054;

double cornish_fisher_t(double z, double dof) {
  const double z3 = z * z * z, z5 = z3 * z * z, z7 = z5 * z * z, z9 = z7 * z * z;
  const double g1 = (z3 + z) / 4;
  const double g2 = (5 * z5 + 16 * z3 + 3 * z) / 96;
  const double g3 = (3 * z7 + 19 * z5 + 17 * z3 - 15 * z) / 384;
  const double g4 = (79 * z9 + 776 * z7 + 1482 * z5 - 1920 * z3 - 945 * z) / 92160;
  return z + g1 / dof + g2 / (dof * dof) + g3 / (dof * dof * dof) + g4 / (dof * dof * dof * dof);
}

}  // namespace

double student_t_975(std::size_t dof) {
  if (dof == 0) throw std::invalid_argument("Student t quantile needs at least one degree of freedom");
  if (dof <= kT975.size()) return kT975[dof - 1];
  return cornish_fisher_t(kZ975, static_cast<double>(dof));
}

Summary summarize(std::span<const double> samples) {
  Summary s;
  s.n = samples.size();
  if (s.n == 0) return s;
  for (double v : samples) s.mean += v;
  s.mean /= static_cast<double>(s.n);
  if (s.n < 2) return s;
  double ss = 0;
  for (double v : samples) ss += (v - s.mean) * (v - s.mean);
  s.stddev = std::sqrt(ss / static_cast<double>(s.n - 1));
  s.half_width = student_t_975(s.n - 1) * s.stddev / std::sqrt(static_cast<double>(s.n));
  return s;
}

nlohmann::json to_json(const Summary& s) {
  nlohmann::json ci = nullptr;
  if (s.has_interval()) ci = {s.lo(), s.hi()};
  return {{"n", s.n}, {"mean", s.mean}, {"stddev", s.stddev}, {"ci95", ci}};
}

PowerFit fit_power_law(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size() || x.size() < 2) throw std::invalid_argument("power-law fit needs >= 2 (x, y) pairs");
  const auto n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0) || !(y[i] > 0)) throw std::invalid_argument("power-law fit needs positive x and y");
    mx += std::log(x[i]);
    my += std::log(y[i]);
  }
  mx /= n;
  my /= n;
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double dx = std::log(x[i]) - mx, dy = std::log(y[i]) - my;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  if (!(sxx > 0)) throw std::invalid_argument("power-law fit needs at least two distinct x");
  PowerFit f;
  f.exponent = sxy / sxx;
  f.coefficient = std::exp(my - f.exponent * mx);
  // The residuals summed one by one, not as syy - sxy^2/sxx: on points close to a power law that
  // difference cancels to rounding noise, and the interval would be the noise's square root.
  double ss_res = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = std::log(y[i]) - my - f.exponent * (std::log(x[i]) - mx);
    ss_res += r * r;
  }
  f.r2 = syy > 0 ? 1.0 - ss_res / syy : 1.0;
  f.points = x.size();
  if (f.has_interval()) {
    const std::size_t dof = f.points - 2;
    f.half_width = student_t_975(dof) * std::sqrt(ss_res / static_cast<double>(dof) / sxx);
  }
  return f;
}

nlohmann::json to_json(const PowerFit& f) {
  return {{"exponent", f.exponent}, {"coefficient", f.coefficient}, {"r2", f.r2}};
}

double median(std::span<const double> samples) {
  if (samples.empty()) return 0;
  std::vector<double> v(samples.begin(), samples.end());
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  if (v.size() % 2 == 1) return v[mid];
  const double upper = v[mid];
  return (*std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid)) + upper) / 2;
}

namespace {

// Below this many values in both samples (and without ties) the p-value is exact.
constexpr std::size_t kExactBelow = 8;

struct Ranked {
  double rank_sum_a = 0;
  double tie_term = 0;  // sum over groups of tied values of t^3 - t
};

Ranked rank(std::span<const double> a, std::span<const double> b) {
  std::vector<std::pair<double, bool>> all;  // value, from a
  for (double x : a) all.emplace_back(x, true);
  for (double x : b) all.emplace_back(x, false);
  std::sort(all.begin(), all.end());
  Ranked r;
  for (std::size_t i = 0; i < all.size();) {
    std::size_t j = i;
    while (j < all.size() && all[j].first == all[i].first) ++j;
    const double t = static_cast<double>(j - i), mid_rank = (static_cast<double>(i + j) + 1) / 2;
    for (std::size_t k = i; k < j; ++k)
      if (all[k].second) r.rank_sum_a += mid_rank;
    r.tie_term += t * t * t - t;
    i = j;
  }
  return r;
}

// P(U <= u) under the null hypothesis for samples of m and n values without ties: the share of the
// C(m+n, m) rank arrangements with at most u pairs in a's favour, counted by the recursion
// c(m, n, u) = c(m - 1, n, u - n) + c(m, n - 1, u).
double exact_cdf(std::size_t m, std::size_t n, double u) {
  const std::size_t max_u = m * n;
  // counts[i][j][v]: arrangements of i values of a and j of b with U = v.
  std::vector<std::vector<std::vector<double>>> counts(m + 1, std::vector<std::vector<double>>(n + 1));
  for (std::size_t i = 0; i <= m; ++i)
    for (std::size_t j = 0; j <= n; ++j) {
      auto& c = counts[i][j];
      c.assign(i * j + 1, 0.0);
      if (i == 0 || j == 0) {
        c[0] = 1;
        continue;
      }
      for (std::size_t v = 0; v <= i * j; ++v) {
        if (v >= j && v - j < counts[i - 1][j].size()) c[v] += counts[i - 1][j][v - j];
        if (v < counts[i][j - 1].size()) c[v] += counts[i][j - 1][v];
      }
    }
  double below = 0, total = 0;
  for (std::size_t v = 0; v <= max_u; ++v) {
    total += counts[m][n][v];
    if (static_cast<double>(v) <= u) below += counts[m][n][v];
  }
  return below / total;
}

}  // namespace

MannWhitney mann_whitney_u(std::span<const double> a, std::span<const double> b) {
  MannWhitney out;
  if (a.empty() || b.empty()) return out;
  const double m = static_cast<double>(a.size()), n = static_cast<double>(b.size()), total = m + n;
  const Ranked r = rank(a, b);
  out.u = r.rank_sum_a - m * (m + 1) / 2;
  const double mean_u = m * n / 2;
  if (r.tie_term == 0 && a.size() < kExactBelow && b.size() < kExactBelow) {
    // U is symmetric about m n / 2, so the two tails are equal.
    out.p = std::min(1.0, 2 * exact_cdf(a.size(), b.size(), std::min(out.u, m * n - out.u)));
    return out;
  }
  const double variance = m * n / 12 * ((total + 1) - r.tie_term / (total * (total - 1)));
  if (!(variance > 0)) return out;
  const double z = std::max(0.0, std::abs(out.u - mean_u) - 0.5) / std::sqrt(variance);
  out.p = std::min(1.0, std::erfc(z / std::sqrt(2.0)));
  return out;
}

}  // namespace bsp
