// OpenSCAD 2021.01's primitives and extrusions (see openscad_shapes.h).
//
// Notation:
//   n        fragments of a full circle (get_fragments_from_r)
//   deg      angles in degrees, as OpenSCAD keeps them; sin_degrees / cos_degrees are its functions
//   h1, h2   bottom and top height of an extrusion
//   level k  the k-th of the slices+1 copies of a ring in linear_extrude (k = 0 bottom, slices top)
//   T_k      the 2x2 map of level k: diag(scale_k) * R(-rot_k), applied as OpenSCAD's Eigen does
//   prev/curr  consecutive ring vertices; suffix 1 / 2 = on the lower / upper level of a slice
//   "insert" OpenSCAD's PolySet::insert_vertex prepends, so a face built by inserting a, b, c is
//            the face [c, b, a]; the faces below are written in their final order.
#include "csg/openscad_shapes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

#include "common/errors.h"

namespace bsp::csg {

namespace {

// OpenSCAD 2021.01, grid.h: GRID_FINE = 2^-20 (a radius below it gets 3 fragments).
constexpr double kGridFine = 0.00000095367431640625;
// OpenSCAD 2021.01, degree_trig.h.
constexpr double kDeg2Rad = 0.017453292519943295769;
constexpr double kSqrt3_4 = 0.86602540378443859659;
constexpr double kSqrt1_2 = 0.70710678118654752440;
// OpenSCAD 2021.01, primitives.cc: F_MINIMUM, the smallest $fs / $fa a primitive accepts.
constexpr double kFMinimum = 0.01;
// OpenSCAD 2021.01, degree_trig.cc: beyond this the reduction to [0, 360) loses all precision.
constexpr double kTrigHuge = double(1L << 26) * 360.0 * double(1L << 26);

// Reduces deg to [0, 360) as degree_trig.cc does; NaN when hopeless (so the result is NaN too).
double reduce_degrees(double deg) {
  if (deg < 360.0 && deg >= 0.0) return deg;
  if (!(deg < kTrigHuge && deg > -kTrigHuge)) return std::numeric_limits<double>::quiet_NaN();
  return deg - 360.0 * std::floor(deg / 360.0);
}

// A primitive's resolution after OpenSCAD's instantiate clamps $fs and $fa (primitives.cc).
Resolution clamped(Resolution res) {
  if (res.fs < kFMinimum) res.fs = kFMinimum;
  if (res.fa < kFMinimum) res.fa = kFMinimum;
  return res;
}

// A slice count OpenSCAD would have computed as an int; refuse what cannot be one (UB there).
int checked_count(double count, const char* what) {
  if (!(count <= double(kMaxFragments))) {
    throw InputError(std::string(what) + " count " + std::to_string(count) +
                     " is not usable (over " + std::to_string(kMaxFragments) + " or undefined)");
  }
  return static_cast<int>(count);
}

// Bounded memory: an object that would have more faces than kMaxFaces is refused before it is made.
void check_faces(double faces) {
  if (!(faces <= double(kMaxFaces)))
    throw InputError("the object would have " + std::to_string(static_cast<unsigned long long>(faces)) + " faces, over " +
                     std::to_string(kMaxFaces));
}

double ring_points(const Shape2& shape) {
  double n = 0;
  for (const Ring& o : shape.rings) n += static_cast<double>(o.points.size());
  return n;
}

// Points of a circle as OpenSCAD's generate_circle and circle() make them (primitives.cc).
std::vector<Vec2> circle_points(double r, int n) {
  std::vector<Vec2> pts(n);
  for (int i = 0; i < n; ++i) {
    const double phi = (360.0 * i) / n;
    pts[i] = {r * cos_degrees(phi), r * sin_degrees(phi)};
  }
  return pts;
}

// Collects faces the way OpenSCAD's OFF export numbers a PolySet (first use, exact equality with
// -0 == 0), dropping repeated consecutive points and faces left with fewer than 3, as OpenSCAD's
// PolySet -> CGAL polyhedron conversion does (cgalutils-polyhedron.cc) before any CSG operation.
class MeshBuilder {
 public:
  void add(std::vector<Vec3> face) {
    face.erase(std::unique(face.begin(), face.end()), face.end());
    while (face.size() > 1 && face.back() == face.front()) face.pop_back();
    if (face.size() < 3) return;
    std::vector<std::uint32_t> idx;
    idx.reserve(face.size());
    for (const Vec3& p : face) idx.push_back(index(p));
    mesh_.faces.push_back(std::move(idx));
  }
  Mesh take() { return std::move(mesh_); }

