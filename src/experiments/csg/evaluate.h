#pragma once
// A CSG program (csg/lower.h) evaluated by successive merges into one solid tree [Naylor1990]:
// every leaf built as a solid tree by one heuristic in one space (the box of all leaves, or its
// grid in the exact kernel), the operands of each step merged two at a time, left to right, the
// result kept a tree between steps, and its boundary extracted and welded at the end: mesh in, mesh
// out, as every peer engine runs. The one pipeline behind `bspbench csg` and the sweep's csg runs;
// the proof (validate/program_check.h) runs after the timed part.
#include <cstdint>
#include <vector>

#include "csg/lower.h"
#include "geometry/mesh_weld.h"
#include "solid/merge.h"
#include "split/splitter.h"
#include "tree/exact_build.h"
#include "validate/program_check.h"

namespace bsp::experiments {

struct CsgLeafCost {
  std::uint32_t node = 0;  // the program node the leaf comes from
  std::uint64_t polygons = 0, fragments = 0;
  SolidSize size;
  double seconds = 0;  // its solid tree's build, labels included
};

// One step of the program: its merges' counters summed, `stats.before` and `after` of its last
// merge (the step's result before and after reduction).
struct CsgStepCost {
  std::uint32_t node = 0;
  StepKind kind = StepKind::Union;
  std::uint32_t operands = 0;
  std::uint64_t merges = 0;  // binary merges made (an empty operand needs none)
  MergeStats stats;
  double seconds = 0;        // merges, or for a hull the hull and its build
};

struct CsgEvaluation {
  Kernel kernel = Kernel::Exact;
  std::vector<CsgLeafCost> leaves;  // in the order the program first needs them built
  std::vector<CsgStepCost> steps;   // set operations and hulls, in program order
  double check_seconds = 0;         // the leaves proved closed, outward and free of self-intersection (untimed part)
  double build_seconds = 0, merge_seconds = 0, boundary_seconds = 0;
  double seconds() const { return build_seconds + merge_seconds + boundary_seconds; }  // mesh in, mesh out
  double proof_seconds = 0;         // the proof after it (untimed part)
  SolidSize result;
  IndexedMesh mesh;  // the result's boundary, welded within plane_eps
  std::uint64_t dropped_input = 0;  // faces the builds dropped (float: slivers; exact: collapsed by snapping)
  ProgramCheck check;
};

struct CsgSettings {
  Kernel kernel = Kernel::Exact;
  MergeOptions merge;  // pruning by bounds (merge.h)
  SolidCheckSettings check;
  bool prove = true;
  // Prove every leaf a closed solid free of self-intersections first; repeated evaluations of
  // leaves already checked (timing) leave it out.
  bool check_inputs = true;
  // The program the result is proved against; nullptr: the one evaluated. Tests plant a wrong
  // evaluation (a step's operation changed) and show the proof catches it.
  const csg::Postfix* truth = nullptr;
};

// Throws InputError naming the program's node when a leaf is not a closed solid (or stops being
// one when snapped to the exact kernel's grid), or its faces intersect.
CsgEvaluation evaluate_program(const csg::Program& program, const csg::Postfix& postfix, Splitter& splitter,
                               const CsgSettings& settings);

}  // namespace bsp::experiments
