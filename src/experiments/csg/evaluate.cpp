// Notation: an operand is what a step of the program pushes: the empty solid, a leaf not yet built
// (a hull of leaves needs only their points), or a solid tree. K is the kernel: FloatKernel or
// ExactKernel below, each a box or space and the operations of solid trees in it.
#include "experiments/csg/evaluate.h"

#include <optional>

#include "common/errors.h"
#include "csg/shapes2d.h"
#include "experiments/job.h"
#include "solid/boundary.h"
#include "solid/exact_merge.h"
#include "solid/solid_build.h"
#include "validate/exact_solid.h"
#include "validate/exact_solid_check.h"

namespace bsp::experiments {

namespace {

SetOp set_op(StepKind kind) {
  return kind == StepKind::Union ? SetOp::Union : kind == StepKind::Intersection ? SetOp::Intersection : SetOp::Difference;
}

// A step's counters: summed over its merges; its result's sizes are its last merge's.
void add(MergeStats& total, const MergeStats& one) {
  total.partition_calls += one.partition_calls;
  total.partition_nodes += one.partition_nodes;
  total.shp_splits += one.shp_splits;
  total.merge_nodes += one.merge_nodes;
  total.cell_ops += one.cell_ops;
  total.complement_nodes += one.complement_nodes;
  total.inconsistent += one.inconsistent;
  total.pruned += one.pruned;
  total.compactions += one.compactions;
  total.compacted_nodes += one.compacted_nodes;
  total.before = one.before;
  total.after = one.after;
  total.merge_seconds += one.merge_seconds;
  total.reduce_seconds += one.reduce_seconds;
}

Box leaves_box(const csg::Postfix& postfix) {
  Box box;
  for (const csg::Leaf& leaf : postfix.leaves)
    for (const Polygon& p : leaf.polygons)
      for (const Vertex& v : p.verts) box.add(v.p);
  return box;
}

struct FloatKernel {
  using Tree = SolidTree;
  Box box;

  Tree build(std::span<const Polygon> polys, Splitter& splitter, CsgLeafCost& cost, std::uint64_t& dropped) const {
    SolidBuild b = build_solid(polys, splitter, box);
    cost.fragments = b.fragments;
    cost.seconds = b.seconds();
    dropped += b.build.dropped_input;
    return std::move(b.solid);
  }
  MergeOptions options;
  Tree merge(const Tree& a, const Tree& b, SetOp op, MergeStats& stats) { return bsp::merge(a, b, op, &stats, options); }
  void release(const Tree&, const Tree&) {}  // float trees own their geometry
  static SolidSize size(const Tree& t) { return solid_size(t); }
  LoopPool boundary(const Tree& t) { return solid_boundary(t); }
  std::vector<Vec3> boundary_points(const Tree& t) const { return solid_boundary(t).points; }
  double eps() const { return Tolerance::for_extent(box.diagonal()).plane_eps; }
};

struct ExactKernel {
  using Tree = ExactSolidTree;
  std::unique_ptr<ExactSolidSpace> space;
  Box box;
  std::vector<PlanePolygon> faces;  // the result's boundary, kept for the proof

  Tree build(std::span<const Polygon> polys, Splitter& splitter, CsgLeafCost& cost, std::uint64_t& dropped) const {
    ExactSolidBuild b = build_exact_solid(polys, splitter, *space);
    cost.fragments = b.fragments;
    cost.seconds = b.seconds();
    dropped += b.build.dropped_input;
    return std::move(b.solid);
  }
  MergeOptions options;
  Tree merge(const Tree& a, const Tree& b, SetOp op, MergeStats& stats) {
    return bsp::merge(a, b, *space, op, &stats, options);
  }
  // The operands' sub-hyperplanes the result does not use go back to the space's store, so memory
  // follows the live trees, not the program's length.
  void release(const Tree& operand, const Tree& result) { discard(operand, result, Tree{}, *space); }
  static SolidSize size(const Tree& t) { return solid_size(t); }
  // The result's boundary, its exact faces kept for the proof.
  LoopPool boundary(const Tree& t) {
    faces = exact_solid_boundary(t, *space);
    LoopPool loops;
    for (const PlanePolygon& f : faces) loops.add(vertex_positions(f, space->grid()));
    return loops;
  }
  // An operand's boundary vertices, for a hull; the result's faces stay as they are.
  std::vector<Vec3> boundary_points(const Tree& t) const {
    std::vector<Vec3> out;
    for (const PlanePolygon& f : exact_solid_boundary(t, *space)) {
      const std::vector<Vec3> v = vertex_positions(f, space->grid());
      out.insert(out.end(), v.begin(), v.end());
    }
    return out;
  }
  double eps() const { return Tolerance::for_extent(box.diagonal()).plane_eps; }
};

template <class K>
class Evaluator {
 public:
  using Tree = typename K::Tree;

