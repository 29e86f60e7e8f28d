#include "search/optimal.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "common/errors.h"
#include "common/rng.h"
#include "geometry/polytope.h"
#include "geometry/segment2.h"
#include "search/decisions.h"
#include "split/splitter.h"
#include "tree/build.h"
#include "tree/build_input.h"
#include "tree/leaf_cell.h"

namespace bsp {

const char* objective_name(OptimalObjective o) {
  switch (o) {
    case OptimalObjective::Fragments: return "fragments";
    case OptimalObjective::EPoint: return "e_point";
    case OptimalObjective::ELine: return "e_line";
  }
  return "?";
}

std::optional<OptimalObjective> objective_named(std::string_view name) {
  for (auto o : {OptimalObjective::Fragments, OptimalObjective::EPoint, OptimalObjective::ELine})
    if (name == objective_name(o)) return o;
  return std::nullopt;
}

namespace {

constexpr std::uint32_t kNone = 0xffffffffu;
constexpr std::uint32_t kLeaf = 0xfffffffeu;
constexpr double kInf = std::numeric_limits<double>::infinity();
// The expected costs are sums of doubles whose order differs between a bound and the value it
// bounds: a bound within this relative distance of another counts as reaching it.
constexpr double kCostSlack = 1e-12;
// Each pass of the search raises its target by this share of the proved lower bound (to the next
// whole number for the fragments): small steps keep each pass's bound tight, and their passes are
// cheap because the memo keeps every bound proved. At 32 segments (E_point) 2% takes 4 to 7 s where
// one pass against the greedy tree takes 7 to 11.
constexpr double kTargetStep = 0.02;
// Seeds of the memo's hashes, one per table, so that a cell key and a state key of the same numbers
// do not hash alike by construction.
constexpr std::uint64_t kCellHashSeed = 0xce11, kStateHashSeed = 0x5eed;
// The clock is read at one budget check in 256: a check costs a few nanoseconds, a clock read tens.
constexpr std::uint64_t kClockEvery = 255;

// One way to cut a state: the plane of one of its fragments and what it leaves on each side.
struct Candidate {
  std::uint32_t plane = kNone;  // pooled, oriented as the fragment it came from
  double own = 0;               // the node's own term of the objective
  std::uint32_t front = kNone, back = kNone;  // child states; kNone for an empty side
  double floor = 0;  // a bound a refinement proved without raising its children's bounds enough to show
};

// A subproblem: a cell's fragments (interned ids; sorted by id, or by source for the cost
// objectives, whose key they are: intern_state) and, for the cost objectives, the cell.
struct State {
  std::vector<std::uint32_t> frags;
  std::uint32_t cell = kNone;
  double lb = 0, ub = kInf;
  std::uint32_t choice = kNone;  // the candidate achieving ub, or kLeaf
  std::uint32_t cand_begin = 0, cand_end = 0;  // its candidates in Solver::cands_, once expanded
  bool expanded = false;
  std::uint32_t visited = 0;  // the last descent that met it
};

// A cell and its terms of the objective. A cell is the root box cut by the planes on a path, and
// paths that cut in another order, or by a plane another cut has made redundant, reach the same
// cell: its key is the set of pooled planes (oriented towards it) that bound one of its faces, so
// those paths share it.
struct Cell {
  ConvexPolytope poly;
  double volume_share = 0, area_share = 0;  // of the root cell's
  std::vector<std::uint32_t> planes;        // the key: sorted oriented plane ids with a face on them
};

std::uint64_t mix(std::uint64_t h, std::uint64_t v) { return splitmix64(h ^ v); }
std::uint64_t bits(double d) { return std::bit_cast<std::uint64_t>(d == 0.0 ? 0.0 : d); }

class Solver {
 public:
  Solver(const OptimalSettings& settings, TreeDraft& draft, bool planar, std::uint32_t planes)
      : s_(settings), draft_(draft), eps_(draft.tol.plane_eps), planar_(planar), planes_(planes) {
    start_ = std::chrono::steady_clock::now();
  }

