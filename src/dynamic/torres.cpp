#include "dynamic/torres.h"

#include "common/cpu_time.h"

namespace bsp {

UpdateWork TorresUpdater::start(std::span<const Polygon> static_polys, std::span<const Polygon> moving,
                                std::size_t objects) {
  UpdateWork work;
  const double start = thread_cpu_seconds();
  build_static(static_polys, moving, objects, *splitter_, work);
  objects_ = build_object_trees(moving, objects, *object_splitter_);
  placements_.assign(objects, Placement{});
  const UpdateWork rest = update(moving);
  work.seconds = thread_cpu_seconds() - start;
  work.nodes_built += rest.nodes_built;
  work.partitioned_nodes += rest.partitioned_nodes;
  work.objects_placed += rest.objects_placed;
  return work;
}

bool TorresUpdater::stays(std::uint32_t k, const BoundingSphere& s) const {
  const Placement& p = placements_[k];
  if (!p.whole) return false;
  const double eps = tree_->tol().plane_eps;
  for (const std::uint32_t plane : p.path)
    if (tree_->planes()[plane].distance(s.center) - s.radius <= eps) return false;
  return true;
}

UpdateWork TorresUpdater::update(std::span<const Polygon> moving) {
  UpdateWork work;
  const double start = thread_cpu_seconds();
  const Poses poses = poses_of(objects_, moving);
  const std::vector<RigidMotion>& motions = poses.motions;
  const std::vector<BoundingSphere>& spheres = poses.spheres;
  Placer placer(*tree_, true);
  std::vector<std::uint32_t> leaving;  // owners
  for (std::uint32_t k = 0; k < objects_.size(); ++k) {
    if (stays(k, spheres[k])) placer.move_in_place(objects_[k], motions[k], k, placements_[k], work);
    else leaving.push_back(k + 1);
  }
  const std::unique_ptr<Splitter> splitter = object_splitter_->clone();
  tree_->remove(leaving, *splitter, work);
  // A repair rebuilt these objects' fragments in new nodes: they are no longer whole.
  for (const std::uint32_t owner : tree_->take_disturbed())
    if (owner != kStaticOwner && owner - 1 < placements_.size()) placements_[owner - 1] = Placement{};
  for (const std::uint32_t owner : leaving)
    placements_[owner - 1] = placer.place(objects_[owner - 1], motions[owner - 1], owner - 1, placements_, spheres, work);
  changed();
  work.seconds = thread_cpu_seconds() - start;
  return work;
}


}  // namespace bsp
