#include "dynamic/object_tree.h"

#include <algorithm>
#include <memory>

#include "tree/build.h"

namespace bsp {

namespace {

// An orthonormal frame from three non-collinear points: along p0p1, then towards p2 in their plane.
void frame_of(const Vec3 p[3], Vec3 out[3]) {
  out[0] = normalize(p[1] - p[0]);
  out[2] = normalize(cross(p[1] - p[0], p[2] - p[0]));
  out[1] = cross(out[2], out[0]);
}

}  // namespace

Plane RigidMotion::apply(const Plane& p) const {
  const Vec3 n = rotate(p.n);
  // The point of the plane nearest the origin, moved, lies on the moved plane.
  return {n, -dot(n, apply(p.n * (-p.d / dot(p.n, p.n))))};
}

RigidMotion motion_between(const Vec3 a[3], const Vec3 b[3]) {
  RigidMotion m;
  frame_of(a, m.from);
  frame_of(b, m.to);
  m.t = b[0] - m.rotate(a[0]);
  return m;
}

ObjectTree::ObjectTree(std::span<const Polygon> first_pose, Splitter& splitter) {
  tree_ = build_tree(first_pose, splitter);
  Box box;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> all;
  for (std::uint32_t i = 0; i < first_pose.size(); ++i)
    for (std::uint32_t v = 0; v < first_pose[i].verts.size(); ++v) {
      all.push_back({i, v});
      box.add(first_pose[i].verts[v].p);
    }
  const auto at = [&](std::pair<std::uint32_t, std::uint32_t> a) { return first_pose[a.first].verts[a.second].p; };
  sphere_.center = (box.lo + box.hi) * 0.5;
  for (const auto& a : all) sphere_.radius = std::max(sphere_.radius, length(at(a) - sphere_.center));
  if (all.empty()) return;
  // Anchors far apart: the first vertex, the vertex farthest from it, and the vertex farthest from
  // the line through both.
  anchor_[0] = all.front();
  anchor_[1] = *std::max_element(all.begin(), all.end(), [&](auto x, auto y) {
    return length(at(x) - at(anchor_[0])) < length(at(y) - at(anchor_[0]));
  });
  const Vec3 axis = normalize(at(anchor_[1]) - at(anchor_[0]));
  const auto off_line = [&](auto x) {
    const Vec3 d = at(x) - at(anchor_[0]);
    return length(d - axis * dot(d, axis));
  };
  anchor_[2] = *std::max_element(all.begin(), all.end(), [&](auto x, auto y) { return off_line(x) < off_line(y); });
  for (int i = 0; i < 3; ++i) anchor_at_start_[i] = at(anchor_[i]);
}

RigidMotion ObjectTree::motion_to(std::span<const Polygon> now) const {
  Vec3 b[3];
  for (int i = 0; i < 3; ++i) b[i] = now[anchor_[i].first].verts[anchor_[i].second].p;
  return motion_between(anchor_at_start_, b);
}

std::vector<ObjectTree> build_object_trees(std::span<const Polygon> moving, std::size_t objects,
                                           const Splitter& splitter) {
  const std::size_t per = objects ? moving.size() / objects : 0;
  std::vector<ObjectTree> out;
  for (std::size_t k = 0; k < objects; ++k) {
    const std::unique_ptr<Splitter> s = splitter.clone();
    out.emplace_back(moving.subspan(k * per, per), *s);
  }
  return out;
}

Poses poses_of(std::span<const ObjectTree> objects, std::span<const Polygon> moving) {
  const std::size_t per = objects.empty() ? 0 : moving.size() / objects.size();
  Poses p;
  for (std::size_t k = 0; k < objects.size(); ++k) {
    p.motions.push_back(objects[k].motion_to(moving.subspan(k * per, per)));
    p.spheres.push_back(objects[k].sphere(p.motions.back()));
  }
  return p;
}

std::uint32_t Placer::moved_plane(const ObjectTree& object, std::uint32_t t_plane, const RigidMotion& m) {
  std::uint32_t& to = plane_map_[t_plane >> 1];
  if (to == kNull) to = host_.planes().add(m.apply(object.tree().planes[t_plane & ~1u]));
  return to ^ (t_plane & 1u);
}

std::uint32_t Placer::moved_fragment(const ObjectTree& object, std::uint32_t f, const RigidMotion& m, std::uint32_t k) {
  const FragmentView v = object.tree().fragments[f];
  scratch_.verts.resize(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) scratch_.verts[i] = Vertex{m.apply(v.p[i])};
  scratch_.source = host_.source_base(k) + v.source;
  return host_.add_fragment(scratch_, moved_plane(object, object.tree().fragment_plane[f], m));
}

std::uint32_t Placer::load(const ObjectTree& object, const RigidMotion& m, std::uint32_t k) {
  const Tree& t = object.tree();
  parts_.clear();
  plane_map_.assign(t.planes.size() / 2, kNull);
  for (std::uint32_t i = 0; i < t.nodes.size(); ++i) {
    PartNode p{moved_plane(object, t.nodes[i].plane, m), t.nodes[i].front, t.nodes[i].back, {}};
    const FragmentRange r = t.fragments_of(i);
    for (std::uint32_t f = r.begin; f < r.end; ++f) p.frags.push_back(moved_fragment(object, f, m, k));
    parts_.push_back(std::move(p));
  }
  return t.nodes.empty() ? kNull : 0;
}

std::uint32_t Placer::make_part(std::uint32_t plane, std::vector<std::uint32_t> frags, std::uint32_t front,
                                std::uint32_t back) {
  if (frags.empty() && front == kNull) return back;
  if (frags.empty() && back == kNull) return front;
  parts_.push_back({plane, front, back, std::move(frags)});
  return static_cast<std::uint32_t>(parts_.size() - 1);
}

// Post-order on explicit stacks: a node's parts are made once both children's are.
std::pair<std::uint32_t, std::uint32_t> Placer::partition(std::uint32_t part, const Plane& h,
                                                          std::vector<std::uint32_t>& on, UpdateWork& work) {
  const double eps = host_.tol().plane_eps;
  std::vector<std::pair<std::uint32_t, bool>> stack{{part, false}};
  std::vector<std::pair<std::uint32_t, std::uint32_t>> done;  // (plus, minus) of finished subtrees
  while (!stack.empty()) {
    const auto [t, expanded] = stack.back();
    stack.pop_back();
    const std::uint32_t tf = parts_[t].front, tb = parts_[t].back;
    if (!expanded) {
      stack.push_back({t, true});
      if (tf != kNull) stack.push_back({tf, false});
      if (tb != kNull) stack.push_back({tb, false});
      continue;
    }
    ++work.partitioned_nodes;
    std::pair<std::uint32_t, std::uint32_t> front{kNull, kNull}, back{kNull, kNull};
    if (tf != kNull) front = done.back(), done.pop_back();
    if (tb != kNull) back = done.back(), done.pop_back();
    std::vector<std::uint32_t> plus, minus;
    for (const std::uint32_t id : parts_[t].frags) {
      switch (host_.store().classify(id, h, eps)) {
        case Side::Coplanar: on.push_back(id); break;
        case Side::Front: plus.push_back(id); break;
        case Side::Back: minus.push_back(id); break;
        case Side::Spanning: {
          const std::uint32_t owner = host_.owner_of_fragment(id);
          const FragmentStore::Parts r = host_.store().split(id, h, eps);
          host_.count_split(owner, r);
          if (r.front != FragmentStore::kNone) plus.push_back(r.front);
          if (r.back != FragmentStore::kNone) minus.push_back(r.back);
          break;
        }
      }
    }
    const std::uint32_t plane = parts_[t].plane;
    const std::uint32_t p = make_part(plane, std::move(plus), front.first, back.first);
    const std::uint32_t q = make_part(plane, std::move(minus), front.second, back.second);
    done.push_back({p, q});
  }
  return done.back();
}

void Placer::hang(std::uint32_t part, Slot slot, std::uint32_t owner, Placement* whole, UpdateWork& work) {
  std::vector<std::pair<std::uint32_t, Slot>> stack{{part, slot}};
  while (!stack.empty()) {
    const auto [t, at] = stack.back();
    stack.pop_back();
    const std::uint32_t n = host_.add_node(at, parts_[t].plane, owner);
    host_.add_fragments(n, parts_[t].frags);
    ++work.nodes_built;
    if (whole) whole->nodes[t] = n;
    if (parts_[t].back != kNull) stack.push_back({parts_[t].back, Slot{n, false}});
    if (parts_[t].front != kNull) stack.push_back({parts_[t].front, Slot{n, true}});
  }
}

// Another object's node on the way: that object no longer owns its cell alone.
void Placer::touch(std::uint32_t host_node, std::uint32_t k, std::vector<Placement>& placements) const {
  const std::uint32_t owner = host_.node(host_node).owner;
  if (owner != kStaticOwner && owner != k + 1 && owner - 1 < placements.size()) placements[owner - 1].whole = false;
}

// Torres' separating plane: halfway across the gap between the two spheres, facing the newcomer.
bool Placer::try_separate(std::uint32_t h, std::uint32_t k, std::uint32_t part, Placement& p,
                          std::vector<Placement>& placements, std::span<const BoundingSphere> spheres, UpdateWork& work) {
  const std::uint32_t owner = host_.node(h).owner;
  if (owner == kStaticOwner || owner == k + 1 || owner - 1 >= placements.size()) return false;
  const std::uint32_t j = owner - 1;
  if (!placements[j].whole || placements[j].root != h) return false;
  const Vec3 between = spheres[k].center - spheres[j].center;
  const double gap = length(between) - spheres[k].radius - spheres[j].radius;
  if (gap <= 2 * host_.tol().plane_eps) return false;
  const Vec3 u = normalize(between);
  const std::uint32_t plane = host_.planes().add(Plane::through(u, spheres[j].center + u * (spheres[j].radius + gap / 2)));
  const std::uint32_t sep = host_.insert_above(h, plane, k + 1, false);
  ++work.nodes_built;
  placements[j].path.push_back(PlanePool::flip(plane));
  p.path.push_back(plane);
  hang(part, Slot{sep, true}, k + 1, &p, work);
  p.root = host_.node(sep).front;
  return true;
}

Placement Placer::place(const ObjectTree& object, const RigidMotion& m, std::uint32_t k,
                        std::vector<Placement>& placements, std::span<const BoundingSphere> spheres, UpdateWork& work) {
  ++work.objects_placed;
  host_.count_input(k + 1, object.tree().stats);
  Placement p;
  const std::uint32_t root = load(object, m, k);
  if (root == kNull) return p;
  p.whole = true;
  p.nodes.assign(object.tree().nodes.size(), kNull);
  const BoundingSphere s = spheres[k];
  const double eps = host_.tol().plane_eps;
  std::vector<std::uint32_t> on;
  std::vector<std::pair<Slot, std::uint32_t>> stack{{Slot{}, root}};
  while (!stack.empty()) {
    const auto [slot, part] = stack.back();
    stack.pop_back();
    const std::uint32_t h = host_.child_at(slot);
    if (h == kNull) {
      hang(part, slot, k + 1, p.whole ? &p : nullptr, work);
      if (p.whole) p.root = host_.child_at(slot);
      continue;
    }
    if (separate_ && p.whole && try_separate(h, k, part, p, placements, spheres, work)) continue;
    touch(h, k, placements);
    const std::uint32_t hp = host_.node(h).plane;
    const Plane plane = host_.planes()[hp];
    const double d = plane.distance(s.center);
    if (d - s.radius > eps || d + s.radius < -eps) {
      const bool front = d > 0;
      p.path.push_back(front ? hp : PlanePool::flip(hp));
      stack.push_back({Slot{h, front}, part});
      continue;
    }
    p.whole = false;
    on.clear();
    const auto [plus, minus] = partition(part, plane, on, work);
    host_.add_fragments(h, on);
    if (minus != kNull) stack.push_back({Slot{h, false}, minus});
    if (plus != kNull) stack.push_back({Slot{h, true}, plus});
  }
  if (!p.whole) p = Placement{};
  work.objects_whole += p.whole;
  return p;
}

void Placer::move_in_place(const ObjectTree& object, const RigidMotion& m, std::uint32_t k, const Placement& p,
                           UpdateWork& work) {
  const Tree& t = object.tree();
  plane_map_.assign(t.planes.size() / 2, kNull);
  for (std::uint32_t i = 0; i < t.nodes.size(); ++i) {
    DynNode& n = host_.node(p.nodes[i]);
    n.plane = moved_plane(object, t.nodes[i].plane, m);
    const FragmentRange r = t.fragments_of(i);
    for (std::uint32_t f = r.begin; f < r.end; ++f) {
      std::uint32_t& id = host_.node(p.nodes[i]).frags[f - r.begin];
      host_.store().release(id);
      id = moved_fragment(object, f, m, k);
    }
    ++work.moved_nodes;
  }
}

}  // namespace bsp
