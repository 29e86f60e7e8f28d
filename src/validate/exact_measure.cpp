#include "validate/exact_measure.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "validate/cgal_mesh.h"

namespace bsp {

namespace {

using Vec3Z = std::array<mpz_class, 3>;

// ---- Integers of any size, and their canonical text.

void set_int128(mpz_class& out, Int128 v) {
  const unsigned __int128 m = v < 0 ? -static_cast<unsigned __int128>(v) : static_cast<unsigned __int128>(v);
  const std::uint64_t limbs[2] = {static_cast<std::uint64_t>(m), static_cast<std::uint64_t>(m >> 64)};
  mpz_import(out.get_mpz_t(), 2, -1, sizeof(std::uint64_t), 0, 0, limbs);
  if (v < 0) mpz_neg(out.get_mpz_t(), out.get_mpz_t());
}

// Appends z to a key as its signed limb count and its limbs: the count makes the encoding
// prefix-free, so keys made of several integers are equal exactly when the integers are.
void append_key(std::string& key, const mpz_class& z) {
  const int count = mpz_sgn(z.get_mpz_t()) * static_cast<int>(mpz_size(z.get_mpz_t()));
  key.append(reinterpret_cast<const char*>(&count), sizeof count);
  key.append(reinterpret_cast<const char*>(mpz_limbs_read(z.get_mpz_t())), mpz_size(z.get_mpz_t()) * sizeof(mp_limb_t));
}

// out = a x b, with no temporaries (mpz_submul), so a reused `out` allocates nothing once grown.
void cross(const Vec3Z& a, const Vec3Z& b, Vec3Z& out) {
  for (int j = 0; j < 3; ++j) {
    const int p = (j + 1) % 3, q = (j + 2) % 3;
    mpz_mul(out[j].get_mpz_t(), a[p].get_mpz_t(), b[q].get_mpz_t());
    mpz_submul(out[j].get_mpz_t(), a[q].get_mpz_t(), b[p].get_mpz_t());
  }
}

void dot(const Vec3Z& a, const Vec3Z& b, mpz_class& out) {
  mpz_mul(out.get_mpz_t(), a[0].get_mpz_t(), b[0].get_mpz_t());
  mpz_addmul(out.get_mpz_t(), a[1].get_mpz_t(), b[1].get_mpz_t());
  mpz_addmul(out.get_mpz_t(), a[2].get_mpz_t(), b[2].get_mpz_t());
}

std::string canonical_text(mpq_class q) {
  q.canonicalize();
  return q.get_str();
}

// ---- Planes and the vertices they make.

struct PlaneZ {
  Vec3Z n;
  mpz_class d;
};

bool below_bits(Int128 v, int bits) { return (v < 0 ? -v : v) < (Int128{1} << bits); }

// The bounds make every vertex's numerators and denominator as small as the header says; a plane
// past them did not come from grid points, so its vertices could need more than the kernel's
// proofs cover, and the caller is told rather than measured wrongly elsewhere.
void set_plane(PlaneZ& out, const GridPlane& p) {
  if (!below_bits(p.a, kNormalBits) || !below_bits(p.b, kNormalBits) || !below_bits(p.c, kNormalBits) ||
      !below_bits(p.d, kOffsetBits))
    throw std::invalid_argument("check_exact_boundary: a plane's coefficients exceed a grid plane's bounds");
  set_int128(out.n[0], p.a);
  set_int128(out.n[1], p.b);
  set_int128(out.n[2], p.c);
  set_int128(out.d, p.d);
}

// A point x / den with den > 0 and gcd(x0, x1, x2, den) = 1: one representation per point.
struct PointZ {
  Vec3Z x;
  mpz_class den;
  bool integral() const { return den == 1; }
};

// Where three planes n_i . x + d_i = 0 meet (Cramer's rule):
// x = -(d1 (n2 x n3) + d2 (n3 x n1) + d3 (n1 x n2)) / (n1 . (n2 x n3)).
class VertexSolver {
 public:
  void solve(const PlaneZ& p1, const PlaneZ& p2, const PlaneZ& p3, PointZ& out) {
    cross(p2.n, p3.n, c23_);
    cross(p3.n, p1.n, c31_);
    cross(p1.n, p2.n, c12_);
    dot(p1.n, c23_, out.den);
    const int sign = sgn(out.den);
    if (sign == 0) throw std::invalid_argument("check_exact_boundary: a vertex's three planes do not meet in a point");
    for (int j = 0; j < 3; ++j) {
      mpz_ptr x = out.x[j].get_mpz_t();
      mpz_mul(x, p1.d.get_mpz_t(), c23_[j].get_mpz_t());
      mpz_addmul(x, p2.d.get_mpz_t(), c31_[j].get_mpz_t());
      mpz_addmul(x, p3.d.get_mpz_t(), c12_[j].get_mpz_t());
      if (sign > 0) mpz_neg(x, x);
    }
    if (sign < 0) mpz_neg(out.den.get_mpz_t(), out.den.get_mpz_t());
    reduce(out);
  }

