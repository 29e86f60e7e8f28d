#include "animation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "catalog.h"
#include "common/errors.h"
#include "common/rng.h"

namespace bsp {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw UsageError("animation: " + what);
}

void check_spec(const AnimationSpec& s) {
  require(s.moving <= 1000, "moving must be 0..1000");
  require(s.frames >= 1 && s.frames <= 100000, "frames must be 1..100000");
  require(s.size > 0 && s.size <= 0.5, "size must be in (0, 0.5] box diagonals");
  require(s.speed >= 0 && s.speed <= 1, "speed must be in [0, 1] box diagonals per frame");
  require(s.spin >= 0 && s.spin <= std::numbers::pi, "spin must be in [0, pi] radians per frame");
  require(s.object == kSceneGroups || find_generator(s.object).closed_solid,
          "object '" + s.object + "' is not a closed solid (bspbench scenes) or '" + std::string(kSceneGroups) + "'");
}

Vec3 centroid_of(const Polygon& p) {
  Vec3 c;
  for (const Vertex& v : p.verts) c += v.p;
  return c / static_cast<double>(p.verts.size());
}

// Takes `count` polygons of `scene` out of it: those whose centroids lie nearest to `at` (ties by
// index), returned about their own centroid.
std::vector<Polygon> take_group(std::vector<Polygon>& scene, const Vec3& at, std::size_t count) {
  std::vector<std::size_t> order(scene.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return length(centroid_of(scene[a]) - at) < length(centroid_of(scene[b]) - at);
  });
  order.resize(count);
  std::sort(order.begin(), order.end());
  std::vector<Polygon> group;
  Vec3 c;
  std::size_t n = 0;
  for (const std::size_t i : order)
    for (const Vertex& v : scene[i].verts) c += v.p, ++n;
  c = c / static_cast<double>(n);
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    group.push_back(std::move(scene[*it]));
    scene.erase(scene.begin() + static_cast<std::ptrdiff_t>(*it));
  }
  std::reverse(group.begin(), group.end());
  for (Polygon& p : group)
    for (Vertex& v : p.verts) v.p = v.p - c;
  return group;
}

// The object's polygons about the origin, scaled so its farthest vertex is at distance 1.
std::vector<Polygon> unit_object(const AnimationSpec& s) {
  Scene o = make_scene(s.object, {{"n", std::to_string(s.object_n)}, {"seed", "0"}});
  double r = 0;
  for (const Polygon& p : o.polygons)
    for (const Vertex& v : p.verts) r = std::max(r, length(v.p));
  for (Polygon& p : o.polygons)
    for (Vertex& v : p.verts) v.p = v.p / r;
  return o.polygons;
}

// Rodrigues' rotation of p by angle about the unit axis k.
Vec3 rotate(const Vec3& p, const Vec3& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return p * c + cross(k, p) * s + k * (dot(k, p) * (1 - c));
}

// A uniformly distributed unit vector [Marsaglia1972].
Vec3 random_axis(Rng& rng) {
  for (;;) {
    const double a = rng.uniform(-1, 1), b = rng.uniform(-1, 1), q = a * a + b * b;
    if (q >= 1 || q == 0) continue;
    const double r = 2 * std::sqrt(1 - q);
    return {a * r, b * r, 1 - 2 * q};
  }
}

}  // namespace

Animation::Animation(AnimationSpec spec) : Animation(spec, (check_spec(spec), make_scene(spec.scene, spec.scene_params))) {}