 private:
  struct Hash {
    std::size_t operator()(const Vec3& p) const {
      // +0.0 folds -0 into 0 so that equal keys hash equally.
      const std::hash<double> h;
      std::size_t s = h(p.x + 0.0);
      s ^= h(p.y + 0.0) + 0x9e3779b97f4a7c15ULL + (s << 6) + (s >> 2);
      s ^= h(p.z + 0.0) + 0x9e3779b97f4a7c15ULL + (s << 6) + (s >> 2);
      return s;
    }
  };
  std::uint32_t index(const Vec3& p) {
    auto [it, fresh] = index_.try_emplace(p, static_cast<std::uint32_t>(mesh_.points.size()));
    if (fresh) mesh_.points.push_back(p);
    return it->second;
  }
  Mesh mesh_;
  std::unordered_map<Vec3, std::uint32_t, Hash> index_;
};

// A 2x2 linear map in row-major order.
struct Mat2 {
  double a, b, c, d;  // [a b; c d]
  // Applied as Eigen's Affine2d * Vector2d: each row's products summed left to right, plus the zero
  // translation (which turns -0 into 0, as OpenSCAD's vertices have it).
  Vec2 operator()(const Vec2& v) const { return {a * v.x + b * v.y + 0.0, c * v.x + d * v.y + 0.0}; }
};

// Eigen::Scaling(scale) * rotate_degrees(-rot) of add_slice / extrudePolygon (GeometryEvaluator.cc):
// each row of the rotation times that row's scale.
Mat2 scaled_rotation(const Vec2& scale, double rot) {
  const double s = sin_degrees(-rot), c = cos_degrees(-rot);
  return {scale.x * c, scale.x * -s, scale.y * s, scale.y * c};
}

Vec3 at(const Vec2& p, double z) { return {p.x, p.y, z}; }
// A cap point: OpenSCAD moves caps by a translation or an affine map, adding 0 to each coordinate.
Vec3 moved(const Vec3& p) { return {p.x + 0.0, p.y + 0.0, p.z + 0.0}; }

// OpenSCAD's sgn_vdiff: compares |v1| and |v2|, equal within 10 ppm of their mean.
int sgn_vdiff(const Vec2& v1, const Vec2& v2) {
  constexpr double ratio_threshold = 1e5;
  const double l1 = std::sqrt(v1.x * v1.x + v1.y * v1.y);
  const double l2 = std::sqrt(v2.x * v2.x + v2.y * v2.y);
  const double diff = 2 * std::fabs(l1 - l2) * ratio_threshold;
  return diff > l1 + l2 ? (l1 < l2 ? -1 : 1) : 0;
}

Vec2 operator-(const Vec2& a, const Vec2& b) { return {a.x - b.x, a.y - b.y}; }

// One level of a linear extrusion: its map, height and the parameters add_slice looks at.
struct Level {
  Vec2 scale;
  double rot = 0, z = 0;
  Mat2 map() const { return scaled_rotation(scale, rot); }
};

// Level k of `slices` as extrudePolygon computes it; the top level takes the top cap's exact
// values (OpenSCAD recomputes them as 1-(1-s)*n/n, twist*n/n, h1+(h2-h1)*n/n, which can differ from
// the cap in the last bit and leave its PolySet open there; we keep the mesh closed).
Level level(const LinearExtrude& p, double h1, double h2, unsigned k, unsigned slices) {
  if (k == slices) return {p.scale, p.twist, h2};
  const double dk = k, ds = slices;
  return {{1 - (1 - p.scale.x) * dk / ds, 1 - (1 - p.scale.y) * dk / ds}, p.twist * dk / ds,
          h1 + (h2 - h1) * dk / ds};
}

// OpenSCAD's add_slice: each ring edge between levels l1 and l2 becomes two triangles split along
// the shorter diagonal (ties by twist direction and ring sign), one when the top collapses (scale 0).
void add_slice(MeshBuilder& out, const Shape2& shape, const Level& l1, const Level& l2) {
  const Mat2 t1 = l1.map(), t2 = l2.map();
  const bool any_zero = l2.scale.x == 0 || l2.scale.y == 0;
  const bool any_non_zero = l2.scale.x != 0 || l2.scale.y != 0;
  const bool back_twist = l2.rot <= l1.rot;
  for (const Ring& o : shape.rings) {
    const std::size_t m = o.points.size();
    if (m == 0) continue;
    const bool flip = (signed_area(o) < 0) != back_twist;
    Vec2 prev1 = t1(o.points[0]), prev2 = t2(o.points[0]);
    for (std::size_t i = 1; i <= m; ++i) {
      const Vec2 curr1 = t1(o.points[i % m]), curr2 = t2(o.points[i % m]);
      const int diff_sign = sgn_vdiff(prev1 - curr2, curr1 - prev2);
      const bool splitfirst = diff_sign == -1 || (diff_sign == 0 && !flip);
      const bool second = !any_zero || (any_non_zero && !(prev2 == curr2));
      const Vec3 p1 = at(prev1, l1.z), c1 = at(curr1, l1.z), p2 = at(prev2, l2.z), c2 = at(curr2, l2.z);
      if (splitfirst != any_zero) {
        out.add({c1, c2, p1});
        if (second) out.add({p2, p1, c2});
      } else {
        out.add({c1, p2, p1});
        if (second) out.add({c1, c2, p2});
      }
      prev1 = curr1;
      prev2 = curr2;
    }
  }
}

// extrudePolygon's slice count: given, else the helix / conical helix / diagonal rule, else 1.
unsigned slice_count(const Shape2& shape, const LinearExtrude& p) {
  if (p.slices > 0) return static_cast<unsigned>(p.slices);
  const Vec2 s = p.scale;
  if (p.twist != 0.0) {
    double max_r1_sqr = 0;
    for (const Ring& o : shape.rings)
      for (const Vec2& v : o.points) max_r1_sqr = std::fmax(max_r1_sqr, v.x * v.x + v.y * v.y);
    if ((s.x == 1.0 && s.y == 1.0) || s.x != s.y) return helix_slices(max_r1_sqr, p.height, p.twist, p.res);
    return conical_helix_slices(max_r1_sqr, p.height, p.twist, s.x, p.res);
  }
  if (s.x != s.y) {
    double max_delta_sqr = 0;
    for (const Ring& o : shape.rings)
      for (const Vec2& v : o.points) {
        const double dx = v.x - v.x * s.x, dy = v.y - v.y * s.y;
        max_delta_sqr = std::fmax(max_delta_sqr, dx * dx + dy * dy);
      }
    return diagonal_slices(max_delta_sqr, p.height, p.res);
  }
  return 1;
}

// linear_extrude's parameters after linearextrude.cc's instantiate: negative scales are 0,
// a non-finite twist is 0.
LinearExtrude normalized(LinearExtrude p) {
  p.scale.x = std::max(p.scale.x, 0.0);
  p.scale.y = std::max(p.scale.y, 0.0);
  if (!std::isfinite(p.twist)) p.twist = 0;
  return p;
}

// The common body of both linear_extrude overloads; `top` is the top cap already transformed.
Mesh extrude(const Shape2& shape, const std::vector<Triangle2>& bottom, const std::vector<Triangle2>& top,
             const LinearExtrude& p) {
  const double h1 = p.center ? -p.height / 2.0 : 0.0;
  const double h2 = p.center ? +p.height / 2.0 : p.height;
  MeshBuilder out;
  auto cap = [](const Vec2& v, double z) { return moved(at(v, z)); };
  for (const Triangle2& t : bottom) out.add({cap(t[2], h1), cap(t[1], h1), cap(t[0], h1)});
  for (const Triangle2& t : top) out.add({cap(t[0], h2), cap(t[1], h2), cap(t[2], h2)});
  const unsigned slices = slice_count(shape, p);
  check_faces(2.0 * ring_points(shape) * slices + double(bottom.size() + top.size()));
  for (unsigned j = 0; j < slices; ++j) add_slice(out, shape, level(p, h1, h2, j, slices), level(p, h1, h2, j + 1, slices));
  return out.take();
}

bool has_top(const LinearExtrude& p) { return p.scale.x > 0 && p.scale.y > 0; }

// OpenSCAD's fill_ring: a ring of the profile placed at angle a (x -> radius, y -> z).
Vec3 revolve(const Vec2& v, double a) { return {v.x * sin_degrees(a), v.x * cos_degrees(a), v.y}; }


// The x range of rotate_extrude's profile, which must not straddle x = 0: OpenSCAD's running
// check (min and max start at 0), with its error message.
struct XRange {
  double min = 0, max = 0;
};
XRange one_sided_x_range(const Shape2& shape) {
  XRange x;
  for (const Ring& o : shape.rings)
    for (const Vec2& v : o.points) {
      x.min = std::fmin(x.min, v.x);
      x.max = std::fmax(x.max, v.x);
      if ((x.max - x.min) > x.max && (x.max - x.min) > std::fabs(x.min))
        throw InputError("all points for rotate_extrude() must have the same X coordinate sign (range is " +
                         std::to_string(x.min) + " -> " + std::to_string(x.max) + ")");
    }
  return x;
}

// A rotate_extrude's sweep: its angle, its n steps, and whether faces are flipped (OpenSCAD's
// flip_faces keeps them outward for either side of the axis and either sweep direction).
struct Revolution {
  double angle;
  unsigned n;
  bool flip;
  // Angle of ring k (0 first, n last) as rotatePolygon computes it; 360 starts on -x.
  double ring_angle(unsigned k) const {
    if (angle == 360) return -90 + (k % n) * 360.0 / n;
    return k == 0 ? 90.0 : 90 - k * angle / n;
  }
};

// The triangulated profile at both ends of a partial sweep. OpenSCAD rotates the end cap by a
// matrix, which can differ from its last ring in the last bit; we put it on the ring, closed.
void add_end_caps(MeshBuilder& out, const std::vector<Triangle2>& cap, const Revolution& rev) {
  const double a0 = rev.ring_angle(0), a1 = rev.ring_angle(rev.n);
  auto start = [&](const Vec2& v) { return moved(revolve(v, a0)); };
  auto end = [&](const Vec2& v) { return moved(revolve(v, a1)); };
  for (const Triangle2& t : cap) {
    if (rev.flip) out.add({start(t[0]), start(t[1]), start(t[2])});
    else out.add({start(t[2]), start(t[1]), start(t[0])});
  }
  for (const Triangle2& t : cap) {
    if (rev.flip) out.add({end(t[2]), end(t[1]), end(t[0])});
    else out.add({end(t[0]), end(t[1]), end(t[2])});
  }
}

// One profile ring swept step by step: two triangles per edge and step (OpenSCAD's fill_ring
// reverses the ring when flipping).
void add_revolved_ring(MeshBuilder& out, const Ring& o, const Revolution& rev) {
  const std::size_t m = o.points.size();
  if (m == 0) return;
  auto ring = [&](unsigned k) {
    std::vector<Vec3> r(m);
    for (std::size_t i = 0; i < m; ++i) r[i] = revolve(o.points[rev.flip ? m - 1 - i : i], rev.ring_angle(k));
    return r;
  };
  std::vector<Vec3> r0 = ring(0);
  for (unsigned j = 0; j < rev.n; ++j) {
    std::vector<Vec3> r1 = ring(j + 1);
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t i1 = (i + 1) % m;
      out.add({r0[i1], r1[i1], r0[i]});
      out.add({r1[i1], r1[i], r0[i]});
    }
    r0 = std::move(r1);
  }
}

}  // namespace