 private:
  void reduce(PointZ& p) {
    mpz_gcd(g_.get_mpz_t(), p.den.get_mpz_t(), p.x[0].get_mpz_t());
    mpz_gcd(g_.get_mpz_t(), g_.get_mpz_t(), p.x[1].get_mpz_t());
    mpz_gcd(g_.get_mpz_t(), g_.get_mpz_t(), p.x[2].get_mpz_t());
    if (g_ == 1) return;
    mpz_divexact(p.den.get_mpz_t(), p.den.get_mpz_t(), g_.get_mpz_t());
    for (mpz_class& x : p.x) mpz_divexact(x.get_mpz_t(), x.get_mpz_t(), g_.get_mpz_t());
  }

  Vec3Z c23_, c31_, c12_;
  mpz_class g_;
};

// ---- Lines.

// The key of the line where two planes meet, the same for every pair of planes through it: the
// primitive integer direction u with its largest component u_k positive (the first such k on a
// tie), and the line's point where coordinate k is 0, each of its two other coordinates a rational
// in lowest terms. Also k, along which the line is parametrised.
class LineKeyMaker {
 public:
  // Writes the key of the line of s and b; returns k. Parallel planes (no line) throw.
  int make(const PlaneZ& s, const PlaneZ& b, std::string& key) {
    cross(s.n, b.n, u_);
    mpz_gcd(g_.get_mpz_t(), u_[0].get_mpz_t(), u_[1].get_mpz_t());
    mpz_gcd(g_.get_mpz_t(), g_.get_mpz_t(), u_[2].get_mpz_t());
    if (g_ == 0) throw std::invalid_argument("check_exact_boundary: an edge's bound is parallel to its face's support");
    int k = 0;
    for (int j = 1; j < 3; ++j)
      if (mpz_cmpabs(u_[j].get_mpz_t(), u_[k].get_mpz_t()) > 0) k = j;
    // The point with x_k = 0: the two planes restricted to axes i, j (cyclic after k, so their
    // determinant s_i b_j - s_j b_i is (s x b)_k, before the gcd) solved by Cramer's rule.
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    det_ = u_[k];
    mpz_mul(num_[0].get_mpz_t(), b.d.get_mpz_t(), s.n[j].get_mpz_t());
    mpz_submul(num_[0].get_mpz_t(), s.d.get_mpz_t(), b.n[j].get_mpz_t());
    mpz_mul(num_[1].get_mpz_t(), s.d.get_mpz_t(), b.n[i].get_mpz_t());
    mpz_submul(num_[1].get_mpz_t(), b.d.get_mpz_t(), s.n[i].get_mpz_t());
    const bool flip = sgn(u_[k]) < 0;
    for (mpz_class& c : u_) mpz_divexact(c.get_mpz_t(), c.get_mpz_t(), g_.get_mpz_t());
    if (flip)
      for (mpz_class& c : u_) mpz_neg(c.get_mpz_t(), c.get_mpz_t());
    key.assign(1, static_cast<char>(k));
    for (const mpz_class& c : u_) append_key(key, c);
    for (mpz_class& n : num_) append_fraction(key, n);
    return k;
  }