Animation::Animation(AnimationSpec spec, Scene static_scene) : spec_(std::move(spec)), static_(std::move(static_scene)) {
  check_spec(spec_);
  check_scene(static_, "scene " + static_.name);
  if (spec_.scene != static_.name) {
    spec_.scene = static_.name;
    spec_.scene_params.clear();
  }
  const Box box = bounds(static_);
  const double diagonal = box.diagonal();
  radius_ = spec_.size * diagonal;
  step_ = spec_.speed * diagonal;
  if (spec_.object != kSceneGroups) {
    std::vector<Polygon> unit = unit_object(spec_);
    for (Polygon& p : unit)
      for (Vertex& v : p.verts) v.p = v.p * radius_;
    locals_.assign(spec_.moving, unit);
  } else {
    require(spec_.object_n * spec_.moving <= static_.polygons.size(),
            "moving * object-n must not exceed the scene's polygons when objects are groups of them");
  }
  for (std::uint32_t i = 0; i < spec_.moving; ++i) {
    Rng rng(stream_seed(spec_.seed, i));
    Path path;
    for (int w = 0; w < 4; ++w) {
      double c[3];
      for (int a = 0; a < 3; ++a) c[a] = box.lo[a] + (box.hi[a] - box.lo[a]) * rng.uniform(0.1, 0.9);
      path.waypoints.push_back({c[0], c[1], c[2]});
    }
    for (std::size_t w = 0; w < 4; ++w) path.length += length(path.waypoints[(w + 1) % 4] - path.waypoints[w]);
    path.axis = random_axis(rng);
    path.phase = rng.uniform(0, 2 * std::numbers::pi);
    if (spec_.object == kSceneGroups) locals_.push_back(take_group(static_.polygons, path.waypoints.front(), spec_.object_n));
    paths_.push_back(std::move(path));
  }
}

Vec3 Animation::position(const Path& path, std::uint32_t frame) const {
  if (!(path.length > 0)) return path.waypoints.front();
  double s = std::fmod(step_ * static_cast<double>(frame), path.length);
  for (std::size_t w = 0;; w = (w + 1) % 4) {
    const Vec3 a = path.waypoints[w], b = path.waypoints[(w + 1) % 4];
    const double leg = length(b - a);
    if (s <= leg) return leg > 0 ? a + (b - a) * (s / leg) : a;
    s -= leg;
  }
}

std::vector<Polygon> Animation::object_at(std::size_t i, std::uint32_t frame, std::uint32_t first_source) const {
  const Path& path = paths_.at(i);
  const Vec3 centre = position(path, frame);
  const double angle = path.phase + spec_.spin * static_cast<double>(frame);
  std::vector<Polygon> out = locals_.at(i);
  for (std::size_t k = 0; k < out.size(); ++k) {
    for (Vertex& v : out[k].verts) v.p = centre + rotate(v.p, path.axis, angle);
    out[k].source = first_source + static_cast<std::uint32_t>(k);
  }
  return out;
}

std::vector<Polygon> Animation::moving_at(std::uint32_t frame, std::uint32_t first_source) const {
  std::vector<Polygon> out;
  out.reserve(moving_polygons());
  for (std::size_t i = 0; i < paths_.size(); ++i) {
    std::vector<Polygon> o = object_at(i, frame, first_source + static_cast<std::uint32_t>(out.size()));
    out.insert(out.end(), std::make_move_iterator(o.begin()), std::make_move_iterator(o.end()));
  }
  return out;
}

Scene Animation::frame(std::uint32_t f) const {
  Scene scene = static_;
  scene.name = static_.name + " animated";
  for (std::size_t k = 0; k < scene.polygons.size(); ++k) scene.polygons[k].source = static_cast<std::uint32_t>(k);
  std::vector<Polygon> moving = moving_at(f, static_cast<std::uint32_t>(scene.polygons.size()));
  scene.polygons.insert(scene.polygons.end(), std::make_move_iterator(moving.begin()),
                        std::make_move_iterator(moving.end()));
  return scene;
}

nlohmann::json Animation::describe() const {
  nlohmann::json paths = nlohmann::json::array();
  for (const Path& p : paths_) {
    nlohmann::json w = nlohmann::json::array();
    for (const Vec3& v : p.waypoints) w.push_back({v.x, v.y, v.z});
    paths.push_back({{"waypoints", std::move(w)}, {"length", p.length}, {"axis", {p.axis.x, p.axis.y, p.axis.z}}});
  }
  const double total = static_cast<double>(static_.polygons.size() + moving_polygons());
  return {{"scene", static_.name},
          {"scene_params", static_.params.to_json()},
          {"frames", spec_.frames},
          {"moving", spec_.moving},
          {"object", spec_.object},
          {"object_polygons", object_polygons()},
          {"radius", radius_},
          {"step", step_},
          {"spin", spec_.spin},
          {"seed", spec_.seed},
          {"static_polygons", static_.polygons.size()},
          {"moving_fraction", static_cast<double>(moving_polygons()) / total},
          {"paths", std::move(paths)}};
}

}  // namespace bsp