Mesh indexed(const std::vector<std::vector<Vec3>>& faces) {
  MeshBuilder out;
  for (const auto& f : faces) out.add(f);
  return out.take();
}

// OpenSCAD 2021.01, degree_trig.cc: sin_degrees, exact at 30, 45, 60, 90.
double sin_degrees(double deg) {
  double x = reduce_degrees(deg);
  if (std::isnan(x)) return x;
  const bool oppose = x >= 180.0;
  if (oppose) x -= 180.0;
  if (x > 90.0) x = 180.0 - x;
  if (x < 45.0) x = (x == 30.0) ? 0.5 : std::sin(x * kDeg2Rad);
  else if (x == 45.0) x = kSqrt1_2;
  else if (x == 60.0) x = kSqrt3_4;
  else x = std::cos((90.0 - x) * kDeg2Rad);
  return oppose ? -x : x;
}

// OpenSCAD 2021.01, degree_trig.cc: cos_degrees, exact at 30, 45, 60, 90.
double cos_degrees(double deg) {
  double x = reduce_degrees(deg);
  if (std::isnan(x)) return x;
  bool oppose = x >= 180.0;
  if (oppose) x -= 180.0;
  if (x > 90.0) {
    x = 180.0 - x;
    oppose = !oppose;
  }
  if (x > 45.0) x = (x == 60.0) ? 0.5 : std::sin((90.0 - x) * kDeg2Rad);
  else if (x == 45.0) x = kSqrt1_2;
  else if (x == 30.0) x = kSqrt3_4;
  else x = std::cos(x * kDeg2Rad);
  return oppose ? -x : x;
}