 private:
  // n / det_ in lowest terms with a positive denominator; det_ is left as it was.
  void append_fraction(std::string& key, mpz_class& n) {
    mpz_gcd(g_.get_mpz_t(), n.get_mpz_t(), det_.get_mpz_t());
    if (sgn(det_) < 0) mpz_neg(g_.get_mpz_t(), g_.get_mpz_t());
    mpz_divexact(n.get_mpz_t(), n.get_mpz_t(), g_.get_mpz_t());
    mpz_divexact(den_.get_mpz_t(), det_.get_mpz_t(), g_.get_mpz_t());
    append_key(key, n);
    append_key(key, den_);
  }

  Vec3Z u_;
  std::array<mpz_class, 2> num_;
  mpz_class g_, det_, den_;
};

// ---- Volume.

// Six times the volume, as the sum over faces of the fan's determinants det(v0, vi, vi+1)
// (the divergence theorem). Faces with integral vertices add to one integer; the others are
// summed pairwise at the end, so that neighbouring faces, whose denominators share factors and
// whose terms along shared edges cancel, meet before the sums grow.
class VolumeSum {
 public:
  void add_face(std::span<const PointZ> v) {
    const bool integral = std::all_of(v.begin(), v.end(), [](const PointZ& p) { return p.integral(); });
    if (integral) {
      for (std::size_t i = 1; i + 1 < v.size(); ++i) {
        cross(v[i].x, v[i + 1].x, c_);
        for (int j = 0; j < 3; ++j) mpz_addmul(whole_.get_mpz_t(), v[0].x[j].get_mpz_t(), c_[j].get_mpz_t());
      }
      return;
    }
    mpq_class face = 0;
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
      cross(v[i].x, v[i + 1].x, c_);
      dot(v[0].x, c_, det_);
      mpq_class term(det_, v[i].den * v[i + 1].den);
      term.canonicalize();
      face += term;
    }
    face /= v[0].den;
    fractions_.push_back(std::move(face));
  }

  mpq_class volume() {
    while (fractions_.size() > 1) {
      std::size_t half = 0;
      for (std::size_t i = 0; i < fractions_.size(); i += 2)
        fractions_[half++] = i + 1 < fractions_.size() ? mpq_class(fractions_[i] + fractions_[i + 1]) : std::move(fractions_[i]);
      fractions_.resize(half);
    }
    mpq_class v(whole_);
    if (!fractions_.empty()) v += fractions_[0];
    v /= 6;
    v.canonicalize();
    return v;
  }

 private:
  mpz_class whole_ = 0, det_;
  Vec3Z c_;
  std::vector<mpq_class> fractions_;
};

// ---- The boundary check.

// One pass over the faces: each face's planes converted once, each vertex solved once and
// interned by its exact coordinates, each edge's line interned by its key; an edge from vertex P
// to vertex Q on line L is the chain Q - P, recorded as the events (L, P, +1) and (L, Q, -1).
// A line's coverage is the running sum of its events in the line's order, so it is zero
// everywhere exactly when every (line, vertex) pair's events sum to zero; only lines where some
// do not are sorted, to count their border segments.
class BoundaryWalk {
 public:
  explicit BoundaryWalk(std::span<const PlanePolygon> faces) : faces_(faces) {}