  std::uint32_t root(std::vector<std::uint32_t> ids) {
    for (auto id : ids) remember_fragment(id);
    std::uint32_t cell = kNone;
    if (s_.objective != OptimalObjective::Fragments) {
      const ConvexPolytope box = ConvexPolytope::box(draft_.bounds.enlarged(s_.cell_margin));
      std::tie(root_volume_, root_area_) = measures(box);
      if (!(root_volume_ > 0)) throw UsageError("optimal: expected costs need a root cell with volume; use a margin > 0");
      cell = intern_cell(box, {});
    }
    return intern_state(std::move(ids), cell);
  }

  // Follows the least-bound candidate from `s` down (expanding what it meets) and gives each state
  // on that tree its value as an upper bound and choice where that is lower than what it has. On
  // fresh states it is the greedy tree, the first incumbent; after a pass of the search it is the
  // tree the pass's bounds point to, so the incumbent improves while the bound rises. A budgeted
  // descent stops where a state would need expanding past the state budget; the bounds it has set
  // by then are each a whole subtree's value. The first descent, which gives the root its first
  // tree, is not budgeted.
  void descend(std::uint32_t s, bool budgeted) {
    struct Item {
      std::uint32_t state;
      std::uint32_t cand;  // kNone on the way down; the candidate followed on the way up
    };
    ++epoch_;
    std::vector<Item> stack{{s, kNone}};
    while (!stack.empty()) {
      const Item item = stack.back();
      stack.pop_back();
      if (item.cand == kNone) {
        // A state shared by two branches is finished before the second meets it (the memo's
        // subproblems form a DAG), so one visit per descent is enough.
        if (states_[item.state].visited == epoch_) continue;
        states_[item.state].visited = epoch_;
        if (budgeted && !states_[item.state].expanded && states_.size() >= s_.max_states) return;
        expand(item.state);
        const State& st = states_[item.state];
        if (st.choice == kLeaf || known(item.state)) continue;
        std::uint32_t best = kNone;
        for (auto c = st.cand_begin; c < st.cand_end; ++c)
          if (best == kNone || candidate_lb(c) < candidate_lb(best)) best = c;
        stack.push_back({item.state, best});
        for (auto child : {cands_[best].front, cands_[best].back})
          if (child != kNone) stack.push_back({child, kNone});
      } else {
        State& st = states_[item.state];
        if (const double value = candidate_ub(item.cand); value < st.ub) {
          st.ub = value;
          st.choice = item.cand;
        }
      }
    }
  }

  // Solves `s` by targets raised from its lower bound: each pass proves the value reaches the
  // target or finds a tree below it. Searched against the greedy tree's value alone, the first
  // candidates are refined deep under a loose bound and the lower bound rises only at the end; by
  // small targets it rises pass by pass, each pass bounded tightly and reusing the memo's bounds
  // (iterative deepening [Korf1985] on the bound), so a budget that runs out leaves a useful interval.
  void deepen(std::uint32_t s) {
    expand(s);
    for (std::uint64_t pass = 1; !known(s) && !out_of_budget(); ++pass) {
      solve(s, next_target(states_[s]));
      if (!budget_hit_) descend(s, true);
      if (s_.on_pass) s_.on_pass({pass, states_[s].lb, states_[s].ub, states_.size(), elapsed()});
    }
  }
  // Fragments are whole numbers, so their target is the next one: a fractional target would leave
  // a fractional bound that proves no more. A cost's bound of 0 (E_point of coarse and leafy trees)
  // steps by a share of the incumbent instead.
  double next_target(const State& st) const {
    if (s_.objective == OptimalObjective::Fragments) return std::floor(st.lb) + 1;
    return st.lb + (st.lb > 0 ? kTargetStep * st.lb : kTargetStep * st.ub);
  }

