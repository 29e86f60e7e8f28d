#include "validate/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "geometry/plane.h"
#include "geometry/tolerance.h"

namespace bsp {

namespace {

// Relative rounding allowed on the coplanar bound: hit points computed in double carry errors of
// ~1e-9 plane_eps in the scenes built to stress this (near-degenerate), far below the bound.
constexpr double kRoundingRelative = 1e-6;
// A grown vertex moves at most this many times the growth distance (a sharp corner's miter would
// go arbitrarily far; a shorter one still covers the corner's edges a little less near the tip).
constexpr double kMiterLimit = 8.0;
// Rays start this many diagonals before they enter the box, so the float start point cannot skip
// a hit on the box's boundary.
constexpr double kStartMargin = 1e-3;

// The intersect context extended with the output (FACTS.md: Embree passes our context pointer to
// the filter, so a struct that starts with RTCIntersectContext can carry more).
struct RecordingContext {
  RTCIntersectContext base;
  std::vector<unsigned>* prims;
};

// Records every candidate triangle and rejects it, so traversal visits the whole ray.
void record_and_reject(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<RecordingContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    ctx->prims->push_back(RTCHitN_primID(args->hit, args->N, i));
    args->valid[i] = 0;
  }
}

void check_device(RTCDevice device, const char* step) {
  const RTCError err = rtcGetDeviceError(device);
  if (err != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("Embree error ") + std::to_string(static_cast<int>(err)) + " during " + step);
}

RTCDevice new_checked_device() {
  RTCDevice device = rtcNewDevice(nullptr);
  if (!device) throw std::runtime_error("Embree: cannot create a device");
  const bool filters = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED) != 0;
  const bool culling = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_BACKFACE_CULLING_ENABLED) != 0;
  if (!filters || culling) {
    rtcReleaseDevice(device);
    throw std::runtime_error(
        "this Embree build cannot collect all hits along a ray: it needs filter functions supported "
        "(EMBREE_FILTER_FUNCTION=ON) and backface culling off (EMBREE_BACKFACE_CULLING=OFF)");
  }
  return device;
}

// Outward in-plane unit normals of a convex polygon's edges (counter-clockwise about n); zero for
// a zero-length edge.
std::vector<Vec3> edge_normals(std::span<const Vec3> v, const Vec3& n) {
  std::vector<Vec3> m(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3 c = cross(v[(i + 1) % v.size()] - v[i], n);
    const double len = length(c);
    m[i] = len > 0.0 ? c / len : Vec3{};
  }
  return m;
}

// The polygon with every edge moved outward by `grow` in its plane. A vertex goes to where its two
// moved edges meet (w·a = w·b = grow) unless that miter point lies more than kMiterLimit * grow
// away (a sharp corner); then the corner is bevelled: two points, each on one moved edge `grow`
// past the vertex, so the edge between two sharp corners of a sliver moves outward too.
std::vector<Vec3> grown(std::span<const Vec3> v, const Vec3& n, double grow) {
  const std::vector<Vec3> m = edge_normals(v, n);
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    Vec3 a = m[(i + v.size() - 1) % v.size()], b = m[i];
    if (a == Vec3{}) a = b;
    if (b == Vec3{}) b = a;
    const double cos_ab = dot(a, b);
    if (cos_ab > -1.0 + 2.0 / (kMiterLimit * kMiterLimit)) {
      out.push_back(v[i] + (a + b) * (grow / (1.0 + cos_ab)));
      continue;
    }
    // The incoming edge runs along cross(n, a), the outgoing one along cross(n, b).
    out.push_back(v[i] + (a + cross(n, a)) * grow);
    out.push_back(v[i] + (b - cross(n, b)) * grow);
  }
  return out;
}

