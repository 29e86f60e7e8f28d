#include "dynamic/object_merge.h"

#include "common/cpu_time.h"

namespace bsp {

UpdateWork MergeUpdater::start(std::span<const Polygon> static_polys, std::span<const Polygon> moving,
                               std::size_t objects) {
  UpdateWork work;
  const double start = thread_cpu_seconds();
  const std::size_t per = objects ? moving.size() / objects : 0;
  tree_.emplace(static_polys, objects, per, bounds_of(static_polys, moving));
  const std::unique_ptr<Splitter> splitter = splitter_->clone();
  tree_->build_all({}, *splitter, work);
  objects_.clear();
  owners_.clear();
  for (std::uint32_t k = 0; k < objects; ++k) {
    const std::unique_ptr<Splitter> s = object_splitter_->clone();
    objects_.emplace_back(moving.subspan(k * per, per), *s);
    owners_.push_back(k + 1);
  }
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
  const std::size_t per = objects_.empty() ? 0 : moving.size() / objects_.size();
  std::vector<RigidMotion> motions;
  std::vector<BoundingSphere> spheres;
  for (std::uint32_t k = 0; k < objects_.size(); ++k) {
    motions.push_back(objects_[k].motion_to(moving.subspan(k * per, per)));
    spheres.push_back(objects_[k].sphere(motions.back()));
  }
  std::vector<Placement> placements(objects_.size());
  Placer placer(*tree_, false);
  for (std::uint32_t k = 0; k < objects_.size(); ++k)
    placer.place(objects_[k], motions[k], k, placements, spheres, work);
  snapshot_.reset();
}

const Tree& MergeUpdater::tree() const {
  if (!snapshot_) snapshot_ = tree_->snapshot();
  return *snapshot_;
}

}  // namespace bsp