  // Refines `s` until its value is known or proved at least `beta` (or the budget runs out).
  void solve(std::uint32_t s, double beta) {
    if (settled(s, beta)) return;
    expand(s);
    for (;;) {
      State& st = states_[s];
      const double bound = std::min(beta, st.ub);
      std::uint32_t best = kNone;
      double least = kInf;
      for (auto c = st.cand_begin; c < st.cand_end; ++c) {
        const double lb = candidate_lb(c);
        least = std::min(least, lb);
        if (!reaches(lb, bound) && (best == kNone || lb < candidate_lb(best))) best = c;
      }
      st.lb = std::max(st.lb, std::min(least, st.ub));
      if (best == kNone || out_of_budget()) return;
      refine(s, best, bound);
    }
  }

  const State& state(std::uint32_t s) const { return states_[s]; }
  const Candidate& candidate(std::uint32_t c) const { return cands_[c]; }
  const PlanePool& planes() const { return draft_.planes; }
  double leaf_cost(const State& st) const { return leaf_term(st.frags.size(), st.cell); }
  OptimalStats stats() {
    stats_.states = states_.size();
    stats_.candidates = cands_.size();
    stats_.fragments = frag_index_.size();
    stats_.seconds = elapsed();
    return stats_;
  }

 private:
  bool settled(std::uint32_t s, double beta) const {
    const State& st = states_[s];
    return reaches(st.lb, std::min(beta, st.ub));
  }
  bool known(std::uint32_t s) const { return reaches(states_[s].lb, states_[s].ub); }
  bool reaches(double lb, double bound) const {
    if (s_.objective == OptimalObjective::Fragments) return lb >= bound;
    return lb >= bound - kCostSlack * std::max(1.0, std::abs(bound));
  }
  double lb_of(std::uint32_t s) const { return s == kNone ? 0.0 : states_[s].lb; }
  double ub_of(std::uint32_t s) const { return s == kNone ? 0.0 : states_[s].ub; }
  double candidate_lb(std::uint32_t c) const {
    const Candidate& k = cands_[c];
    return std::max(k.floor, k.own + lb_of(k.front) + lb_of(k.back));
  }
  double candidate_ub(std::uint32_t c) const {
    const Candidate& k = cands_[c];
    return k.own + ub_of(k.front) + ub_of(k.back);
  }

  // Solves the candidate's front side with the bound it must beat given the back's lower bound,
  // then (if the front is solved) the back with what remains.
  void refine(std::uint32_t s, std::uint32_t c, double bound) {
    const Candidate k = cands_[c];
    if (k.front != kNone) solve(k.front, bound - k.own - lb_of(k.back));
    const bool front_known = k.front == kNone || known(k.front);
    if (front_known && k.back != kNone) solve(k.back, bound - k.own - ub_of(k.front));
    const bool back_known = k.back == kNone || known(k.back);
    State& st = states_[s];
    if (front_known && back_known) {
      const double value = candidate_ub(c);
      if (value < st.ub) {
        st.ub = value;
        st.choice = c;
      }
      cands_[c].floor = std::max(cands_[c].floor, value);
    } else if (!budget_hit_) {
      // The children proved their bounds; their sum reaches `bound` up to rounding.
      cands_[c].floor = std::max(cands_[c].floor, bound);
    }
  }