// Where the ray enters the box, or nullopt when it misses it (slab test).
std::optional<double> box_entry(const Box& box, const Ray& ray) {
  double enter = 0.0, leave = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double o = ray.origin[a], d = ray.dir[a];
    if (d == 0.0) {
      if (o < box.lo[a] || o > box.hi[a]) return std::nullopt;
      continue;
    }
    double t0 = (box.lo[a] - o) / d, t1 = (box.hi[a] - o) / d;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
  }
  if (enter > leave) return std::nullopt;
  return enter;
}

}  // namespace

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Box box;                               // the fragments' box grown by the growth distance
  Vec3 offset;                           // subtracted from every point handed to Embree
  std::vector<Vec3> points;              // every fragment's vertices, fragment after fragment
  std::vector<std::uint32_t> first;      // fragment f's vertices: points[first[f], first[f + 1])
  std::vector<Plane> plane;              // per fragment, unit normal; n = 0 for zero area
  std::vector<Vec3> center;              // per fragment, its vertex average
  std::vector<double> reach;             // per fragment, its farthest vertex from `center`
  std::vector<std::uint32_t> fragment;   // per Embree triangle (primID)
  double eps = 0.0;                      // plane_eps of the fragments
  double inside_slack = 0.0;             // kInsideEps * eps

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void store(std::span<const Polygon> polys);
  void build(double grow);
  std::vector<unsigned> candidates(const Ray& ray) const;
  std::optional<Hit> exact_hit(const Ray& ray, std::uint32_t f) const;
  std::vector<Hit> hits(const Ray& ray) const;

  std::span<const Vec3> verts(std::uint32_t f) const { return {points.data() + first[f], first[f + 1] - first[f]}; }
  double inside_distance(std::uint32_t f, const Vec3& x) const;
  bool coplanar_at(const Ray& ray, const Hit& a, const Hit& b) const;
  bool touches_at(std::uint32_t f, const Vec3& xf, std::uint32_t g, const Vec3& xg, double radius) const;
};

void EmbreeScene::Impl::store(std::span<const Polygon> polys) {
  for (const auto& p : polys) {
    first.push_back(static_cast<std::uint32_t>(points.size()));
    for (const auto& v : p.verts) points.push_back(v.p);
    const auto support = p.verts.size() >= 3 ? supporting_plane(p) : std::nullopt;
    plane.push_back(support.value_or(Plane{}));
    const Vec3 c = p.verts.empty() ? Vec3{} : centroid(p);
    double r = 0.0;
    for (const auto& v : p.verts) r = std::max(r, length(v.p - c));
    center.push_back(c);
    reach.push_back(r);
  }
  first.push_back(static_cast<std::uint32_t>(points.size()));
  for (const Vec3& p : points) box.add(p);
}

void EmbreeScene::Impl::build(double grow) {
  offset = box.empty() ? Vec3{} : box.center();
  std::vector<Vec3> corners;
  for (std::uint32_t f = 0; f + 1 < first.size(); ++f) {
    if (plane[f].n == Vec3{}) continue;
    const std::span<const Vec3> v(points.data() + first[f], first[f + 1] - first[f]);
    const std::vector<Vec3> g = grown(v, plane[f].n, grow);
    for (std::size_t i = 1; i + 1 < g.size(); ++i) {  // fan from vertex 0
      corners.insert(corners.end(), {g[0], g[i], g[i + 1]});
      fragment.push_back(f);
    }
  }
  scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  if (!fragment.empty()) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), corners.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), fragment.size()));
    check_device(device, "buffer allocation");
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const Vec3 p = corners[i] - offset;
      vb[3 * i] = static_cast<float>(p.x);
      vb[3 * i + 1] = static_cast<float>(p.y);
      vb[3 * i + 2] = static_cast<float>(p.z);
      ib[i] = static_cast<unsigned>(i);
    }
    rtcSetGeometryIntersectFilterFunction(geom, record_and_reject);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(scene);
  check_device(device, "scene build");
}

// Embree's candidate triangles along the ray, from just before it enters the box.
std::vector<unsigned> EmbreeScene::Impl::candidates(const Ray& ray) const {
  std::vector<unsigned> prims;
  const auto entry = box_entry(box, ray);
  if (!entry || fragment.empty()) return prims;
  const double start = std::max(0.0, *entry - kStartMargin * box.diagonal() / length(ray.dir));
  RecordingContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.prims = &prims;
  RTCRayHit rh{};
  const Vec3 o = ray.origin + ray.dir * start - offset;
  rh.ray.org_x = static_cast<float>(o.x);
  rh.ray.org_y = static_cast<float>(o.y);
  rh.ray.org_z = static_cast<float>(o.z);
  rh.ray.dir_x = static_cast<float>(ray.dir.x);
  rh.ray.dir_y = static_cast<float>(ray.dir.y);
  rh.ray.dir_z = static_cast<float>(ray.dir.z);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &ctx.base, &rh);
  return prims;
}

