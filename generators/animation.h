#pragma once
// Animated scenes for dynamic-scene measurements: a static scene from the catalog plus K moving
// closed solids (solids.cpp), or K groups of the scene's own polygons (kSceneGroups), that travel
// along seeded closed paths through the static scene's box,
// crossing it and each other, and spin about seeded axes, for F frames. Everything is a function
// of the spec: the same spec gives the same frames, bit for bit, everywhere.
//
// Each object's path is a closed polygon through 4 waypoints drawn uniformly in the middle 80% of
// the static box (per axis); the object advances `speed` box diagonals along it per frame and
// turns `spin` radians per frame about its axis, starting from a seeded phase. Object i draws from
// stream_seed(seed, i), so adding objects does not move the others.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/params.h"
#include "scene/scene.h"

namespace bsp {

// AnimationSpec::object naming groups of the static scene's own polygons instead of a solid: object
// i is the object_n polygons whose centroids lie nearest to its path's first waypoint, taken out of
// the static scene (in object order) and moved rigidly about their centroid; `size` does not apply.
inline constexpr std::string_view kSceneGroups = "scene";

struct AnimationSpec {
  std::string scene;              // a catalog scene or mesh:NAME
  ParamAssignments scene_params;
  std::uint32_t moving = 4;       // K, 0..1000
  std::string object = "sphere";  // a closed-solid generator, or kSceneGroups
  std::uint64_t object_n = 80;    // its `n` (polygons per object, by its count rule)
  double size = 0.04;             // object radius, in box diagonals; (0, 0.5]
  double speed = 0.004;           // path length per frame, in box diagonals; [0, 1]
  double spin = 0.02;             // radians per frame; [0, pi]
  std::uint32_t frames = 100;     // F, 1..100000
  std::uint64_t seed = 1;
};

class Animation {
 public:
  // Throws UsageError for a value out of range or an object that is not a closed solid, and what
  // make_scene throws for the scene.
  explicit Animation(AnimationSpec spec);
  // The same around a static scene given whole (a mesh file): spec.scene and scene_params are
  // replaced by the scene's name and left empty.
  Animation(AnimationSpec spec, Scene static_scene);

  const AnimationSpec& spec() const { return spec_; }
  const Scene& static_scene() const { return static_; }
  std::size_t object_polygons() const { return locals_.empty() ? 0 : locals_.front().size(); }  // per moving object
  std::size_t moving_polygons() const { return object_polygons() * paths_.size(); }

  // The moving objects at frame f (any f; paths are closed), object by object, each object's
  // polygons in one block of object_polygons(); `source` numbers them from `first_source`.
  std::vector<Polygon> moving_at(std::uint32_t frame, std::uint32_t first_source = 0) const;
  // Object i alone at frame f.
  std::vector<Polygon> object_at(std::size_t i, std::uint32_t frame, std::uint32_t first_source = 0) const;
  // The whole scene at frame f: the static polygons, then moving_at(f), numbered in that order.
  Scene frame(std::uint32_t f) const;

  // What moves and how far: {scene, frames, moving, object, object_polygons, radius, step, spin,
  // static_polygons, moving_fraction, paths: [{waypoints, length, axis}]}. `step` is the distance
  // an object travels per frame; moving_fraction the moving share of a frame's polygons.
  nlohmann::json describe() const;

 private:
  struct Path {
    std::vector<Vec3> waypoints;  // closed: the last leads back to the first
    double length = 0;
    Vec3 axis;
    double phase = 0;
  };
  Vec3 position(const Path& path, std::uint32_t frame) const;

  AnimationSpec spec_;
  Scene static_;
  std::vector<std::vector<Polygon>> locals_;  // per object: its polygons about its centre, at its size
  double radius_ = 0, step_ = 0;
  std::vector<Path> paths_;
};

}  // namespace bsp