  bool out_of_budget() {
    if (budget_hit_) return true;
    if (states_.size() >= s_.max_states) stats_.out_of_states = budget_hit_ = true;
    if ((++budget_checks_ & kClockEvery) == 0 && elapsed() > s_.seconds) stats_.out_of_time = budget_hit_ = true;
    return budget_hit_;
  }
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  // The objective's term of a leaf of `count` fragments (coarse and leafy shapes) in `cell`.
  double leaf_term(std::size_t count, std::uint32_t cell) const {
    switch (s_.objective) {
      case OptimalObjective::Fragments: return static_cast<double>(count);
      case OptimalObjective::EPoint: return 0.0;
      case OptimalObjective::ELine: return cells_[cell].area_share;
    }
    return 0.0;
  }
  // The term of a node with a plane that keeps `coplanar` fragments.
  double node_term(std::size_t coplanar, std::uint32_t cell) const {
    switch (s_.objective) {
      case OptimalObjective::Fragments: return static_cast<double>(coplanar);
      case OptimalObjective::EPoint: return cells_[cell].volume_share;
      case OptimalObjective::ELine: return cells_[cell].area_share;
    }
    return 0.0;
  }
  // A bound on f(S) before S is expanded: each sturdy fragment leaves at least one stored piece;
  // a strict tree gives every non-empty cell a node with a plane; every node's cell meets its share
  // of lines.
  double initial_lb(const std::vector<std::uint32_t>& frags, std::uint32_t cell) const {
    switch (s_.objective) {
      case OptimalObjective::Fragments:
        return static_cast<double>(std::count_if(frags.begin(), frags.end(), [&](auto id) { return sturdy(id); }));
      case OptimalObjective::EPoint: return s_.shape == Shape::Strict ? cells_[cell].volume_share : 0.0;
      case OptimalObjective::ELine: return cells_[cell].area_share;
    }
    return 0.0;
  }

  // Whether some piece of the fragment survives every tree. A split drops a part as a sliver when
  // its area over its longest edge is below eps (a segment part: shorter than eps), and the k other
  // planes cut a fragment into at most as many pieces as their lines make cells in its plane,
  // k²/2 + k/2 + 1 (k + 1 for a segment). Every piece dropped has an area below eps times the
  // fragment's diameter, which no piece's longest edge exceeds, so a fragment whose area over its
  // diameter is at least eps times that many pieces (with a factor 2 for the rounding of cut
  // points) keeps one. Inputs away from the tolerance have no fragment that is not sturdy.
  bool sturdy(std::uint32_t id) const {
    const auto p = draft_.store.points(id);
    const double k = planes_;
    if (p.size() == 2) return length(p[1] - p[0]) >= 2 * eps_ * (k + 1);
    const double reach = 2 * eps_ * (k * k / 2 + k / 2 + 1);
    double diameter = 0;
    for (const Vec3& a : p)
      for (const Vec3& b : p) diameter = std::max(diameter, length(b - a));
    return diameter > 0 && fragment_measure(id) / diameter >= reach;
  }

  double fragment_measure(std::uint32_t id) const {
    const auto p = draft_.store.points(id);
    if (p.size() == 2) return length(p[1] - p[0]);
    return 0.5 * length(newell_normal(p));
  }

  void expand(std::uint32_t s) {
    if (states_[s].expanded) return;
    ++stats_.expansions;
    const std::vector<std::uint32_t> ids = states_[s].frags;
    const std::uint32_t cell = states_[s].cell;
    const bool leaf = (s_.shape == Shape::Coarse && is_convex_set(ids, draft_.store, draft_.planes, eps_)) ||
                      (s_.shape == Shape::Leafy && !convexity_witness(ids, draft_.store, draft_.planes, eps_));
    if (leaf) {
      State& st = states_[s];
      st.lb = st.ub = leaf_term(ids.size(), cell);
      st.choice = kLeaf;
      st.expanded = true;
      return;
    }
    const auto begin = static_cast<std::uint32_t>(cands_.size());
    std::vector<std::uint32_t> seen;
    for (auto id : ids) {
      const std::uint32_t p = draft_.store.plane(id);
      const std::uint32_t key = s_.shape == Shape::Leafy ? p : p >> 1;
      if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
      seen.push_back(key);
      const Plane plane = draft_.planes[p];
      if (s_.shape == Shape::Leafy && !parts_leafy(ids, draft_.store, draft_.planes, plane, eps_)) continue;
      cands_.push_back(cut(ids, cell, p));
    }
    State& st = states_[s];
    st.cand_begin = begin;
    st.cand_end = static_cast<std::uint32_t>(cands_.size());
    st.expanded = true;
  }

