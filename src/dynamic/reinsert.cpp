#include "dynamic/reinsert.h"

#include "common/cpu_time.h"

namespace bsp {

UpdateWork ReinsertUpdater::start(std::span<const Polygon> static_polys, std::span<const Polygon> moving,
                                  std::size_t objects) {
  UpdateWork work;
  const double start = thread_cpu_seconds();
  objects_ = objects;
  const std::size_t per = objects ? moving.size() / objects : 0;
  tree_.emplace(static_polys, objects, per, bounds_of(static_polys, moving));
  std::vector<std::uint32_t> ids;
  for (std::uint32_t k = 0; k < objects; ++k) {
    const std::vector<std::uint32_t> object = tree_->load_object(k, moving.subspan(k * per, per));
    ids.insert(ids.end(), object.begin(), object.end());
  }
  const std::unique_ptr<Splitter> splitter = splitter_->clone();
  tree_->build_all(std::move(ids), *splitter, work);
  changed();
  work.seconds = thread_cpu_seconds() - start;
  return work;
}

UpdateWork ReinsertUpdater::update(std::span<const Polygon> moving) {
  UpdateWork work;
  const double start = thread_cpu_seconds();
  const std::size_t per = objects_ ? moving.size() / objects_ : 0;
  const std::unique_ptr<Splitter> splitter = splitter_->clone();
  const auto insert = [&](std::uint32_t k) {
    tree_->insert(tree_->load_object(k, moving.subspan(k * per, per)), k + 1, *splitter, work);
  };
  if (one_at_a_time_) {
    for (std::uint32_t k = 0; k < objects_; ++k) {
      const std::uint32_t owner = k + 1;
      tree_->remove(std::span(&owner, 1), *splitter, work);
      insert(k);
    }
  } else {
    std::vector<std::uint32_t> owners;
    for (std::uint32_t k = 0; k < objects_; ++k) owners.push_back(k + 1);
    tree_->remove(owners, *splitter, work);
    for (std::uint32_t k = 0; k < objects_; ++k) insert(k);
  }
  changed();
  work.seconds = thread_cpu_seconds() - start;
  return work;
}

}  // namespace bsp