  ExactBoundaryCheck run() {
    ExactBoundaryCheck out;
    out.faces = faces_.size();
    reserve();
    for (std::uint32_t f = 0; f < faces_.size(); ++f) out.edges += walk_face(f);
    out.vertices = vertex_ids_.size();
    out.lines = line_axis_.size();
    out.border_segments = border_segments();
    const mpq_class v = volume_.volume();
    out.volume = canonical_text(v);
    out.volume_double = v.get_d();
    return out;
  }

 private:
  struct Event {
    std::uint64_t line_vertex;  // line << 32 | vertex
    int weight;
  };

  // A closed surface has about as many vertices and lines as faces (Euler: V - E + F = 2 with
  // E = 3F/2 for triangles, 2F for quadrilaterals), so the maps are sized once.
  void reserve() {
    std::size_t edges = 0;
    for (const PlanePolygon& face : faces_) edges += face.size();
    events_.reserve(2 * edges);
    vertex_ids_.reserve(faces_.size());
    line_ids_.reserve(faces_.size());
    vertex_origin_.reserve(faces_.size());
  }

  std::size_t walk_face(std::uint32_t f) {
    const PlanePolygon& face = faces_[f];
    const std::size_t n = face.size();
    if (n < 3) throw std::invalid_argument("check_exact_boundary: a face with fewer than three bounds");
    if (planes_.size() < n) {
      planes_.resize(n);
      points_.resize(n);
      ids_.resize(n);
    }
    set_plane(support_, face.support);
    for (std::size_t i = 0; i < n; ++i) set_plane(planes_[i], face.bounds[i]);
    for (std::size_t i = 0; i < n; ++i) {
      solver_.solve(support_, planes_[i], planes_[(i + 1) % n], points_[i]);
      ids_[i] = vertex_id(points_[i], f, static_cast<std::uint32_t>(i));
    }
    for (std::size_t i = 0; i < n; ++i) {  // edge i: on bounds[i], from vertex i - 1 to vertex i
      const std::uint64_t line = line_id(planes_[i]);
      events_.push_back({line << 32 | ids_[(i + n - 1) % n], +1});
      events_.push_back({line << 32 | ids_[i], -1});
    }
    volume_.add_face(std::span<const PointZ>(points_.data(), n));
    return n;
  }

  std::uint32_t vertex_id(const PointZ& p, std::uint32_t face, std::uint32_t index) {
    key_.clear();
    for (const mpz_class& x : p.x) append_key(key_, x);
    append_key(key_, p.den);
    const auto [it, fresh] = vertex_ids_.try_emplace(key_, static_cast<std::uint32_t>(vertex_origin_.size()));
    if (fresh) vertex_origin_.emplace_back(face, index);
    return it->second;
  }

  std::uint32_t line_id(const PlaneZ& bound) {
    const int axis = lines_.make(support_, bound, key_);
    const auto [it, fresh] = line_ids_.try_emplace(key_, static_cast<std::uint32_t>(line_axis_.size()));
    if (fresh) line_axis_.push_back(static_cast<std::uint8_t>(axis));
    return it->second;
  }

  // Sums each (line, vertex) pair's events; lines with a non-zero sum are walked in order.
  std::uint64_t border_segments() {
    std::sort(events_.begin(), events_.end(), [](const Event& a, const Event& b) { return a.line_vertex < b.line_vertex; });
    std::uint64_t segments = 0;
    std::vector<std::pair<std::uint32_t, int>> open;  // (vertex, weight) of the current line
    for (std::size_t i = 0; i < events_.size();) {
      const std::uint64_t line = events_[i].line_vertex >> 32;
      open.clear();
      while (i < events_.size() && events_[i].line_vertex >> 32 == line) {
        const std::uint64_t key = events_[i].line_vertex;
        int sum = 0;
        for (; i < events_.size() && events_[i].line_vertex == key; ++i) sum += events_[i].weight;
        if (sum != 0) open.emplace_back(static_cast<std::uint32_t>(key), sum);
      }
      if (!open.empty()) segments += segments_on(line_axis_[line], open);
    }
    return segments;
  }

