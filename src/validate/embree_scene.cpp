#include "validate/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

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

// Rays per Embree packet: rtcIntersect16, the widest packet (AVX-512 traces it natively; Embree
// splits it on narrower CPUs). The rays of a batch point nearly the same way (order_check.cpp).
constexpr std::size_t kPacket = 16;

// The intersect context extended with the output (Embree passes our context pointer to the
// filter, so a struct that starts with RTCIntersectContext can carry more).
struct RecordingContext {
  RTCIntersectContext base;
  std::vector<std::uint64_t>* keys;
};

// Records every candidate as (ray id << 32 | triangle) and rejects it, so traversal visits every
// ray to its end. Nothing else happens here: the filter runs once per candidate.
void record_and_reject(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<RecordingContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    ctx->keys->push_back((std::uint64_t{RTCRayN_id(args->ray, args->N, i)} << 32) |
                         RTCHitN_primID(args->hit, args->N, i));
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
  std::vector<double> near2;             // per fragment, (reach + inside_slack)^2
  std::vector<Vec3> inward;              // per vertex, the unit in-plane normal of the edge it starts, pointing inside; 0 for a zero-length edge
  std::vector<std::uint32_t> fragment;   // per Embree triangle (primID)
  double eps = 0.0;                      // plane_eps of the fragments
  double inside_slack = 0.0;             // kInsideEps * eps

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void store(std::span<const Polygon> polys);
  void build(double grow);
  void propose(std::span<const Ray> rays, std::size_t base, std::vector<std::uint64_t>& keys) const;
  std::optional<Hit> exact_hit(const Ray& ray, double dir_length, std::uint32_t f) const;
  void hits(std::span<const Ray> rays, HitBatch& out) const;

  std::span<const Vec3> verts(std::uint32_t f) const { return {points.data() + first[f], first[f + 1] - first[f]}; }
  double inside_distance(std::uint32_t f, const Vec3& x) const;
  bool coplanar_at(double gap, const Hit& a, const Hit& b) const;
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
    for (std::size_t i = 0; i < p.verts.size(); ++i) {
      const Vec3 e = p.verts[(i + 1) % p.verts.size()].p - p.verts[i].p;
      const double len = length(e);
      inward.push_back(len > 0.0 ? cross(plane.back().n, e) / len : Vec3{});
    }
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

// Embree's candidate triangles along rays[base, base + kPacket), appended to `keys` as
// (ray index << 32 | triangle); each ray starts just before it enters the box.
void EmbreeScene::Impl::propose(std::span<const Ray> rays, std::size_t base,
                                std::vector<std::uint64_t>& keys) const {
  RecordingContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.base.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  ctx.keys = &keys;
  RTCRayHit16 rh{};
  alignas(64) int valid[kPacket] = {};
  bool any = false;
  for (std::size_t lane = 0; lane < kPacket && base + lane < rays.size(); ++lane) {
    const Ray& ray = rays[base + lane];
    const auto entry = box_entry(box, ray);
    if (!entry) continue;
    const double start = std::max(0.0, *entry - kStartMargin * box.diagonal() / length(ray.dir));
    const Vec3 o = ray.origin + ray.dir * start - offset;
    rh.ray.org_x[lane] = static_cast<float>(o.x);
    rh.ray.org_y[lane] = static_cast<float>(o.y);
    rh.ray.org_z[lane] = static_cast<float>(o.z);
    rh.ray.dir_x[lane] = static_cast<float>(ray.dir.x);
    rh.ray.dir_y[lane] = static_cast<float>(ray.dir.y);
    rh.ray.dir_z[lane] = static_cast<float>(ray.dir.z);
    rh.ray.tfar[lane] = std::numeric_limits<float>::infinity();
    rh.ray.mask[lane] = 0xffffffffu;
    rh.ray.id[lane] = static_cast<unsigned>(base + lane);
    rh.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
    valid[lane] = -1;
    any = true;
  }
  if (any) rtcIntersect16(valid, scene, &ctx.base, &rh);
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
  const Vec3* m = inward.data() + first[f];
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i)
    if (m[i] != Vec3{}) least = std::min(least, dot(m[i], x - v[i]));
  if (least >= 0.0) return least;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) nearest = std::min(nearest, distance_to_segment(x, v[i], v[(i + 1) % v.size()]));
  return -nearest;
}

// The double-precision decision (header, step 2).
std::optional<Hit> EmbreeScene::Impl::exact_hit(const Ray& ray, double dir_length, std::uint32_t f) const {
  const Plane& p = plane[f];
  const double denom = dot(p.n, ray.dir);
  if (denom == 0.0) return std::nullopt;
  const double t = -p.distance(ray.origin) / denom;
  if (!(t >= 0.0)) return std::nullopt;
  const Vec3 x = ray.origin + ray.dir * t;
  // Farther than reach + slack from the centre is farther than the slack from the polygon: the
  // same answer as inside_distance, without walking the edges (most of Embree's candidates on
  // scenes with features far below float resolution, such as near-degenerate).
  const Vec3 from_center = x - center[f];
  if (dot(from_center, from_center) > near2[f]) return std::nullopt;
  const double inside = inside_distance(f, x);
  if (inside < -inside_slack) return std::nullopt;
  const double grazing = std::min(dir_length / std::abs(denom), kMaxGrazingScale);
  return Hit{{t, f}, t * dir_length, inside_slack + eps * grazing, inside, grazing};
}

