#include "geometry/grid_plane.h"

#include <cmath>
#include <cstdlib>
#include <algorithm>
#include <cstdint>
#include <utility>

namespace bsp {

namespace {

struct Wide3 {
  Int128 x, y, z;
};

Wide3 difference(const GridPoint& q, const GridPoint& p) {
  return {Int128{q.x} - p.x, Int128{q.y} - p.y, Int128{q.z} - p.z};
}

Wide3 cross(const Wide3& e, const Wide3& f) {
  return {e.y * f.z - e.z * f.y, e.z * f.x - e.x * f.z, e.x * f.y - e.y * f.x};
}

GridPlane plane_with_normal(const Wide3& n, const GridPoint& p) {
  return {n.x, n.y, n.z, -(n.x * p.x + n.y * p.y + n.z * p.z)};
}

Int128 magnitude(Int128 v) { return v < 0 ? -v : v; }

using UInt128 = unsigned __int128;

// Binary GCD [Knuth1997, algorithm B]; gcd(0, v) = v. Each step removes at least
// a bit, and once both numbers fit 64 bits the steps run in 64-bit registers. The step keeps the
// smaller number and the difference with min and max, not a swap: which is smaller is a coin
// toss for the branch predictor, and a canonical plane pays about a hundred steps.
std::uint64_t gcd64(std::uint64_t u, std::uint64_t v) {
  if (u == 0) return v;
  if (v == 0) return u;
  const int shift = __builtin_ctzll(u | v);
  u >>= __builtin_ctzll(u);
  while (v != 0) {
    v >>= __builtin_ctzll(v);
    const std::uint64_t low = std::min(u, v);
    v = std::max(u, v) - low;
    u = low;
  }
  return u << shift;
}

UInt128 gcd(UInt128 u, UInt128 v) {
  if (u == 0) return v;
  if (v == 0) return u;
  const auto trailing = [](UInt128 x) {
    const auto low = static_cast<std::uint64_t>(x);
    return low ? __builtin_ctzll(low) : 64 + __builtin_ctzll(static_cast<std::uint64_t>(x >> 64));
  };
  const int shift = std::min(trailing(u), trailing(v));
  u >>= trailing(u);
  v >>= trailing(v);
  // One Euclidean step when only one of them needs 128 bits (a partial gcd is often small): the
  // binary steps would take a bit at a time off the large one. gcd(u, v) = gcd(u, v mod u), and the
  // remainder's factors of two are not common ones (the other number is odd), so they go too.
  if ((u >> 64) == 0 && (v >> 64) != 0) v %= u;
  if ((v >> 64) == 0 && (u >> 64) != 0) u %= v;
  if (u == 0 || v == 0) return (u | v) << shift;
  u >>= trailing(u);
  v >>= trailing(v);
  while ((u >> 64) != 0 || (v >> 64) != 0) {  // both odd here
    const UInt128 low = std::min(u, v);
    v = std::max(u, v) - low;
    u = low;
    if (v == 0) return u << shift;
    v >>= trailing(v);
  }
  return static_cast<UInt128>(gcd64(static_cast<std::uint64_t>(u), static_cast<std::uint64_t>(v))) << shift;
}

}  // namespace

GridPlane canonical(const GridPlane& p) {
  const auto mag = [](Int128 v) { return static_cast<UInt128>(v < 0 ? -v : v); };
  UInt128 g = gcd(mag(p.a), mag(p.b));
  if (g != 1) g = gcd(g, mag(p.c));
  if (g != 1) g = gcd(g, mag(p.d));
  if (g <= 1) return p;
  const auto div = [g](Int128 v) { return v < 0 ? -static_cast<Int128>(static_cast<UInt128>(-v) / g) : static_cast<Int128>(static_cast<UInt128>(v) / g); };
  return {div(p.a), div(p.b), div(p.c), div(p.d)};
}

std::optional<GridPlane> round_plane(const Plane& p, const Grid& grid) {
  const double m = std::max({std::abs(p.n.x), std::abs(p.n.y), std::abs(p.n.z)});
  if (!(m > 0) || !std::isfinite(m) || !std::isfinite(p.d)) return std::nullopt;
  // 2^e * m in [2^(bits - 1), 2^bits): frexp gives m = f * 2^x with f in [0.5, 1).
  int x = 0;
  std::frexp(m, &x);
  const int e = kFreeNormalBits - x;
  const double offset = std::ldexp((dot(p.n, grid.origin()) + p.d) / grid.step(), e);
  if (!(std::abs(offset) < kFreeOffsetLimit)) return std::nullopt;
  const auto round = [](double v) { return static_cast<Int128>(static_cast<std::int64_t>(std::nearbyint(v))); };
  const auto round_big = [](double v) {  // |v| < 2^82: the rounded magnitude is split at 2^64 exactly
    const double r = std::nearbyint(std::abs(v));
    const double high = std::floor(r * 0x1p-64);
    const Int128 magnitude = static_cast<Int128>(static_cast<std::uint64_t>(high)) << 64 |
                             static_cast<Int128>(static_cast<std::uint64_t>(r - high * 0x1p64));
    return v < 0 ? -magnitude : magnitude;
  };
  const GridPlane q{round(std::ldexp(p.n.x, e)), round(std::ldexp(p.n.y, e)), round(std::ldexp(p.n.z, e)),
                    round_big(offset)};
  return canonical(q);
}

std::optional<GridPlane> plane_through(const GridPoint& p, const GridPoint& q, const GridPoint& r) {
  const Wide3 n = cross(difference(q, p), difference(r, p));
  if (n.x == 0 && n.y == 0 && n.z == 0) return std::nullopt;
  return plane_with_normal(n, p);
}

std::optional<GridPlane> edge_plane(const GridPoint& p, const GridPoint& q, const GridPlane& support,
                                    const GridPoint& inside) {
  if (p == q) return std::nullopt;
  // The axis of support's largest normal component is not parallel to the support plane.
  const Int128 ax = magnitude(support.a), ay = magnitude(support.b), az = magnitude(support.c);
  const Wide3 axis = ax >= ay && ax >= az ? Wide3{1, 0, 0} : ay >= az ? Wide3{0, 1, 0} : Wide3{0, 0, 1};
  const GridPlane plane = plane_with_normal(cross(difference(q, p), axis), p);
  const int side = plane.side(inside);
  if (side == 0) return std::nullopt;
  return side > 0 ? plane : -plane;
}

}  // namespace bsp