  // The border segments of one line: its non-zero points in the line's order (coordinate `axis`,
  // increasing along the line's direction since that component is positive), coverage summed.
  std::uint64_t segments_on(int axis, std::span<const std::pair<std::uint32_t, int>> points) {
    std::vector<std::pair<mpq_class, int>> ordered;
    for (const auto& [vertex, weight] : points) {
      const PointZ p = vertex_point(vertex);
      mpq_class t(p.x[axis], p.den);
      t.canonicalize();
      ordered.emplace_back(std::move(t), weight);
    }
    std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::uint64_t segments = 0;
    int coverage = 0;
    for (const auto& [t, weight] : ordered) {
      if (coverage == 0) ++segments;
      coverage += weight;
    }
    return segments;
  }

  // A vertex solved again from the face where it was first seen (only for lines that do not close).
  PointZ vertex_point(std::uint32_t vertex) {
    const auto [f, i] = vertex_origin_[vertex];
    const PlanePolygon& face = faces_[f];
    PlaneZ s, p, q;
    set_plane(s, face.support);
    set_plane(p, face.before(i));
    set_plane(q, face.after(i));
    PointZ out;
    solver_.solve(s, p, q, out);
    return out;
  }

  std::span<const PlanePolygon> faces_;
  PlaneZ support_;
  std::vector<PlaneZ> planes_;
  std::vector<PointZ> points_;
  std::vector<std::uint32_t> ids_;
  VertexSolver solver_;
  LineKeyMaker lines_;
  std::string key_;
  std::unordered_map<std::string, std::uint32_t> vertex_ids_, line_ids_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> vertex_origin_;  // (face, vertex index)
  std::vector<std::uint8_t> line_axis_;
  std::vector<Event> events_;
  VolumeSum volume_;
};

// ---- Meshes of grid points.

void check_grid_point(const GridPoint& p) {
  constexpr std::int64_t limit = std::int64_t{1} << kGridBits;
  for (const std::int64_t c : {p.x, p.y, p.z})
    if (c <= -limit || c >= limit) throw std::invalid_argument("a mesh coordinate is outside the grid (|c| >= 2^kGridBits)");
}

// det(p, q, r) = p . (q x r): |coordinates| < 2^40 make each product of three below 2^120 and
// the sum of six below 2^123, inside Int128.
Int128 det3(const GridPoint& p, const GridPoint& q, const GridPoint& r) {
  const Int128 cx = Int128{q.y} * r.z - Int128{q.z} * r.y;
  const Int128 cy = Int128{q.z} * r.x - Int128{q.x} * r.z;
  const Int128 cz = Int128{q.x} * r.y - Int128{q.y} * r.x;
  return p.x * cx + p.y * cy + p.z * cz;
}

using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using EpeckMesh = CGAL::Surface_mesh<Epeck::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

// Grid coordinates below 2^40 are exact doubles, so the points are exactly the grid points.
EpeckMesh epeck_mesh(std::span<const std::vector<GridPoint>> polys, const char* which) {
  std::vector<Epeck::Point_3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::map<std::array<std::int64_t, 3>, std::size_t> index;
  const auto id = [&](const GridPoint& p) {
    check_grid_point(p);
    const auto [it, fresh] = index.try_emplace({p.x, p.y, p.z}, points.size());
    if (fresh) points.emplace_back(static_cast<double>(p.x), static_cast<double>(p.y), static_cast<double>(p.z));
    return it->second;
  };
  for (const std::vector<GridPoint>& poly : polys)
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) triangles.push_back({id(poly[0]), id(poly[i]), id(poly[i + 1])});
  if (!PMP::is_polygon_soup_a_polygon_mesh(triangles))
    throw std::runtime_error(std::string("exact_corefine: operand ") + which + " is not a polygon mesh");
  EpeckMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, triangles, mesh);
  if (!CGAL::is_closed(mesh)) throw std::runtime_error(std::string("exact_corefine: operand ") + which + " is not closed");
  return mesh;
}

