#pragma once
// Moving objects as trees of their own, merged into a host tree each frame [Naylor1990; Torres1990].
//
// Notation: T is an object's tree, built once from the object's polygons at its first pose; M is
// the rigid motion from that pose to the current one; a part is (a piece of) M(T) on its way into
// the host, a small tree in the placer's scratch arena. A part meeting a host node whose plane
// crosses the object's bounding sphere is partitioned by that plane (Naylor's partitionTree for
// drawing trees: each node's fragments are split, and a node keeps its place on a side while it
// holds fragments there or separates two non-empty subtrees there); a part reaching an empty cell
// is hung there. Fragments coplanar with a host plane join the host node.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "dynamic/dynamic_tree.h"
#include "geometry/plane.h"
#include "split/fragment_store.h"
#include "tree/tree.h"

namespace bsp {

// x -> R x + t, with R given by where it takes an orthonormal frame: R x = sum_i to[i] (from[i] . x).
struct RigidMotion {
  Vec3 from[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Vec3 to[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Vec3 t;
  Vec3 rotate(const Vec3& v) const { return to[0] * dot(from[0], v) + to[1] * dot(from[1], v) + to[2] * dot(from[2], v); }
  Vec3 apply(const Vec3& p) const { return rotate(p) + t; }
  Plane apply(const Plane& p) const;
};

// The motion taking a[i] to b[i], three points of one rigid body that are not collinear.
RigidMotion motion_between(const Vec3 a[3], const Vec3 b[3]);

class ObjectTree {
 public:
  // Builds T from the object's polygons (sources 0..m-1) with `splitter`.
  ObjectTree(std::span<const Polygon> first_pose, Splitter& splitter);
  // The motion from the first pose to `now` (the same polygons moved rigidly), from three vertices
  // chosen at the first pose to be far apart, so rounding in the estimate stays near one ulp.
  RigidMotion motion_to(std::span<const Polygon> now) const;
  BoundingSphere sphere(const RigidMotion& m) const { return {m.apply(sphere_.center), sphere_.radius}; }
  const Tree& tree() const { return tree_; }

 private:
  Tree tree_;
  std::pair<std::uint32_t, std::uint32_t> anchor_[3];  // (polygon, vertex)
  Vec3 anchor_at_start_[3];
  BoundingSphere sphere_;  // of every vertex at the first pose
};

// The objects' own trees, each built with a clone of `splitter` from its block of `moving` (objects
// blocks of equal size, at their first poses).
std::vector<ObjectTree> build_object_trees(std::span<const Polygon> moving, std::size_t objects,
                                           const Splitter& splitter);

// Every object's motion from its first pose to the frame's, and its bounding sphere there.
struct Poses {
  std::vector<RigidMotion> motions;
  std::vector<BoundingSphere> spheres;
};
Poses poses_of(std::span<const ObjectTree> objects, std::span<const Polygon> moving);

// Where an object ended up when placed (torres keeps it to move the object in place next frame).
struct Placement {
  bool whole = false;  // hung as one piece in one empty cell: nothing partitioned, nothing shared
  // The host planes the descent passed, each oriented towards the object: while the object's sphere
  // stays in front of all of them, it stays in its cell.
  std::vector<std::uint32_t> path;
  std::uint32_t root = kNull;  // host node of T's root when whole
  // When whole: host node of each T node, in T's node order.
  std::vector<std::uint32_t> nodes;
};

class Placer {
 public:
  // With separate (Torres), an object whose descent meets the root of another whole object, their
  // spheres disjoint, gets a separating plane between the two instead of being merged into it.
  Placer(DynamicTree& host, bool separate) : host_(host), separate_(separate) {}
  // Places M(T) for object k (owner k + 1). `placements` holds every object's current placement:
  // the separating case reads and extends others' paths, and marks objects merged into as not whole.
  // `spheres` holds every object's sphere at its current pose.
  Placement place(const ObjectTree& object, const RigidMotion& m, std::uint32_t k, std::vector<Placement>& placements,
                  std::span<const BoundingSphere> spheres, UpdateWork& work);
  // Moves a whole object's nodes and fragments to pose m without touching anything else.
  void move_in_place(const ObjectTree& object, const RigidMotion& m, std::uint32_t k, const Placement& p,
                     UpdateWork& work);

 private:
  struct PartNode {
    std::uint32_t plane;  // in the host pool
    std::uint32_t front, back;
    std::vector<std::uint32_t> frags;  // ids in the host store
  };
  std::uint32_t load(const ObjectTree& object, const RigidMotion& m, std::uint32_t k);
  std::pair<std::uint32_t, std::uint32_t> partition(std::uint32_t part, const Plane& h, std::vector<std::uint32_t>& on,
                                                    UpdateWork& work);
  std::uint32_t make_part(std::uint32_t plane, std::vector<std::uint32_t> frags, std::uint32_t front, std::uint32_t back);
  void hang(std::uint32_t part, Slot slot, std::uint32_t owner, Placement* whole, UpdateWork& work);
  bool try_separate(std::uint32_t host_node, std::uint32_t k, std::uint32_t part, Placement& p,
                    std::vector<Placement>& placements, std::span<const BoundingSphere> spheres, UpdateWork& work);
  void touch(std::uint32_t host_node, std::uint32_t k, std::vector<Placement>& placements) const;
  std::uint32_t moved_plane(const ObjectTree& object, std::uint32_t t_plane, const RigidMotion& m);
  std::uint32_t moved_fragment(const ObjectTree& object, std::uint32_t f, const RigidMotion& m, std::uint32_t k);

  DynamicTree& host_;
  const bool separate_;
  std::vector<PartNode> parts_;
  std::vector<std::uint32_t> plane_map_;  // T plane pair -> host index of its moved plane, this frame
  Polygon scratch_;
};

}  // namespace bsp
