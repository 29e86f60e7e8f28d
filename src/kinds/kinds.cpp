#include "kinds/kinds.h"

#include <algorithm>

#include "experiments/animate/animate.h"
#include "experiments/csg/csg.h"
#include "experiments/doom/doom.h"
#include "experiments/draw/draw.h"
#include "experiments/kernel/kernel.h"
#include "experiments/merge/merge.h"
#include "experiments/occlude/occlude.h"
#include "experiments/optimal/optimal.h"

namespace bsp {

std::span<const experiments::Kind* const> kinds() {
  static const experiments::Kind* const all[] = {
      &experiments::draw_kind(),    &experiments::merge_kind(), &experiments::animate_kind(),
      &experiments::occlude_kind(), &experiments::doom_kind(),  &experiments::kernel_kind(),
      &experiments::csg_kind(),     &experiments::optimal_kind(),
  };
  return all;
}

const experiments::Kind* find_kind(std::string_view name) {
  const auto all = kinds();
  const auto it = std::find_if(all.begin(), all.end(), [&](const experiments::Kind* k) { return k->name == name; });
  return it == all.end() ? nullptr : *it;
}

}  // namespace bsp
