#pragma once
// In-run references for the scaling benchmark: what a BSP build and a back-to-front traversal are
// measured against, on the same machine in the same run.
//  - Embree 3's BVH build (RTC_BUILD_QUALITY_MEDIUM, one triangle geometry over shared buffers)
//    of the same polygons, fan-triangulated, on a device limited to the same number of threads:
//    the cost of a good spatial hierarchy over the same input.
//  - Embree casting one primary ray per pixel of a grid through each view's near rectangle
//    (rtcIntersect1, first hits; the BVH built once beforehand): the cost of finding the visible
//    surfaces by ray casting, which occlusion culling competes with.
//  - std::sort of as many (float depth, uint32 id) pairs as the traversal emits: the cost of a
//    plain painter's-algorithm depth sort, which a back-to-front traversal replaces.
// Each returns the median of `repeats` timed runs, in seconds.
#include <cstddef>
#include <memory>
#include <span>

#include "geometry/polygon.h"
#include "tree/traverse_culled.h"

namespace bsp::bench {

double embree_bvh_build_seconds(std::span<const Polygon> polygons, int threads, int repeats);
double depth_sort_seconds(std::size_t pairs, int repeats);
// Seconds per view of a grid x grid primary-ray image, on one thread: the median over `repeats`.
double embree_primary_rays_seconds(std::span<const Polygon> polygons, std::span<const Frustum> views, int grid,
                                   int repeats);

// The same primary rays, the BVH built once, for a benchmark that times them beside each of its own
// runs (a reference paired run by run, as the sweep's are: experiments/timing.h).
class EmbreePrimaryRays {
 public:
  EmbreePrimaryRays(std::span<const Polygon> polygons, std::span<const Frustum> views, int grid);
  ~EmbreePrimaryRays();
  EmbreePrimaryRays(const EmbreePrimaryRays&) = delete;
  EmbreePrimaryRays& operator=(const EmbreePrimaryRays&) = delete;
  // Wall seconds per view of one pass over every view.
  double seconds_per_view();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bsp::bench