EpeckMesh corefine_one(EpeckMesh x, EpeckMesh y, SetOp op) {
  EpeckMesh out;
  bool ok = false;
  try {
    switch (op) {
      case SetOp::Union: ok = PMP::corefine_and_compute_union(x, y, out); break;
      case SetOp::Intersection: ok = PMP::corefine_and_compute_intersection(x, y, out); break;
      default: ok = PMP::corefine_and_compute_difference(x, y, out); break;
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("CGAL corefinement failed: ") + e.what());
  }
  if (!ok) throw std::runtime_error("CGAL corefinement failed (self-intersecting or non-manifold operands)");
  return out;
}

// A leaf of convex polygons with double coordinates, each taken exactly (cgal_mesh.h).
EpeckMesh epeck_mesh(std::span<const Polygon> polys) {
  EpeckMesh mesh = cgal_mesh_of<Epeck::Point_3>(polys);
  if (!CGAL::is_closed(mesh)) throw std::runtime_error("a leaf is not closed");
  return mesh;
}

// One operand of a program: nullopt is the empty solid.
using ProgramOperand = std::optional<EpeckMesh>;

ProgramOperand combine(ProgramOperand x, ProgramOperand y, StepKind kind) {
  if (kind == StepKind::Union) {
    if (!x) return y;
    if (!y) return x;
    return corefine_one(std::move(*x), std::move(*y), SetOp::Union);
  }
  if (!x || !y) return kind == StepKind::Difference ? x : std::nullopt;
  return corefine_one(std::move(*x), std::move(*y), kind == StepKind::Intersection ? SetOp::Intersection : SetOp::Difference);
}

// Fewer than four points off one plane have no 3D hull: the empty solid, as OpenSCAD gives none.
ProgramOperand hull(std::span<ProgramOperand> operands) {
  std::vector<Epeck::Point_3> points;
  for (const ProgramOperand& m : operands)
    if (m)
      for (const auto v : m->vertices()) points.push_back(m->point(v));
  if (points.size() < 4) return std::nullopt;
  EpeckMesh out;
  CGAL::convex_hull_3(points.begin(), points.end(), out);
  if (out.number_of_faces() < 4 || PMP::volume(out) == 0) return std::nullopt;  // coplanar points: no solid
  return out;
}


}  // namespace

ExactBoundaryCheck check_exact_boundary(std::span<const PlanePolygon> faces) { return BoundaryWalk(faces).run(); }

std::string exact_mesh_volume(std::span<const std::vector<GridPoint>> polys) {
  mpz_class six = 0;
  Int128 partial = 0;  // flushed before it could overflow: below 2^125 + 2^123 after any addition
  for (const std::vector<GridPoint>& poly : polys) {
    for (const GridPoint& p : poly) check_grid_point(p);
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
      partial += det3(poly[0], poly[i], poly[i + 1]);
      if (!below_bits(partial, 125)) {
        mpz_class m;
        set_int128(m, partial);
        six += m;
        partial = 0;
      }
    }
  }
  mpz_class m;
  set_int128(m, partial);
  six += m;
  return canonical_text(mpq_class(six, 6));
}