  // The candidate of plane `p` for fragments `ids` in `cell`, as the build loop partitions them.
  Candidate cut(const std::vector<std::uint32_t>& ids, std::uint32_t cell, std::uint32_t p) {
    const Plane plane = draft_.planes[p];
    std::vector<std::uint32_t> front, back;
    std::size_t coplanar = 0;
    for (auto id : ids) {
      switch (draft_.store.classify(id, plane, eps_)) {
        case Side::Front: front.push_back(id); break;
        case Side::Back: back.push_back(id); break;
        case Side::Coplanar:
          if (s_.shape != Shape::Leafy) {
            ++coplanar;
          } else {
            (dot(draft_.planes[draft_.store.plane(id)].n, plane.n) > 0 ? front : back).push_back(id);
          }
          break;
        case Side::Spanning: {
          const auto [f, b] = split(id, p);
          if (f != kNone) front.push_back(f);
          if (b != kNone) back.push_back(b);
          break;
        }
      }
    }
    Candidate k;
    k.plane = p;
    k.own = node_term(coplanar, cell);
    std::uint32_t front_cell = kNone, back_cell = kNone;
    if (cell != kNone) {
      if (!front.empty()) front_cell = child_cell(cell, p);
      if (!back.empty()) back_cell = child_cell(cell, PlanePool::flip(p));
    }
    if (!front.empty()) k.front = intern_state(std::move(front), front_cell);
    if (!back.empty()) k.back = intern_state(std::move(back), back_cell);
    return k;
  }

  // Fragment `id` split by pooled plane `p` as FragmentStore::split does, without releasing it
  // (memoised states still hold it); the parts interned. Memoised per (fragment, plane).
  std::pair<std::uint32_t, std::uint32_t> split(std::uint32_t id, std::uint32_t p) {
    const std::uint64_t key = (std::uint64_t{id} << 32) | p;
    if (auto it = splits_.find(key); it != splits_.end()) return it->second;
    draft_.store.view(id).copy_to(whole_);
    const SplitKept kept = whole_.verts.size() == 2 ? split_segment_into(whole_, draft_.planes[p], eps_, front_, back_)
                                                    : split_into(whole_, draft_.planes[p], eps_, front_, back_);
    const std::uint32_t support = draft_.store.plane(id);
    const std::pair<std::uint32_t, std::uint32_t> parts{kept.front ? intern_fragment(front_, support) : kNone,
                                                         kept.back ? intern_fragment(back_, support) : kNone};
    splits_.emplace(key, parts);
    return parts;
  }

  std::uint64_t fragment_hash(std::uint32_t id) const {
    std::uint64_t h = mix(draft_.store.source(id), draft_.store.plane(id));
    for (const Vec3& v : draft_.store.points(id)) h = mix(mix(mix(h, bits(v.x)), bits(v.y)), bits(v.z));
    return h;
  }
  void remember_fragment(std::uint32_t id) { frag_index_.emplace(fragment_hash(id), id); }
  // The id of a fragment of the same source, plane and vertices as `poly`, adding it if new.
  std::uint32_t intern_fragment(const Polygon& poly, std::uint32_t support) {
    const std::uint32_t id = draft_.store.add(poly, support);
    const std::uint64_t h = fragment_hash(id);
    const auto [lo, hi] = frag_index_.equal_range(h);
    for (auto it = lo; it != hi; ++it) {
      const auto a = draft_.store.points(it->second), b = draft_.store.points(id);
      if (draft_.store.source(it->second) == poly.source && draft_.store.plane(it->second) == support &&
          std::equal(a.begin(), a.end(), b.begin(), b.end(),
                     [](const Vec3& x, const Vec3& y) { return x.x == y.x && x.y == y.y && x.z == y.z; })) {
        draft_.store.release(id);  // the newest id and span: the next add reuses them
        return it->second;
      }
    }
    frag_index_.emplace(h, id);
    return id;
  }