// Whether, where the ray meets them, the two hits lie within 2 eps of each other across one of the
// fragments' planes: the gap along the ray times the sine (floored by the grazing cap), that is
// divided by `grazing`. Both are then within eps of one plane, on which a BSP may file both.
bool EmbreeScene::Impl::coplanar_at(double gap, const Hit& a, const Hit& b) const {
  return gap <= 2.0 * eps * (1.0 + kRoundingRelative) * std::max(a.grazing, b.grazing);
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

// Embree's candidates, grouped by ray (a counting sort on the ray index), turned into fragments and
// deduplicated (a fragment is several triangles, and Embree may report one triangle twice), then
// decided in double; each ray's hits sorted by (t, fragment).
void EmbreeScene::Impl::hits(std::span<const Ray> rays, HitBatch& out) const {
  out.keys.clear();
  out.hits.clear();
  if (!fragment.empty())
    for (std::size_t base = 0; base < rays.size(); base += kPacket) propose(rays, base, out.keys);
  out.first.assign(rays.size() + 1, 0);
  for (std::uint64_t k : out.keys) ++out.first[(k >> 32) + 1];
  for (std::size_t r = 0; r < rays.size(); ++r) out.first[r + 1] += out.first[r];
  out.frags.resize(out.keys.size());
  for (std::uint64_t k : out.keys) out.frags[out.first[k >> 32]++] = fragment[static_cast<std::uint32_t>(k)];
  std::uint32_t begin = 0;
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const std::uint32_t end = out.first[r];
    out.first[r] = static_cast<std::uint32_t>(out.hits.size());
    const auto f0 = out.frags.begin() + begin, f1 = out.frags.begin() + end;
    const double dir_length = length(rays[r].dir);
    std::sort(f0, f1);
    for (auto f = f0; f != f1; f = std::upper_bound(f, f1, *f))
      if (const auto hit = exact_hit(rays[r], dir_length, *f)) out.hits.push_back(*hit);
    std::sort(out.hits.begin() + out.first[r], out.hits.end(),
              [](const Hit& a, const Hit& b) { return a.t != b.t ? a.t < b.t : a.fragment < b.fragment; });
    begin = end;
  }
  out.first[rays.size()] = static_cast<std::uint32_t>(out.hits.size());
}

EmbreeScene::EmbreeScene(std::span<const Polygon> fragments, std::optional<double> plane_eps)
    : impl_(std::make_unique<Impl>()) {
  impl_->device = new_checked_device();
  impl_->store(fragments);
  const double diagonal = impl_->box.diagonal();
  const double grow = kGrowRelative * diagonal;
  impl_->eps = plane_eps.value_or(Tolerance::for_extent(diagonal).plane_eps);
  impl_->inside_slack = kInsideEps * impl_->eps;
  for (double r : impl_->reach) impl_->near2.push_back((r + impl_->inside_slack) * (r + impl_->inside_slack));
  if (!impl_->box.empty()) impl_->box = {impl_->box.lo - Vec3{grow, grow, grow}, impl_->box.hi + Vec3{grow, grow, grow}};
  impl_->build(grow);
}

EmbreeScene::~EmbreeScene() = default;
EmbreeScene::EmbreeScene(EmbreeScene&&) noexcept = default;
EmbreeScene& EmbreeScene::operator=(EmbreeScene&&) noexcept = default;

std::vector<Hit> EmbreeScene::all_hits(const Ray& ray) const {
  HitBatch batch;
  impl_->hits({&ray, 1}, batch);
  return std::move(batch.hits);
}

void EmbreeScene::all_hits(std::span<const Ray> rays, HitBatch& out) const { impl_->hits(rays, out); }

std::optional<Hit> EmbreeScene::first_hit(const Ray& ray) const {
  const std::vector<Hit> hits = all_hits(ray);
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
  return impl_->exact_hit(ray, length(ray.dir), fragment);
}

// The edge reason needs the hits within twice the pair's radius of each other and one of them
// within the radius of its fragment's boundary, so most pairs skip its edge walk.
TieReason EmbreeScene::tie_reason(const Ray& ray, const Hit& a, const Hit& b) const {
  const double radius = a.radius + b.radius;
  const double gap = std::abs(b.depth - a.depth);
  if (gap <= 2.0 * radius && (a.inside <= radius || b.inside <= radius)) {
    const Vec3 xa = ray.origin + ray.dir * a.t, xb = ray.origin + ray.dir * b.t;
    if (impl_->touches_at(a.fragment, xa, b.fragment, xb, radius) ||
        impl_->touches_at(b.fragment, xb, a.fragment, xa, radius))
      return TieReason::Edge;
  }
  if (impl_->coplanar_at(gap, a, b)) return TieReason::Coplanar;
  if (a.inside < 0.0 || b.inside < 0.0) return TieReason::Boundary;
  return TieReason::None;
}

bool EmbreeScene::overlap_nearby(const Hit& a, const Hit& b) const {
  if ((a.inside < 0.0) == (b.inside < 0.0)) return false;
  const Hit& out = a.inside < 0.0 ? a : b;
  const Hit& other = a.inside < 0.0 ? b : a;
  if (!(out.t > 0.0)) return false;
  if (other.grazing >= kMaxGrazingScale) return false;  // the sine is only bounded there, not known
  const double moved = -out.inside * (other.t / out.t) * other.grazing;
  return other.inside > moved + impl_->inside_slack;
}

double EmbreeScene::plane_eps() const { return impl_->eps; }
std::size_t EmbreeScene::fragment_count() const { return impl_->first.size() - 1; }

}  // namespace bsp