// OpenSCAD 2021.01, calc.cc: Calc::get_fragments_from_r.
int fragments(double r, const Resolution& res) {
  if (r < kGridFine || std::isinf(res.fn) || std::isnan(res.fn)) return 3;
  if (res.fn > 0.0) return checked_count(res.fn >= 3 ? res.fn : 3, "fragment");
  return checked_count(std::ceil(std::fmax(std::fmin(360.0 / res.fa, r * 2 * M_PI / res.fs), 5)), "fragment");
}

// OpenSCAD 2021.01, calc.cc: Calc::get_helix_slices (twist with scale 1 or non-uniform scale).
int helix_slices(double r_sqr, double height, double twist, const Resolution& res) {
  twist = std::fabs(twist);
  const int min_slices = std::max(checked_count(std::ceil(twist / 120.0), "slice"), 1);
  if (std::sqrt(r_sqr) < kGridFine || std::isinf(res.fn) || std::isnan(res.fn)) return min_slices;
  if (res.fn > 0.0) return std::max(checked_count(std::ceil(twist / 360.0 * res.fn), "slice"), min_slices);
  const int fa_slices = checked_count(std::ceil(twist / res.fa), "slice");
  // Helix arc length: T sqrt(r^2 + c^2), T the twist in radians, c = height / T.
  const double t = twist * kDeg2Rad, c = height / t;
  const int fs_slices = checked_count(std::ceil(t * std::sqrt(r_sqr + c * c) / res.fs), "slice");
  return std::max(std::min(fa_slices, fs_slices), min_slices);
}

