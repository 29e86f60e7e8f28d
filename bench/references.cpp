#include "references.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench_common.h"
#include "experiments/reference_build.h"
#include "metrics/statistics.h"

namespace bsp::bench {

namespace {

using Clock = std::chrono::steady_clock;

// The polygons fan-triangulated into float vertex and index arrays, as a renderer would hand them
// to Embree.
struct Triangles {
  std::vector<float> vertices;  // x, y, z per vertex, plus one float of padding Embree may read
  std::vector<unsigned> indices;
};

Triangles triangulate(std::span<const Polygon> polygons) {
  Triangles t;
  for (const Polygon& p : polygons) {
    const auto base = static_cast<unsigned>(t.vertices.size() / 3);
    for (const Vertex& v : p.verts)
      t.vertices.insert(t.vertices.end(), {static_cast<float>(v.p.x), static_cast<float>(v.p.y), static_cast<float>(v.p.z)});
    for (unsigned i = 1; i + 1 < p.verts.size(); ++i) t.indices.insert(t.indices.end(), {base, base + i, base + i + 1});
  }
  t.vertices.push_back(0.0f);
  return t;
}

// One triangle geometry over the shared buffers, built at MEDIUM quality (Embree's default).
RTCScene committed_scene(RTCDevice device, const Triangles& t) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_MEDIUM);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, t.vertices.data(), 0,
                             3 * sizeof(float), (t.vertices.size() - 1) / 3);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, t.indices.data(), 0,
                             3 * sizeof(unsigned), t.indices.size() / 3);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  return scene;
}

}  // namespace

double embree_bvh_build_seconds(std::span<const Polygon> polygons, int threads, int repeats) {
  const experiments::ReferenceBuild reference(polygons, threads);
  std::vector<double> times;
  for (int i = 0; i < repeats; ++i) {
    const auto start = Clock::now();
    reference.run();
    times.push_back(seconds_since(start));
  }
  return median(times);
}

struct EmbreePrimaryRays::Impl {
  Triangles triangles;
  std::vector<Frustum> views;
  int grid = 0;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  unsigned hits = 0;  // keeps the casts observable
};

EmbreePrimaryRays::EmbreePrimaryRays(std::span<const Polygon> polygons, std::span<const Frustum> views, int grid)
    : impl_(std::make_unique<Impl>()) {
  impl_->triangles = triangulate(polygons);
  impl_->views.assign(views.begin(), views.end());
  impl_->grid = grid;
  impl_->device = rtcNewDevice("threads=1");
  if (!impl_->device) throw std::runtime_error("Embree: cannot create a device");
  impl_->scene = committed_scene(impl_->device, impl_->triangles);
}

EmbreePrimaryRays::~EmbreePrimaryRays() {
  rtcReleaseScene(impl_->scene);
  rtcReleaseDevice(impl_->device);
}

double EmbreePrimaryRays::seconds_per_view() {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const int grid = impl_->grid;
  const auto start = Clock::now();
  for (const Frustum& view : impl_->views) {
    const auto c = view.corners();
    for (int i = 0; i < grid; ++i)
      for (int j = 0; j < grid; ++j) {
        const Vec3 d = c[0] + (c[2] - c[0]) * ((i + 0.5) / grid) + (c[1] - c[0]) * ((j + 0.5) / grid) - view.eye;
        RTCRayHit rh{};
        rh.ray.org_x = static_cast<float>(view.eye.x), rh.ray.org_y = static_cast<float>(view.eye.y);
        rh.ray.org_z = static_cast<float>(view.eye.z);
        rh.ray.dir_x = static_cast<float>(d.x), rh.ray.dir_y = static_cast<float>(d.y), rh.ray.dir_z = static_cast<float>(d.z);
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = std::numeric_limits<float>::infinity();
        rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(impl_->scene, &context, &rh);
        impl_->hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
  }
  benchmark::DoNotOptimize(impl_->hits);
  return seconds_since(start) / static_cast<double>(std::max<std::size_t>(impl_->views.size(), 1));
}

double embree_primary_rays_seconds(std::span<const Polygon> polygons, std::span<const Frustum> views, int grid,
                                   int repeats) {
  EmbreePrimaryRays rays(polygons, views, grid);
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) times.push_back(rays.seconds_per_view());
  return median(times);
}

double depth_sort_seconds(std::size_t pairs, int repeats) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> depth(0.0f, 1.0f);
  std::vector<std::pair<float, std::uint32_t>> input(pairs);
  for (std::size_t i = 0; i < pairs; ++i) input[i] = {depth(rng), static_cast<std::uint32_t>(i)};
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    auto work = input;
    const auto start = Clock::now();
    std::sort(work.begin(), work.end());
    times.push_back(seconds_since(start));
  }
  return median(times);
}

}  // namespace bsp::bench
