#include "dynamic/object_merge.h"

#include "common/cpu_time.h"

namespace bsp {

UpdateWork MergeUpdater::start(std::span<const Polygon> static_polys, std::span<const Polygon> moving,
                               std::size_t objects) {
  UpdateWork work;
  const double start = thread_cpu_seconds();
  build_static(static_polys, moving, objects, *splitter_, work);
  objects_ = build_object_trees(moving, objects, *object_splitter_);
  owners_.clear();
  for (std::uint32_t k = 0; k < objects; ++k) owners_.push_back(k + 1);
  place_all(moving, work);
  work.seconds = thread_cpu_seconds() - start;
  return work;
}

UpdateWork MergeUpdater::update(std::span<const Polygon> moving) {
  UpdateWork work;
  const double start = thread_cpu_seconds();
  // Only object parts go: no static node is removed, so the splitter is never consulted.
  const std::unique_ptr<Splitter> splitter = splitter_->clone();
  tree_->remove(owners_, *splitter, work);
  place_all(moving, work);
  work.seconds = thread_cpu_seconds() - start;
  return work;
}

void MergeUpdater::place_all(std::span<const Polygon> moving, UpdateWork& work) {
  const Poses poses = poses_of(objects_, moving);
  std::vector<Placement> placements(objects_.size());
  Placer placer(*tree_, false);
  for (std::uint32_t k = 0; k < objects_.size(); ++k)
    placer.place(objects_[k], poses.motions[k], k, placements, poses.spheres, work);
  changed();
}


}  // namespace bsp