// OpenSCAD 2021.01, calc.cc: Calc::get_conical_helix_slices (twist with uniform scale != 1).
int conical_helix_slices(double r_sqr, double height, double twist, double scale, const Resolution& res) {
  twist = std::fabs(twist);
  const double r = std::sqrt(r_sqr);
  const int min_slices = std::max(checked_count(std::ceil(twist / 120.0), "slice"), 1);
  if (r < kGridFine || std::isinf(res.fn) || std::isnan(res.fn)) return min_slices;
  if (res.fn > 0.0) return std::max(checked_count(std::ceil(twist * res.fn / 360), "slice"), min_slices);
  // The vertex path projects to a piece of an Archimedes spiral r = a theta between the angles
  // where the scale, extended to 0, puts it; its length with the height as the other leg.
  const double rads = twist * kDeg2Rad;
  const double angle_end = scale > 1 ? rads * scale / (scale - 1) : rads / (1 - scale);
  const double angle_start = angle_end - rads;
  const double a = r / angle_end;
  auto spiral = [a](double th) { return 0.5 * a * (th * std::sqrt(1 + th * th) + std::asinh(th)); };
  const double spiral_length = spiral(angle_end) - spiral(angle_start);
  const double total_length = std::sqrt(spiral_length * spiral_length + height * height);
  const int fs_slices = checked_count(std::ceil(total_length / res.fs), "slice");
  const int fa_slices = checked_count(std::ceil(twist / res.fa), "slice");
  return std::max(std::min(fa_slices, fs_slices), min_slices);
}

// OpenSCAD 2021.01, calc.cc: Calc::get_diagonal_slices (non-uniform scale without twist).
int diagonal_slices(double delta_sqr, double height, const Resolution& res) {
  constexpr int min_slices = 1;
  if (std::sqrt(delta_sqr) < kGridFine || std::isinf(res.fn) || std::isnan(res.fn)) return min_slices;
  if (res.fn > 0.0) return std::max(checked_count(res.fn, "slice"), min_slices);
  return std::max(checked_count(std::ceil(std::sqrt(delta_sqr + height * height) / res.fs), "slice"), min_slices);
}

