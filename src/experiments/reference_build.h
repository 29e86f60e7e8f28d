#pragma once
// The in-run reference of the gated timings (timing.h): Embree 3's BVH build [Wald2014] of a job's
// own input, at Embree's default quality (RTC_BUILD_QUALITY_MEDIUM), over buffers shared with it.
// It is a tree build, like ours, in code that does not change with ours (a Debian package), so a
// host state that slows our builds slows it too, and the ratio of the two cancels it
// [Mytkowicz2009]. The scaling benchmark measures against the same build (bench/references.h).
//
// Polygons are fan-triangulated as a renderer would hand them to Embree. A 2D segment (two
// vertices, as Doom maps and the segment scenes hold) becomes a wall: a square standing on it, so a
// flat scene has a reference as big as a solid one. Embree never appears in this header (pimpl).
#include <memory>
#include <span>

#include "geometry/polygon.h"

namespace bsp::experiments {

class ReferenceBuild {
 public:
  // Triangulates `polygons` and builds once (Embree's first build of a device pays its start-up).
  // `threads` limits Embree's device; the gated timings are single-threaded, so 1. Throws
  // std::runtime_error when Embree fails.
  explicit ReferenceBuild(std::span<const Polygon> polygons, int threads = 1);
  ~ReferenceBuild();
  ReferenceBuild(const ReferenceBuild&) = delete;
  ReferenceBuild& operator=(const ReferenceBuild&) = delete;

  // One BVH build of the triangles, released again. Throws std::runtime_error when Embree fails.
  void run() const;
  std::size_t triangles() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bsp::experiments
