#include "metrics/statistics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

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
  // Residual sum of squares of the line is syy - sxy^2/sxx; a constant y is fitted exactly.
  const double ss_res = std::max(0.0, syy - sxy * sxy / sxx);
  f.r2 = syy > 0 ? 1.0 - ss_res / syy : 1.0;
  return f;
}

nlohmann::json to_json(const PowerFit& f) {
  return {{"exponent", f.exponent}, {"coefficient", f.coefficient}, {"r2", f.r2}};
}

}  // namespace bsp