// OpenSCAD 2021.01, primitives.cc: cube's six quads (top, bottom, then the four sides).
Mesh cube(const Vec3& size, bool center) {
  const double x = size.x, y = size.y, z = size.z;
  if (!(x > 0 && y > 0 && z > 0) || std::isinf(x) || std::isinf(y) || std::isinf(z)) return {};
  const double x1 = center ? -x / 2 : 0, x2 = center ? +x / 2 : x;
  const double y1 = center ? -y / 2 : 0, y2 = center ? +y / 2 : y;
  const double z1 = center ? -z / 2 : 0, z2 = center ? +z / 2 : z;
  MeshBuilder out;
  out.add({{x1, y1, z2}, {x2, y1, z2}, {x2, y2, z2}, {x1, y2, z2}});  // top
  out.add({{x1, y2, z1}, {x2, y2, z1}, {x2, y1, z1}, {x1, y1, z1}});  // bottom
  out.add({{x1, y1, z1}, {x2, y1, z1}, {x2, y1, z2}, {x1, y1, z2}});
  out.add({{x2, y1, z1}, {x2, y2, z1}, {x2, y2, z2}, {x2, y1, z2}});
  out.add({{x2, y2, z1}, {x1, y2, z1}, {x1, y2, z2}, {x2, y2, z2}});
  out.add({{x1, y2, z1}, {x1, y1, z1}, {x1, y1, z2}, {x1, y2, z2}});
  return out.take();
}

// OpenSCAD 2021.01, primitives.cc: (n+1)/2 rings at polar angles 180 (i + 1/2) / rings, joined by
// triangle strips that alternate between the rings, capped by two n-gons.
Mesh sphere(double r, const Resolution& res) {
  if (!(r > 0) || std::isinf(r)) return {};
  const int n = fragments(r, clamped(res));
  const int rings = (n + 1) / 2;
  check_faces(double(n) * rings + 2);
  std::vector<std::vector<Vec3>> ring(rings);
  for (int i = 0; i < rings; ++i) {
    const double phi = (180.0 * (i + 0.5)) / rings;
    const double z = r * cos_degrees(phi);
    for (const Vec2& p : circle_points(r * sin_degrees(phi), n)) ring[i].push_back(at(p, z));
  }
  MeshBuilder out;
  out.add(ring[0]);
  for (int i = 0; i + 1 < rings; ++i) {
    const auto &up = ring[i], &down = ring[i + 1];
    // Both rings have n points, so OpenSCAD's merge by i/n alternates: a step along the lower ring,
    // then one along the upper ring.
    for (int k = 0; k < n; ++k) {
      out.add({down[k], down[(k + 1) % n], up[k]});
      out.add({down[(k + 1) % n], up[(k + 1) % n], up[k]});
    }
  }
  out.add(std::vector<Vec3>(ring[rings - 1].rbegin(), ring[rings - 1].rend()));
  return out.take();
}

// OpenSCAD 2021.01, primitives.cc: side quads (triangles for a cone), bottom n-gon, top n-gon.
Mesh cylinder(double h, double r1, double r2, bool center, const Resolution& res) {
  if (!(h > 0) || std::isinf(h) || !(r1 >= 0) || !(r2 >= 0) || !(r1 > 0 || r2 > 0) || std::isinf(r1) ||
      std::isinf(r2))
    return {};
  const int n = fragments(std::fmax(r1, r2), clamped(res));
  const double z1 = center ? -h / 2 : 0, z2 = center ? +h / 2 : h;
  std::vector<Vec3> c1, c2;
  for (const Vec2& p : circle_points(r1, n)) c1.push_back(at(p, z1));
  for (const Vec2& p : circle_points(r2, n)) c2.push_back(at(p, z2));
  MeshBuilder out;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    if (r1 == r2) {
      out.add({c1[j], c2[j], c2[i], c1[i]});
    } else {
      if (r1 > 0) out.add({c1[j], c2[i], c1[i]});
      if (r2 > 0) out.add({c1[j], c2[j], c2[i]});
    }
  }
  if (r1 > 0) out.add(std::vector<Vec3>(c1.rbegin(), c1.rend()));
  if (r2 > 0) out.add(c2);
  return out.take();
}