double distance_to_segment(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 e = b - a;
  const double len2 = dot(e, e);
  const double s = len2 > 0.0 ? std::clamp(dot(x - a, e) / len2, 0.0, 1.0) : 0.0;
  return length(x - (a + e * s));
}

// Signed distance of x (in f's plane) from f's boundary, positive inside: inside, the least
// distance to an edge's line; outside, the distance to the nearest edge segment (not its line,
// which beside a sharp corner passes far closer than the polygon does). Zero-length edges do not
// count.
double EmbreeScene::Impl::inside_distance(std::uint32_t f, const Vec3& x) const {
  const std::span<const Vec3> v = verts(f);
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3 e = v[(i + 1) % v.size()] - v[i];
    const double len = length(e);
    if (len > 0.0) least = std::min(least, dot(cross(e, x - v[i]), plane[f].n) / len);
  }
  if (least >= 0.0) return least;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) nearest = std::min(nearest, distance_to_segment(x, v[i], v[(i + 1) % v.size()]));
  return -nearest;
}

// The double-precision decision (header, step 2).
std::optional<Hit> EmbreeScene::Impl::exact_hit(const Ray& ray, std::uint32_t f) const {
  const Plane& p = plane[f];
  const double denom = dot(p.n, ray.dir);
  if (denom == 0.0) return std::nullopt;
  const double t = -p.distance(ray.origin) / denom;
  if (!(t >= 0.0)) return std::nullopt;
  const Vec3 x = ray.origin + ray.dir * t;
  // Farther than reach + slack from the centre is farther than the slack from the polygon: the
  // same answer as inside_distance, without walking the edges (most of Embree's candidates on
  // scenes with features far below float resolution, such as near-degenerate).
  if (length(x - center[f]) > reach[f] + inside_slack) return std::nullopt;
  const double inside = inside_distance(f, x);
  if (inside < -inside_slack) return std::nullopt;
  const double grazing = std::min(length(ray.dir) / std::abs(denom), kMaxGrazingScale);
  return Hit{{t, f}, inside_slack + eps * grazing, inside};
}

// Whether, where the ray meets them, the two hits lie within 2 eps of each other across one of the
// fragments' planes (the sine floored by the grazing cap): both within eps of one plane, on which a
// BSP may file both.
bool EmbreeScene::Impl::coplanar_at(const Ray& ray, const Hit& a, const Hit& b) const {
  const double gap = std::abs(b.t - a.t) * length(ray.dir);
  const auto within = [&](std::uint32_t f) {
    const double sine = std::abs(dot(plane[f].n, ray.dir)) / length(ray.dir);
    return gap * std::max(sine, 1.0 / kMaxGrazingScale) <= 2.0 * eps * (1.0 + kRoundingRelative);
  };
  return within(a.fragment) || within(b.fragment);
}

// Whether some edge of f passes within `radius` of xf at a point c that lies within eps of g's
// plane, inside g up to `radius`, and within `radius` of xg: the ray meets f and g where they touch.
bool EmbreeScene::Impl::touches_at(std::uint32_t f, const Vec3& xf, std::uint32_t g, const Vec3& xg,
                                   double radius) const {
  const std::span<const Vec3> v = verts(f);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3& a = v[i];
    const Vec3 e = v[(i + 1) % v.size()] - a;
    const double len2 = dot(e, e);
    const Vec3 c = a + e * (len2 > 0.0 ? std::clamp(dot(xf - a, e) / len2, 0.0, 1.0) : 0.0);
    if (length(xf - c) <= radius && length(xg - c) <= radius && std::abs(plane[g].distance(c)) <= eps &&
        inside_distance(g, c) >= -radius)
      return true;
  }
  return false;
}