  Evaluator(const csg::Postfix& postfix, Splitter& splitter, K& kernel, CsgEvaluation& out)
      : postfix_(postfix), splitter_(splitter), k_(kernel), out_(out) {
    // Operands point at hull meshes held here: reserving keeps them in place.
    std::size_t hulls = 0;
    for (const Step& s : postfix_.steps) hulls += s.kind == StepKind::Hull;
    hulls_.reserve(hulls);
  }

  // The timed part: every step, then the boundary. Returns the result tree (nullopt: empty).
  std::optional<Tree> run() {
    for (const Step& step : postfix_.steps) {
      if (step.kind == StepKind::Leaf) stack_.push_back({&postfix_.leaves[step.count].polygons, std::nullopt, step.node});
      else if (step.kind == StepKind::Empty) stack_.push_back({});
      else apply(step);
    }
    if (stack_.size() != 1) throw std::logic_error("csg: the program leaves " + std::to_string(stack_.size()) + " operands");
    std::optional<Tree> result = built(stack_.back());
    const auto start = wall_seconds();
    if (result) {
      out_.result = K::size(*result);
      boundary_ = k_.boundary(*result);
    }
    check_boundary(boundary_, k_.eps(), &out_.mesh);
    out_.boundary_seconds = wall_seconds() - start;
    return result;
  }
  const LoopPool& boundary() const { return boundary_; }
  std::vector<std::vector<Polygon>>& hulls() { return hulls_; }

 private:
  struct Operand {
    const std::vector<Polygon>* mesh = nullptr;  // a leaf (or hull) not built yet
    std::optional<Tree> tree;
    std::uint32_t node = 0;
    bool empty() const { return !mesh && !tree; }
  };

  std::optional<Tree> built(Operand& o) {
    if (o.tree || !o.mesh) return std::move(o.tree);
    CsgLeafCost cost;
    cost.node = o.node;
    cost.polygons = o.mesh->size();
    Tree t = k_.build(*o.mesh, splitter_, cost, out_.dropped_input);
    cost.size = K::size(t);
    out_.build_seconds += cost.seconds;
    out_.leaves.push_back(cost);
    return t;
  }

  void apply(const Step& step) {
    const auto first = stack_.end() - step.count;
    std::vector<Operand> operands(std::make_move_iterator(first), std::make_move_iterator(stack_.end()));
    stack_.erase(first, stack_.end());
    CsgStepCost cost;
    cost.node = step.node;
    cost.kind = step.kind;
    cost.operands = step.count;
    Operand result = step.kind == StepKind::Hull ? hull(operands, cost) : combine(operands, step.kind, cost);
    out_.steps.push_back(cost);
    stack_.push_back(std::move(result));
  }

  // Left to right; an empty operand needs no merge (union ignores it, intersection becomes empty,
  // a difference's empty first operand makes the result empty).
  Operand combine(std::vector<Operand>& ops, StepKind kind, CsgStepCost& cost) {
    if (ops.empty()) return {};
    Operand acc = std::move(ops[0]);
    for (std::size_t i = 1; i < ops.size(); ++i) {
      Operand& next = ops[i];
      if (next.empty()) {
        if (kind == StepKind::Intersection) acc = {};
        continue;
      }
      if (acc.empty()) {
        if (kind == StepKind::Union) acc = std::move(next);
        continue;
      }
      std::optional<Tree> a = built(acc), b = built(next);
      MergeStats stats;
      const auto start = wall_seconds();
      Tree r = k_.merge(*a, *b, set_op(kind), stats);
      k_.release(*a, r);
      k_.release(*b, r);
      const double seconds = wall_seconds() - start;
      cost.seconds += seconds;
      out_.merge_seconds += seconds;
      ++cost.merges;
      add(cost.stats, stats);
      acc = {nullptr, std::move(r), acc.node};
    }
    return acc;
  }