double signed_area(const Ring& ring) {
  const auto& p = ring.points;
  double twice = 0;
  for (std::size_t i = 0, m = p.size(); i < m; ++i) {
    const Vec2 &a = p[i], &b = p[(i + 1) % m];
    twice += a.x * b.y - b.x * a.y;
  }
  return twice / 2;
}

double area(const Shape2& shape) {
  double sum = 0;
  for (const Ring& r : shape.rings) sum += signed_area(r);
  return sum;
}

// OpenSCAD 2021.01, primitives.cc: n points from angle 0, counter-clockwise.
Shape2 circle(double r, const Resolution& res) {
  if (!(r > 0) || std::isinf(r)) return {};
  return {{Ring{circle_points(r, fragments(r, clamped(res)))}}};
}

// OpenSCAD 2021.01, primitives.cc: (x1,y1), (x2,y1), (x2,y2), (x1,y2).
Shape2 square(const Vec2& size, bool center) {
  if (!(size.x > 0 && size.y > 0) || std::isinf(size.x) || std::isinf(size.y)) return {};
  Vec2 v1{0, 0}, v2 = size;
  if (center) {
    v1 = {v1.x - size.x / 2, v1.y - size.y / 2};
    v2 = {v2.x - size.x / 2, v2.y - size.y / 2};
  }
  return {{Ring{{v1, {v2.x, v1.y}, v2, {v1.x, v2.y}}}}};
}

// OpenSCAD 2021.01, primitives.cc: polygon's outlines before sanitizing.
Shape2 polygon(const std::vector<Vec2>& points, const std::vector<std::vector<std::size_t>>& paths) {
  Shape2 out;
  if (paths.empty()) {
    if (points.size() > 2) out.rings.push_back({points});
    return out;
  }
  for (const auto& path : paths) {
    Ring ring;
    for (std::size_t idx : path)
      if (idx < points.size()) ring.points.push_back(points[idx]);
    out.rings.push_back(std::move(ring));
  }
  return out;
}

Mesh linear_extrude(const Shape2& shape, const std::vector<Triangle2>& cap, const LinearExtrude& given) {
  const LinearExtrude p = normalized(given);
  if (!(p.height > 0) || shape.empty()) return {};
  std::vector<Triangle2> top;
  if (has_top(p)) {
    const Mat2 t = scaled_rotation(p.scale, p.twist);
    for (const Triangle2& tri : cap) top.push_back({t(tri[0]), t(tri[1]), t(tri[2])});
  }
  return extrude(shape, cap, top, p);
}

Mesh linear_extrude(const Shape2& shape, const Triangulator& triangulate, const LinearExtrude& given) {
  const LinearExtrude p = normalized(given);
  if (!(p.height > 0) || shape.empty()) return {};
  std::vector<Triangle2> top;
  if (has_top(p)) {
    const Mat2 t = scaled_rotation(p.scale, p.twist);
    Shape2 moved = shape;
    for (Ring& r : moved.rings)
      for (Vec2& v : r.points) v = t(v);
    top = triangulate(moved);
  }
  return extrude(shape, triangulate(shape), top, p);
}

// OpenSCAD 2021.01, GeometryEvaluator.cc rotatePolygon: the profile's rings revolved about z in
// `fragments * |angle| / 360` steps (x -> radius), two triangles per ring edge and step, plus the
// profile's triangulation at both ends when the angle is not 360.
Mesh rotate_extrude(const Shape2& shape, const std::vector<Triangle2>& cap, const RotateExtrude& given) {
  double angle = given.angle;
  if (!std::isfinite(angle) || angle <= -360 || angle > 360) angle = 360;  // rotateextrude.cc
  if (angle == 0 || shape.empty()) return {};
  const XRange x = one_sided_x_range(shape);
  const Revolution rev{angle, static_cast<unsigned>(std::fmax(fragments(x.max - x.min, given.res) * std::fabs(angle) / 360, 1)),
                       (x.min >= 0 && angle > 0 && angle != 360) || (x.min < 0 && (angle < 0 || angle == 360))};
  check_faces(2.0 * ring_points(shape) * rev.n + 2.0 * double(cap.size()));
  MeshBuilder out;
  if (angle != 360) add_end_caps(out, cap, rev);
  for (const Ring& o : shape.rings) add_revolved_ring(out, o, rev);
  return out.take();
}

}  // namespace bsp::csg
