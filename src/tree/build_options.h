#pragma once
// How a tree is built: the options of the recursive build (tree/build.h) and of the incremental
// one (tree/build_incremental.h), in a module of their own so that the recursive build can hand
// over to the incremental one without the two including each other.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "geometry/plane.h"
#include "geometry/tolerance.h"
#include "tree/tree.h"

namespace bsp {

enum class InsertOrder : std::uint8_t { Given, Shuffled };

struct BuildOptions {
  Shape shape = Shape::Strict;
  bool incremental = false;                 // Thibault–Naylor insertion, one polygon at a time
  InsertOrder order = InsertOrder::Given;   // incremental only
  std::uint64_t order_seed = 0;             // InsertOrder::Shuffled only
  // How the recursive build divides its work among threads. The main builder makes the top of the
  // tree and hands every pending subtree of at most 1/task_share of the input, and at least
  // min_task_fragments fragments, to a task that builds it alone on any thread (OpenMP tasks). The
  // tree does not depend on these (tests build with other values and compare bit for bit), only how
  // the work divides: 64 leaves tens of tasks to balance two threads over; 512 keeps a task's setup
  // (moving its fragments out) small beside its work, so inputs under 32,768 polygons build on one
  // thread.
  std::size_t task_share = 64;
  std::size_t min_task_fragments = 512;
  // Shape::Leafy only: the group of each input polygon (by source index), such as a Doom seg's
  // sector; a leaf then holds fragments of one group. Empty: no groups.
  std::vector<std::uint32_t> leaf_groups{};
  // When set, every free plane (a splitter's Kind::Free choice, or the plane that parts a leafy
  // convex set of several groups) passes through it before use: a format that can only store
  // some planes (Doom's partition lines through integer points) gets the plane it will store, and
  // the tree is built with exactly that plane.
  std::function<Plane(const Plane&)> snap_free_plane{};
  // The float kernel's tolerance relative to the input's diagonal (geometry/tolerance.h). Only the
  // kernel runs that measure what the tolerance does set another (experiments/kernel/kernel.h).
  double plane_eps_relative = kPlaneEpsRelative;
};

}  // namespace bsp
