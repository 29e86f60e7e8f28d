#pragma once
// Merge runs: set operations on solid pairs (generators/solid_pairs.h). A suite block of this kind
// is a "merges" entry: pair x size x heuristic x operation x seed. Each job builds the pair's two
// operands as solid trees with the heuristic, merges them by the operation (set_operation.h, the
// pipeline `bspbench merge` runs), times repeated merges, and proves the result against CGAL. The
// record is analysis/SCHEMA.md's MERGE RUN: the operands' tree sizes and the merge cost
// (partitionTree calls, sub-hyperplane splits, nodes visited, result size before and after
// reduction) as metrics, the boundary's closure as invariants, the proof as validation.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "experiments/heuristic_choice.h"
#include "experiments/kind.h"
#include "scene/scene.h"
#include "solid/merge.h"
#include "tree/exact_build.h"

namespace bsp::experiments {

struct MergeBlock final : Block {
  std::vector<std::string> pairs;       // empty: every pair
  std::vector<std::string> heuristics;  // empty: every registered heuristic
  std::vector<SetOp> ops;               // empty: union, intersection, difference and xor
  std::vector<std::uint64_t> sizes;     // polygons per operand, within the pair's range; unsized pairs run once
  std::vector<std::uint64_t> seeds;
  std::uint64_t points = 0;             // classified against CGAL's exact answer per run
  std::vector<Kernel> kernels = {Kernel::Float};

  Jobs expand() const override;
};

struct MergeSpec {
  std::string pair;
  std::uint64_t n = 0;  // polygons per operand; 0 for an unsized pair
  HeuristicChoice heuristic;
  SetOp op = SetOp::Union;
  std::uint64_t seed = 1;  // the pair's, the heuristic's and the checked points'
  std::uint64_t points = 0;
  Kernel kernel = Kernel::Float;  // joins the key and the identity only when exact
};

class MergeJob final : public Job {
 public:
  explicit MergeJob(MergeSpec spec);
  std::string_view kind() const override { return "merge"; }
  nlohmann::json identity() const override;
  nlohmann::json run(const RunContext& context) const override;
  const MergeSpec& spec() const { return spec_; }

 private:
  nlohmann::json run_exact(const RunContext& context, const Scene& a, const Scene& b, double start) const;
  MergeSpec spec_;
};

const Kind& merge_kind();

}  // namespace bsp::experiments
