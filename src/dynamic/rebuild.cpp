#include "dynamic/rebuild.h"

#include <ctime>

#include "split/registry.h"

namespace bsp {

namespace {

double thread_cpu() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

RebuildUpdater::RebuildUpdater(UpdaterSettings settings) : settings_(std::move(settings)) {
  make_splitter(settings_.heuristic, settings_.params, settings_.seed);  // reject a bad name now
}

UpdateWork RebuildUpdater::start(std::span<const Polygon> static_polys, std::span<const Polygon> moving,
                                 std::size_t) {
  input_.assign(static_polys.begin(), static_polys.end());
  static_count_ = input_.size();
  return update(moving);
}

UpdateWork RebuildUpdater::update(std::span<const Polygon> moving) {
  input_.resize(static_count_);
  input_.insert(input_.end(), moving.begin(), moving.end());
  const double start = thread_cpu();
  // A fresh splitter per frame: each frame's tree is the one a plain build of that frame gives.
  auto splitter = make_splitter(settings_.heuristic, settings_.params, settings_.seed);
  tree_ = build_tree(input_, *splitter, settings_.build);
  return {thread_cpu() - start, input_.size()};
}

}  // namespace bsp