  // As metrics/expected_cost.h measures cells: volume and surface area, or a 2D cell's area and
  // perimeter.
  std::pair<double, double> measures(const ConvexPolytope& cell) const {
    if (!planar_) return {cell.volume(), cell.surface_area()};
    const ConvexPolytope::Section s = cell.top_section();
    return {s.area, s.perimeter};
  }

  // The part of `cell` in front of pooled plane `p`, interned by its key: the parent's planes and
  // `p`, less those that no longer bound a face. A cell clipped away entirely keeps every plane, so
  // it cannot take the key of a larger cell.
  std::uint32_t child_cell(std::uint32_t cell, std::uint32_t p) {
    ConvexPolytope poly = cells_[cell].poly.clipped(draft_.planes[p], eps_);
    std::vector<std::uint32_t> key = cells_[cell].planes;
    // A plane already bounding the cell has its fragments stored above or sent to one side (leafy),
    // so no candidate repeats it; a repeat would give one cell two keys.
    assert(!std::binary_search(key.begin(), key.end(), p) &&
           !std::binary_search(key.begin(), key.end(), PlanePool::flip(p)));
    key.insert(std::upper_bound(key.begin(), key.end(), p), p);
    if (!poly.empty())
      std::erase_if(key, [&](std::uint32_t q) { return !has_face_on(poly, draft_.planes[q]); });
    return intern_cell(std::move(poly), std::move(key));
  }
  // Whether a face of `poly` lies on `plane`: all its vertices within the tolerance of it.
  bool has_face_on(const ConvexPolytope& poly, const Plane& plane) const {
    for (std::size_t f = 0; f < poly.face_count(); ++f) {
      const auto face = poly.face(f);
      if (std::all_of(face.begin(), face.end(), [&](const Vec3& v) { return std::abs(plane.distance(v)) <= eps_; }))
        return true;
    }
    return false;
  }

  // The cell of `key`, measured the first time a path reaches it.
  std::uint32_t intern_cell(ConvexPolytope poly, std::vector<std::uint32_t> key) {
    std::uint64_t h = mix(kCellHashSeed, key.size());
    for (auto q : key) h = mix(h, q);
    const auto [lo, hi] = cell_index_.equal_range(h);
    for (auto it = lo; it != hi; ++it)
      if (cells_[it->second].planes == key) return it->second;
    Cell c;
    const auto [volume, area] = measures(poly);
    c.volume_share = volume / root_volume_;
    c.area_share = area / root_area_;
    c.poly = std::move(poly);
    c.planes = std::move(key);
    cells_.push_back(std::move(c));
    const auto index = static_cast<std::uint32_t>(cells_.size() - 1);
    cell_index_.emplace(h, index);
    return index;
  }

  // A state of the fragments objective is its fragment set, whatever its cell. A state of an
  // expected cost is its cell, which decides which fragments it holds: a convex cell holds at most
  // one piece of each input fragment, so its sources name them, while their vertices may differ in
  // the last bits between paths that cut in different orders (the sources stay in the key, so a
  // piece the tolerance dropped on one path only keeps the states apart).
  std::uint32_t intern_state(std::vector<std::uint32_t> frags, std::uint32_t cell) {
    const auto key = [&](std::uint32_t id) { return cell == kNone ? id : draft_.store.source(id); };
    std::sort(frags.begin(), frags.end(), [&](auto a, auto b) { return key(a) < key(b); });
    std::uint64_t h = mix(kStateHashSeed, cell);
    for (auto id : frags) h = mix(h, key(id));
    const auto [lo, hi] = state_index_.equal_range(h);
    for (auto it = lo; it != hi; ++it) {
      const State& st = states_[it->second];
      if (st.cell == cell && std::equal(st.frags.begin(), st.frags.end(), frags.begin(), frags.end(),
                                        [&](auto a, auto b) { return key(a) == key(b); })) {
        ++stats_.memo_hits;
        return it->second;
      }
    }
    State st;
    st.lb = initial_lb(frags, cell);
    st.frags = std::move(frags);
    st.cell = cell;
    states_.push_back(std::move(st));
    const auto index = static_cast<std::uint32_t>(states_.size() - 1);
    state_index_.emplace(h, index);
    return index;
  }

