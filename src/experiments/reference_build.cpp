#include "experiments/reference_build.h"

#include <embree3/rtcore.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace bsp::experiments {

namespace {

// x, y, z per vertex, plus one float of padding Embree may read past the last vertex.
struct Triangles {
  std::vector<float> vertices;
  std::vector<unsigned> indices;

  unsigned add(const Vec3& p) {
    vertices.insert(vertices.end(), {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
    return static_cast<unsigned>(vertices.size() / 3 - 1);
  }
};

// A segment's wall: the square standing on it, up the z axis (2D scenes lie in z = 0).
void add_wall(const Vec3& a, const Vec3& b, Triangles& t) {
  const Vec3 up{0, 0, length(b - a)};
  const unsigned i = t.add(a), j = t.add(b), k = t.add(b + up), l = t.add(a + up);
  t.indices.insert(t.indices.end(), {i, j, k, i, k, l});
}

Triangles triangulate(std::span<const Polygon> polygons) {
  Triangles t;
  for (const Polygon& p : polygons) {
    if (p.verts.size() == 2) {
      add_wall(p.verts[0].p, p.verts[1].p, t);
      continue;
    }
    if (p.verts.size() < 3) continue;
    const unsigned base = t.add(p.verts[0].p);
    for (std::size_t i = 1; i < p.verts.size(); ++i) t.add(p.verts[i].p);
    for (unsigned i = 1; i + 1 < p.verts.size(); ++i) t.indices.insert(t.indices.end(), {base, base + i, base + i + 1});
  }
  t.vertices.push_back(0.0f);
  return t;
}

void check(RTCDevice device) {
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw std::runtime_error("Embree failed to build the reference BVH");
}

}  // namespace

struct ReferenceBuild::Impl {
  Triangles triangles;
  RTCDevice device = nullptr;
};

ReferenceBuild::ReferenceBuild(std::span<const Polygon> polygons, int threads) : impl_(std::make_unique<Impl>()) {
  impl_->triangles = triangulate(polygons);
  impl_->device = rtcNewDevice(("threads=" + std::to_string(threads)).c_str());
  if (!impl_->device) throw std::runtime_error("Embree: cannot create a device");
  run();
}

ReferenceBuild::~ReferenceBuild() {
  if (impl_ && impl_->device) rtcReleaseDevice(impl_->device);
}

void ReferenceBuild::run() const {
  const Triangles& t = impl_->triangles;
  RTCScene scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_MEDIUM);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, t.vertices.data(), 0,
                             3 * sizeof(float), (t.vertices.size() - 1) / 3);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, t.indices.data(), 0,
                             3 * sizeof(unsigned), t.indices.size() / 3);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  rtcReleaseScene(scene);
  check(impl_->device);
}

std::size_t ReferenceBuild::triangles() const { return impl_->triangles.indices.size() / 3; }

}  // namespace bsp::experiments
