#include "split/fragment_extents.h"

namespace bsp {

void FragmentExtents::measure(const SplitContext& ctx) {
  lo_.clear();
  hi_.clear();
  box_ = Box{};
  for (auto id : ctx.ids) {
    Box f;
    for (const Vec3& p : ctx.frags.points(id)) f.add(p);
    lo_.push_back(f.lo);
    hi_.push_back(f.hi);
    box_.add(f);
  }
}

bool FragmentExtents::parts(int axis, double x, double eps) const {
  bool back = false, front = false;
  for (std::size_t i = 0; i < lo_.size() && !(back && front); ++i) {
    back |= hi_[i][axis] < x - eps;
    front |= lo_[i][axis] > x + eps;
  }
  return back && front;
}

}  // namespace bsp
