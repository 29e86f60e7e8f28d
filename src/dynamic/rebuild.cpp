#include "dynamic/rebuild.h"

#include "common/cpu_time.h"

namespace bsp {

RebuildUpdater::RebuildUpdater(std::unique_ptr<Splitter> splitter, const BuildOptions& build)
    : splitter_(std::move(splitter)), build_(build) {}

UpdateWork RebuildUpdater::start(std::span<const Polygon> static_polys, std::span<const Polygon> moving,
                                 std::size_t) {
  input_.assign(static_polys.begin(), static_polys.end());
  static_count_ = input_.size();
  return update(moving);
}

UpdateWork RebuildUpdater::update(std::span<const Polygon> moving) {
  input_.resize(static_count_);
  input_.insert(input_.end(), moving.begin(), moving.end());
  const double start = thread_cpu_seconds();
  // A fresh clone per frame, whatever state a splitter keeps: each frame's tree is the plain build
  // of that frame.
  const std::unique_ptr<Splitter> splitter = splitter_->clone();
  tree_ = build_tree(input_, *splitter, build_);
  return {thread_cpu_seconds() - start, input_.size()};
}

}  // namespace bsp