  const OptimalSettings& s_;
  TreeDraft& draft_;
  const double eps_;
  const bool planar_;
  const std::uint32_t planes_;  // distinct planes of the input
  std::chrono::steady_clock::time_point start_;
  double root_volume_ = 1, root_area_ = 1;
  std::vector<State> states_;
  std::vector<Candidate> cands_;
  std::vector<Cell> cells_;
  std::unordered_multimap<std::uint64_t, std::uint32_t> state_index_, frag_index_, cell_index_;
  std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> splits_;
  Polygon whole_, front_, back_;
  OptimalStats stats_;
  std::uint64_t budget_checks_ = 0;
  std::uint32_t epoch_ = 0;  // descents so far
  bool budget_hit_ = false;
};

std::uint32_t distinct_planes(const TreeDraft& draft, std::span<const std::uint32_t> ids) {
  std::vector<std::uint32_t> keys;
  for (auto id : ids) keys.push_back(draft.store.plane(id) >> 1);
  std::sort(keys.begin(), keys.end());
  return static_cast<std::uint32_t>(std::unique(keys.begin(), keys.end()) - keys.begin());
}

}  // namespace

bool OptimalResult::optimal() const {
  if (objective == OptimalObjective::Fragments) return lower >= upper;
  return lower >= upper - kCostSlack * std::max(1.0, std::abs(upper));
}

OptimalResult solve_optimal(std::span<const Polygon> input, const OptimalSettings& settings) {
  OptimalResult out;
  out.objective = settings.objective;
  out.shape = settings.shape;
  TreeDraft draft;
  draft.shape = settings.shape;
  std::vector<std::uint32_t> ids = load_input(input, draft);
  const std::uint32_t planes = distinct_planes(draft, ids);
  if (planes > settings.max_planes)
    throw UsageError("optimal: the input has " + std::to_string(planes) + " distinct planes, more than max_planes " +
                     std::to_string(settings.max_planes));
  BuildOptions options;
  options.shape = settings.shape;
  options.min_task_fragments = std::numeric_limits<std::size_t>::max();
  if (ids.empty()) {
    DecisionSplitter none(std::make_shared<const Decisions>(), nullptr);
    out.tree = build_tree(input, none, options);
    return out;
  }
  Solver solver(settings, draft, all_segments(input), planes);
  const std::uint32_t root = solver.root(std::move(ids));
  solver.descend(root, false);
  out.greedy = solver.state(root).ub;
  solver.deepen(root);

  // Walk the tree of choices from the root, summing its value and recording each node's plane.
  auto choices = std::make_shared<Decisions>();
  struct Item {
    std::uint32_t state;
    std::uint64_t key;
  };
  std::vector<Item> stack{{root, SplitContext::kRootKey}};
  double value = 0;
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const State& st = solver.state(item.state);
    if (st.choice == kLeaf) {
      value += solver.leaf_cost(st);
      continue;
    }
    const Candidate& c = solver.candidate(st.choice);
    value += c.own;
    choices->emplace(item.key, Decision{solver.planes()[c.plane], false});
    if (c.back != kNone) stack.push_back({c.back, SplitContext::child_key(item.key, false)});
    if (c.front != kNone) stack.push_back({c.front, SplitContext::child_key(item.key, true)});
  }
  out.upper = value;
  out.lower = std::min(solver.state(root).lb, value);
  out.stats = solver.stats();
  out.stats.planes = planes;
  DecisionSplitter replay(choices, nullptr);
  out.tree = build_tree(input, replay, options);
  return out;
}

}  // namespace bsp
