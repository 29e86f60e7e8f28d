// random-segments: n pairwise disjoint segments in the unit square at z = 0, a 2D scene
// (geometry/segment2.h). The setting of the random-autopartition bound: a random autopartition of n
// disjoint segments makes at most n + 2n ln n fragments in expectation [PatersonYao1990;
// deBerg2008 §12.2]. One segment per cell of an m x m grid (m = ceil(sqrt(n)), cells in
// x-fastest order), centred at a random point of its cell, in a random direction, `length` cells
// long at most; a segment that would touch an earlier one is halved until it does not, and drawn
// again (another centre and direction) when it would have to become shorter than kMinLength cells.
// Long segments reach across many cells, so a partition line through one meets many others: the
// bound is tested where it has something to say.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "catalog.h"
#include "common/rng.h"
#include "shapes.h"

namespace bsp {

namespace {

constexpr int kCentreDraws = 64;
// The shortest segment drawn, in grid cells: a scene of comparable segments, none near the
// tolerance (a segment that has to be shorter lies almost on an earlier one: another place is drawn).
constexpr double kMinLength = 0.05;
constexpr double kPi = 3.14159265358979323846;

struct Seg {
  double ax, ay, bx, by;
};

double orient(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

bool on_box(double ax, double ay, double bx, double by, double cx, double cy) {
  return std::min(ax, bx) <= cx && cx <= std::max(ax, bx) && std::min(ay, by) <= cy && cy <= std::max(ay, by);
}

// Closed segments meet (touching counts: the scene is meant to be strictly disjoint).
bool meet(const Seg& s, const Seg& t) {
  const double d1 = orient(t.ax, t.ay, t.bx, t.by, s.ax, s.ay), d2 = orient(t.ax, t.ay, t.bx, t.by, s.bx, s.by);
  const double d3 = orient(s.ax, s.ay, s.bx, s.by, t.ax, t.ay), d4 = orient(s.ax, s.ay, s.bx, s.by, t.bx, t.by);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 == 0 && on_box(t.ax, t.ay, t.bx, t.by, s.ax, s.ay)) || (d2 == 0 && on_box(t.ax, t.ay, t.bx, t.by, s.bx, s.by)) ||
         (d3 == 0 && on_box(s.ax, s.ay, s.bx, s.by, t.ax, t.ay)) || (d4 == 0 && on_box(s.ax, s.ay, s.bx, s.by, t.bx, t.by));
}

// Accepted segments by the grid cells their bounding boxes cover.
class SegmentGrid {
 public:
  explicit SegmentGrid(std::size_t m) : m_(m), cells_(m * m) {}

  bool free(const Seg& s) const {
    for (auto c : covered(s))
      for (auto id : cells_[c])
        if (meet(s, segs_[id])) return false;
    return true;
  }
  void add(const Seg& s) {
    const auto id = static_cast<std::uint32_t>(segs_.size());
    segs_.push_back(s);
    for (auto c : covered(s)) cells_[c].push_back(id);
  }
  const std::vector<Seg>& segments() const { return segs_; }

 private:
  std::size_t cell_of(double v) const {
    const double c = std::floor(v * static_cast<double>(m_));
    return static_cast<std::size_t>(std::clamp(c, 0.0, static_cast<double>(m_ - 1)));
  }
  std::vector<std::size_t> covered(const Seg& s) const {
    std::vector<std::size_t> out;
    for (std::size_t y = cell_of(std::min(s.ay, s.by)); y <= cell_of(std::max(s.ay, s.by)); ++y)
      for (std::size_t x = cell_of(std::min(s.ax, s.bx)); x <= cell_of(std::max(s.ax, s.bx)); ++x)
        out.push_back(y * m_ + x);
    return out;
  }

  std::size_t m_;
  std::vector<std::vector<std::uint32_t>> cells_;
  std::vector<Seg> segs_;
};

// A segment through (cx, cy) of the given length, clipped to the unit square's interior.
Seg segment_at(double cx, double cy, double angle, double len) {
  const double dx = 0.5 * len * std::cos(angle), dy = 0.5 * len * std::sin(angle);
  auto clamp01 = [](double v) { return std::clamp(v, 0.0, 1.0); };
  return {clamp01(cx - dx), clamp01(cy - dy), clamp01(cx + dx), clamp01(cy + dy)};
}

Seg place(std::size_t i, std::size_t m, double max_cells, std::uint64_t seed, const SegmentGrid& grid) {
  Rng rng(stream_seed(seed, i));
  const double h = 1.0 / static_cast<double>(m);
  const double x0 = static_cast<double>(i % m) * h, y0 = static_cast<double>(i / m) * h;
  for (int draw = 0; draw < kCentreDraws; ++draw) {
    const double cx = x0 + h * rng.uniform(), cy = y0 + h * rng.uniform();
    const double angle = 2 * kPi * rng.uniform();
    for (double len = max_cells * h * (0.5 + 0.5 * rng.uniform()); len >= kMinLength * h; len *= 0.5) {
      const Seg s = segment_at(cx, cy, angle, len);
      if ((s.ax != s.bx || s.ay != s.by) && grid.free(s)) return s;
    }
  }
  throw std::logic_error("random-segments: no free place for segment " + std::to_string(i));
}

std::vector<Polygon> make(const ParamSet& p) {
  const std::size_t n = count_of(p);
  auto m = static_cast<std::size_t>(std::sqrt(static_cast<double>(n)));
  while (m * m < n) ++m;
  m = std::max<std::size_t>(m, 1);
  SegmentGrid grid(m);
  for (std::size_t i = 0; i < n; ++i) grid.add(place(i, m, p.real("length"), seed_of(p), grid));
  std::vector<Polygon> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Seg& s = grid.segments()[i];
    out.push_back(Polygon{{Vertex{{s.ax, s.ay, 0}}, Vertex{{s.bx, s.by, 0}}}, static_cast<std::uint32_t>(i)});
  }
  return out;
}

}  // namespace

GeneratorInfo random_segments_generator() {
  return {"random-segments",
          "2D: n disjoint segments of random direction, up to `length` grid cells long; where the random "
          "autopartition bound n + 2n ln n (Paterson-Yao) is measured",
          "exactly n segments",
          {n_param(1000, "number of segments"), seed_param(),
           {"length", ParamSpec::Kind::Real,
            "longest segment, in grid cells (the grid has ceil(sqrt(n)) cells a side); longer segments cross more "
            "partition lines",
            4.0, 0.1, 16.0, {}}},
          make,
          true,
          false,
          true};
}

}  // namespace bsp
