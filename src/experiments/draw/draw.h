#pragma once
// Drawing runs: one scene's tree built by one heuristic (or by insertion), measured, its invariants
// checked, its back-to-front orders validated against Embree from `views` eyes and its ray shooting
// cross-checked against Embree's first hits (on at most kMaxShootRays of the validation's rays,
// evenly strided). A suite block of this kind is a "blocks" entry (analysis/SUITE_SCHEMA.md): scene
// x size x heuristic x shape x seed; the record is analysis/SCHEMA.md's RUN.
//
// A block names no heuristic and no scene unless it wants to: it takes every entry of the
// registries (every 3D generator but the closed solids, every heuristic), so one added there is
// swept without further wiring. Sizes are the generators' `n`; a generator without one runs once at
// its defaults, and a size outside a generator's `n` range is skipped for it. A mesh has no size: it
// runs once per heuristic, shape and seed, the seed feeding only the heuristic.
//
// A block may also run each job in the exact kernel (tree/exact_build.h), as `bspbench build
// --kernel exact` and `bspbench validate --kernel exact` do: the tree is the exact one, measured on
// its view in doubles, its invariants and order checked exactly. Such a run's key and identity name
// the kernel; a float run's are as they were before kernels existed.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/params.h"
#include "experiments/kind.h"
#include "experiments/scene_run.h"
#include "metrics/tree_metrics.h"
#include "split/splitter.h"
#include "tree/build.h"
#include "tree/exact_build.h"
#include "tree/tree.h"

namespace bsp::experiments {

// A drawing run's tree, as a drawing job builds it and as `bspbench build` (and every command that
// builds one tree) does: the splitter's build, or Thibault–Naylor insertion in the order `options`
// give when there is no splitter.
Tree build_drawing(std::span<const Polygon> polygons, Splitter* splitter, const BuildOptions& options);
// A drawing run's metrics: size and shape, and for a 3D scene the query costs measured with
// `settings`. A flat scene (2D segments) has no cells, frustums or rays in space to cost.
TreeMetrics measure_drawing(const Tree& tree, std::span<const Polygon> scene, const MetricsSettings& settings);

// How much ray-cast validation each run gets; bigger scenes get fewer views so a suite stays
// within its time budget.
struct ValidationPlan {
  std::uint32_t views = 0;            // views for scenes up to `reduce_above` polygons; 0 = no validation
  std::uint64_t reduce_above = 0;     // polygon count past which `reduced_views` apply
  std::uint32_t reduced_views = 0;
  std::uint32_t views_for(std::uint64_t n) const { return n > reduce_above ? reduced_views : views; }
};

// Sizes for one scene, in place of the block's common sizes (a scene whose cost grows much faster
// than n log n).
struct SceneSizes {
  std::string scene;
  std::vector<std::uint64_t> sizes;
};

// A scene of a block: a generator by name with parameters other than n and seed (those come from
// the block's sizes and seeds); a mesh of the cache, "mesh:NAME" (generators/mesh_scenes.h); or a
// mesh file, "file:PATH", PATH as its suite wrote it and `path` as opened.
struct SceneSpec {
  std::string name;
  ParamAssignments params = {};
  std::string path = {};
};

struct DrawBlock final : Block {
  std::vector<SceneSpec> scenes;          // empty: every drawn generator
  std::vector<std::string> heuristics;    // empty: every registered heuristic; none when incremental
  std::vector<std::uint64_t> sizes;
  std::vector<SceneSizes> scene_sizes;    // overrides `sizes` for the scenes named
  std::vector<std::uint64_t> seeds;
  std::vector<Shape> shapes;
  ValidationPlan validation;
  // One incremental build (tree/build_incremental.h, seeded shuffled order) per scene, size, shape
  // and seed instead of one build per heuristic: it consults no heuristic, so it runs once.
  bool incremental = false;
  // Each job once per kernel. The exact kernel builds 3D scenes recursively,
  // strict or coarse, so the parser refuses it with an incremental build, leafy trees or 2D scenes.
  std::vector<Kernel> kernels = {Kernel::Float};

  Jobs expand() const override;
};

class DrawJob final : public Job {
 public:
  // The kernel joins the key and the identity only when it is not float.
  explicit DrawJob(SceneRun spec, Kernel kernel = Kernel::Float);
  std::string_view kind() const override { return "draw"; }
  std::string measured_identity() const override;
  nlohmann::json identity() const override;
  nlohmann::json run(const RunContext& context) const override;
  const SceneRun& spec() const { return spec_; }
  Kernel kernel() const { return kernel_; }

 private:
  nlohmann::json run_exact(const RunContext& context, const Scene& scene, double start) const;
  SceneRun spec_;
  Kernel kernel_;
};

// The ray-shooting walk costs far more per ray than Embree (a 40 000-fragment saddle-grid tree has
// half a million validation rays): this many, spread over all of them, find a broken walk (it
// misses whole subtrees, so many rays) while keeping the quick suite within CI's budget.
inline constexpr std::size_t kMaxShootRays = 1500;

std::span<const TimingField> draw_timing_fields();
const Kind& draw_kind();

}  // namespace bsp::experiments