ExactCorefine exact_corefine(std::span<const std::vector<GridPoint>> a, std::span<const std::vector<GridPoint>> b,
                             SetOp op) {
  const auto start = std::chrono::steady_clock::now();
  const EpeckMesh ma = epeck_mesh(a, "a"), mb = epeck_mesh(b, "b");
  Epeck::FT volume = 0;
  ExactCorefine out;
  if (op == SetOp::SymmetricDifference) {
    const EpeckMesh d1 = corefine_one(ma, mb, SetOp::Difference), d2 = corefine_one(mb, ma, SetOp::Difference);
    volume = PMP::volume(d1) + PMP::volume(d2);
    out.triangles = d1.number_of_faces() + d2.number_of_faces();
  } else {
    const EpeckMesh r = corefine_one(ma, mb, op);
    volume = PMP::volume(r);
    out.triangles = r.number_of_faces();
  }
  mpq_class v = to_mpq(CGAL::exact(volume));
  v.canonicalize();
  out.volume = v.get_str();
  out.volume_double = v.get_d();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {

// Left to right, or as a balanced tree (exact_measure.h); `operations` counts the binary ones done.
ProgramOperand fold(std::vector<ProgramOperand> ops, StepKind kind, FoldOrder order, std::uint64_t& operations) {
  if (ops.empty()) return std::nullopt;
  if (order == FoldOrder::Balanced && kind == StepKind::Difference && ops.size() > 2) {
    std::vector<ProgramOperand> rest(std::make_move_iterator(ops.begin() + 1), std::make_move_iterator(ops.end()));
    ProgramOperand cut = fold(std::move(rest), StepKind::Union, order, operations);
    operations += ops[0] && cut;
    return combine(std::move(ops[0]), std::move(cut), kind);
  }
  if (order == FoldOrder::Balanced && kind != StepKind::Difference) {
    while (ops.size() > 1) {
      std::vector<ProgramOperand> next;
      for (std::size_t i = 0; i + 1 < ops.size(); i += 2) {
        operations += ops[i] && ops[i + 1];
        next.push_back(combine(std::move(ops[i]), std::move(ops[i + 1]), kind));
      }
      if (ops.size() % 2 == 1) next.push_back(std::move(ops.back()));
      ops = std::move(next);
    }
    return std::move(ops[0]);
  }
  ProgramOperand result = std::move(ops[0]);
  for (std::size_t i = 1; i < ops.size(); ++i) {
    operations += result && ops[i];
    result = combine(std::move(result), std::move(ops[i]), kind);
  }
  return result;
}

}  // namespace

ExactProgramVolume exact_corefine_program(std::span<const std::vector<Polygon>> leaves, std::span<const Step> steps, FoldOrder order,
                                          const std::vector<std::vector<Polygon>>* hulls) {
  std::size_t next_hull = 0;
  const auto start = std::chrono::steady_clock::now();
  ExactProgramVolume out;
  std::vector<ProgramOperand> stack;
  try {
    for (const Step& step : steps) {
      if (step.kind == StepKind::Leaf) {
        stack.emplace_back(epeck_mesh(leaves[step.count]));
        continue;
      }
      if (step.count > stack.size()) throw std::logic_error("exact_corefine_program: a step pops more operands than pushed");
      const auto first = stack.end() - step.count;
      ProgramOperand result;
      if (step.kind == StepKind::Hull && hulls) {
        const std::vector<Polygon>& given = (*hulls)[next_hull++];
        if (!given.empty()) result = epeck_mesh(given);
      } else if (step.kind == StepKind::Hull) {
        result = hull(std::span<ProgramOperand>(&*first, step.count));
        ++out.operations;
      } else {
        result = fold(std::vector<ProgramOperand>(std::make_move_iterator(first), std::make_move_iterator(stack.end())),
                      step.kind, order, out.operations);
      }
      stack.erase(first, stack.end());
      stack.push_back(std::move(result));
    }
    if (stack.size() != 1) throw std::logic_error("exact_corefine_program: the program leaves " + std::to_string(stack.size()) + " operands");
    mpq_class v = 0;
    if (stack[0]) {
      v = to_mpq(CGAL::exact(PMP::volume(*stack[0])));
      out.triangles = stack[0]->number_of_faces();
    }
    v.canonicalize();
    out.volume = v.get_str();
    out.volume_double = v.get_d();
  } catch (const std::runtime_error& e) {
    out.error = e.what();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace bsp