std::vector<Hit> EmbreeScene::Impl::hits(const Ray& ray) const {
  std::vector<unsigned> prims = candidates(ray);
  std::vector<std::uint32_t> frags;
  frags.reserve(prims.size());
  for (unsigned prim : prims) frags.push_back(fragment[prim]);
  std::sort(frags.begin(), frags.end());
  frags.erase(std::unique(frags.begin(), frags.end()), frags.end());
  std::vector<Hit> out;
  for (std::uint32_t f : frags)
    if (const auto hit = exact_hit(ray, f)) out.push_back(*hit);
  std::sort(out.begin(), out.end(), [](const Hit& a, const Hit& b) { return a.t != b.t ? a.t < b.t : a.fragment < b.fragment; });
  return out;
}

EmbreeScene::EmbreeScene(std::span<const Polygon> fragments, std::optional<double> plane_eps)
    : impl_(std::make_unique<Impl>()) {
  impl_->device = new_checked_device();
  impl_->store(fragments);
  const double diagonal = impl_->box.diagonal();
  const double grow = kGrowRelative * diagonal;
  impl_->eps = plane_eps.value_or(Tolerance::for_extent(diagonal).plane_eps);
  impl_->inside_slack = kInsideEps * impl_->eps;
  if (!impl_->box.empty()) impl_->box = {impl_->box.lo - Vec3{grow, grow, grow}, impl_->box.hi + Vec3{grow, grow, grow}};
  impl_->build(grow);
}

EmbreeScene::~EmbreeScene() = default;
EmbreeScene::EmbreeScene(EmbreeScene&&) noexcept = default;
EmbreeScene& EmbreeScene::operator=(EmbreeScene&&) noexcept = default;

std::vector<Hit> EmbreeScene::all_hits(const Ray& ray) const { return impl_->hits(ray); }

std::optional<Hit> EmbreeScene::first_hit(const Ray& ray) const {
  const std::vector<Hit> hits = impl_->hits(ray);
  if (hits.empty()) return std::nullopt;
  return hits.front();
}

std::optional<Hit> EmbreeScene::first_hit_exhaustive(const Ray& ray) const {
  std::optional<Hit> best;
  for (std::uint32_t f = 0; f < fragment_count(); ++f) {
    const auto h = hit(ray, f);
    if (h && (!best || h->t < best->t)) best = h;
  }
  return best;
}

std::optional<Hit> EmbreeScene::hit(const Ray& ray, std::uint32_t fragment) const {
  if (impl_->plane[fragment].n == Vec3{}) return std::nullopt;
  return impl_->exact_hit(ray, fragment);
}

// The edge reason needs one hit within the pair's radius of its fragment's boundary, so most pairs
// skip its edge walk.
TieReason EmbreeScene::tie_reason(const Ray& ray, const Hit& a, const Hit& b) const {
  const double radius = a.radius + b.radius;
  const Vec3 xa = ray.origin + ray.dir * a.t, xb = ray.origin + ray.dir * b.t;
  if (length(xa - xb) <= 2.0 * radius && (a.inside <= radius || b.inside <= radius) &&
      (impl_->touches_at(a.fragment, xa, b.fragment, xb, radius) ||
       impl_->touches_at(b.fragment, xb, a.fragment, xa, radius)))
    return TieReason::Edge;
  if (impl_->coplanar_at(ray, a, b)) return TieReason::Coplanar;
  if (a.inside < 0.0 || b.inside < 0.0) return TieReason::Boundary;
  return TieReason::None;
}

bool EmbreeScene::overlap_nearby(const Hit& a, const Hit& b) const {
  if ((a.inside < 0.0) == (b.inside < 0.0)) return false;
  const Hit& out = a.inside < 0.0 ? a : b;
  const Hit& other = a.inside < 0.0 ? b : a;
  if (!(out.t > 0.0)) return false;
  const double grazing = (other.radius - impl_->inside_slack) / impl_->eps;
  if (grazing >= kMaxGrazingScale) return false;  // the sine is only bounded there, not known
  const double moved = -out.inside * (other.t / out.t) * grazing;
  return other.inside > moved + impl_->inside_slack;
}

double EmbreeScene::plane_eps() const { return impl_->eps; }
std::size_t EmbreeScene::fragment_count() const { return impl_->first.size() - 1; }

}  // namespace bsp