  // The convex hull of the operands' points: a leaf's vertices, or a tree's boundary vertices.
  Operand hull(std::vector<Operand>& ops, CsgStepCost& cost) {
    const auto start = wall_seconds();
    std::vector<Vec3> points;
    for (Operand& o : ops) {
      if (o.mesh) {
        for (const Polygon& p : *o.mesh)
          for (const Vertex& v : p.verts) points.push_back(v.p);
      } else if (o.tree) {
        const std::vector<Vec3> v = k_.boundary_points(*o.tree);
        points.insert(points.end(), v.begin(), v.end());
      }
    }
    const csg::Mesh mesh = csg::hull3(points);
    std::vector<Polygon>& polys = hulls_.emplace_back();
    for (const auto& face : mesh.faces) {
      Polygon p;
      for (std::uint32_t i : face) p.verts.push_back({mesh.points[i], 0, 0});
      p.source = static_cast<std::uint32_t>(polys.size());
      polys.push_back(std::move(p));
    }
    cost.seconds = wall_seconds() - start;
    out_.merge_seconds += cost.seconds;
    if (polys.empty()) return {};
    return {&polys, std::nullopt, cost.node};
  }

  const csg::Postfix& postfix_;
  Splitter& splitter_;
  K& k_;
  CsgEvaluation& out_;
  std::vector<Operand> stack_;
  std::vector<std::vector<Polygon>> hulls_;  // one per hull step, in order
  LoopPool boundary_;
};

// The leaves as closed, outward, non-self-intersecting solids, named by their node.
void check_leaves(const csg::Program& program, const csg::Postfix& postfix, const Kernel kernel, const Box& box,
                  const ExactSolidSpace* space) {
  const double eps = Tolerance::for_extent(box.diagonal()).plane_eps;
  for (const csg::Leaf& leaf : postfix.leaves) {
    const std::string name = program.path + ":" + std::to_string(program.nodes[leaf.node].line) + ": " + program.nodes[leaf.node].name;
    require_closed_solid(leaf.polygons, eps, name);
    if (kernel == Kernel::Exact) {
      require_snapped_solid(leaf.polygons, space->grid(), name);
    } else if (const std::size_t n = ExactSolid(leaf.polygons).self_intersecting_pairs(); n > 0) {
      throw InputError(name + ": not the boundary of a solid: " + std::to_string(n) + " pairs of faces intersect");
    }
  }
}

SolidTree empty_solid(const Box& box) {
  SolidTree t;
  t.box = box;
  t.tol = Tolerance::for_extent(box.diagonal());
  return t;
}

}  // namespace

CsgEvaluation evaluate_program(const csg::Program& program, const csg::Postfix& postfix, Splitter& splitter,
                               const CsgSettings& settings) {
  CsgEvaluation out;
  out.kernel = settings.kernel;
  Box leaves = leaves_box(postfix);
  if (leaves.empty()) leaves = Box{{0, 0, 0}, {1, 1, 1}};  // a program of nothing: any space will do
  const Box box = solid_box(leaves, leaves);
  const csg::Postfix& truth = settings.truth ? *settings.truth : postfix;
  const auto start = wall_seconds();
  if (settings.kernel == Kernel::Float) {
    FloatKernel k{box, settings.merge};
    if (settings.check_inputs) check_leaves(program, postfix, settings.kernel, box, nullptr);
    out.check_seconds = wall_seconds() - start;
    Evaluator<FloatKernel> e(postfix, splitter, k, out);
    const std::optional<SolidTree> result = e.run();
    const auto proof_start = wall_seconds();
    if (settings.prove)
      out.check = check_program(result ? *result : empty_solid(box), e.boundary(), truth.leaf_meshes(), e.hulls(), truth.steps,
                                settings.check);
    out.proof_seconds = wall_seconds() - proof_start;
    return out;
  }
  ExactKernel k{ExactSolidSpace::for_box(box), box, {}, settings.merge};
  if (settings.check_inputs) check_leaves(program, postfix, settings.kernel, box, k.space.get());
  out.check_seconds = wall_seconds() - start;
  Evaluator<ExactKernel> e(postfix, splitter, k, out);
  const std::optional<ExactSolidTree> result = e.run();
  const auto proof_start = wall_seconds();
  if (settings.prove)
    out.check = check_exact_program(result ? *result : ExactSolidTree{}, *k.space, k.faces, truth.leaf_meshes(), e.hulls(),
                                    truth.steps, settings.check);
  out.proof_seconds = wall_seconds() - proof_start;
  return out;
}

}  // namespace bsp::experiments
