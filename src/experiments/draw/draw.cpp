#include "experiments/draw/draw.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <set>

#include <nlohmann/json.hpp>

#include "catalog.h"
#include "common/cpu_time.h"
#include "common/errors.h"
#include "common/hash.h"
#include "experiments/reference_build.h"
#include "geometry/segment2.h"
#include "io/mesh_reader.h"
#include "mesh_scenes.h"
#include "metrics/kernel_stats.h"
#include "metrics/tree_metrics.h"
#include "tree/build.h"
#include "validate/exact_invariants.h"
#include "validate/exact_order_check.h"
#include "validate/order_check.h"
#include "validate/ray_shoot_check.h"
#include "validate/tree_invariants.h"

namespace bsp::experiments {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr TimingField kTimings[] = {
    {"build_seconds", TimingRole::Wall, "wall time of the first build (the tree that is measured)"},
    {"build_cpu_samples", TimingRole::GatedSamples,
     "thread CPU seconds per build, one per timed batch of at least 2 ms (experiments/timing.h)"},
    {"build_reference_samples", TimingRole::ReferenceSamples,
     "thread CPU seconds per Embree BVH build of the same input, one batch before each timed batch: the gate divides each sample by it (experiments/reference_build.h)"},
    {"build_cpu_seconds", TimingRole::SamplesMedian, "the median of build_cpu_samples"},
    {"build_cpu_builds", TimingRole::SampleCount, "builds timed for the samples: depends on the machine's speed"},
    {"metrics_cpu_seconds", TimingRole::Cpu, "thread CPU seconds of measure_tree"},
    {"validation_seconds", TimingRole::Wall, "wall time of the Embree order check"},
    {"validation_rays_per_second", TimingRole::Rate, "rays cast per wall-clock second in the order check"},
    {"exact_snap_seconds", TimingRole::Wall, "exact kernel: wall time of snapping the input to the grid, in the first build"},
    {"exact_load_seconds", TimingRole::Wall, "exact kernel: wall time of loading the snapped input (cofactors, pooled supports)"},
    {"exact_view_seconds", TimingRole::Wall, "exact kernel: wall time of computing the tree's view in doubles"},
    {"job_seconds", TimingRole::Wall, "wall time of the whole job"},
};

// What aggregation groups by and fits growth of (experiments/kind.h). A float run names no kernel,
// so float groups are as they were before kernels existed.
constexpr std::string_view kGroupBy[] = {"kernel"};
constexpr std::string_view kGrowthMetrics[] = {"fragments", "nodes"};
constexpr std::string_view kGrowthTimings[] = {"build_cpu_seconds", "build_seconds"};
// Splits (what a partition adds), fragments and build time, over the sizes, for the theory check.
constexpr std::string_view kSizeGrowthMetrics[] = {"splits", "fragments"};
constexpr std::string_view kSizeGrowthTimings[] = {"build_cpu_seconds"};

// ---- the block ----

bool is_mesh(const SceneSpec& spec) { return is_file_scene(spec.name) || is_mesh_scene(spec.name); }

// The sizes a block asks of generator g: its own (scene_sizes) or the block's.
std::vector<std::uint64_t> sizes_for(const GeneratorInfo& g, const DrawBlock& block) {
  for (const auto& o : block.scene_sizes)
    if (o.scene == g.name) return sizes_in_range(g, o.sizes);
  return sizes_in_range(g, block.sizes);
}

// Every generator but the closed solids (generators/solids.cpp), which are the operands of set
// operations rather than scenes to draw, and the 2D scenes.
bool drawn(const GeneratorInfo& g) { return !g.closed_solid && !g.segments; }

std::vector<SceneSpec> scene_specs(const DrawBlock& block) {
  if (!block.scenes.empty()) return block.scenes;
  std::vector<SceneSpec> all;
  for (const auto& g : generators())
    if (drawn(g)) all.push_back({g.name});
  return all;
}

// The block's heuristics, parsed; one std::nullopt (no heuristic) for an incremental block.
std::vector<std::optional<HeuristicChoice>> heuristic_choices(const DrawBlock& block) {
  if (block.incremental) return {std::nullopt};
  std::vector<std::optional<HeuristicChoice>> out;
  for (auto& h : choices_or_all(block.heuristics)) out.emplace_back(std::move(h));
  return out;
}

SceneFile scene_file(const SceneSpec& spec) {
  std::string path = spec.path;
  if (path.empty())
    path = is_file_scene(spec.name) ? spec.name.substr(kFileScenePrefix.size()) : mesh_scene_path(spec.name);
  std::string hash = file_hash(path);
  return {std::move(path), std::move(hash)};
}

// A mesh has no size and no seed of its own: one job per heuristic, shape and seed, at the block's
// views for small scenes (its polygon count is not known before it is read).
void expand_mesh(const DrawBlock& block, const SceneSpec& spec, Jobs& out) {
  const SceneFile file = scene_file(spec);
  for (const auto& h : heuristic_choices(block))
    for (auto shape : block.shapes)
      for (auto kernel : block.kernels)
        for (auto seed : block.seeds)
          out.push_back(std::make_shared<DrawJob>(
              SceneRun{spec.name, {}, file, h, shape, seed, 0, block.validation.views}, kernel));
}

// ---- the block's parser ----

class DrawBlockReader {
 public:
  explicit DrawBlockReader(const BlockReader& r) : r_(r) {}

  std::unique_ptr<const Block> block(const json& j, const std::string& path) const {
    r_.expect(j, j.is_object(), path, "an object");
    r_.check_keys(j, path,
                  {"scenes", "heuristics", "incremental", "sizes", "scene_sizes", "seeds", "shapes", "validation", "kernels"});
    auto b = std::make_unique<DrawBlock>();
    if (const json* inc = r_.optional(j, "incremental")) b->incremental = r_.boolean(*inc, child(path, "incremental"));
    // The generators of the block, named or (no "scenes") every drawn one.
    std::vector<const GeneratorInfo*> named;
    if (const json* scenes = r_.optional(j, "scenes")) {
      std::map<std::string, std::string> seen;
      r_.each(*scenes, child(path, "scenes"), "leave \"scenes\" out to run every 3D generator",
              [&](const json& s, const std::string& p) {
                ParsedScene parsed = scene(s, p);
                r_.once(seen, parsed.identity, p);
                if (parsed.generator) named.push_back(parsed.generator);
                b->scenes.push_back(std::move(parsed.spec));
              });
    }
    const bool every_generator = b->scenes.empty();
    std::vector<const GeneratorInfo*> sized;
    if (every_generator) {
      for (const auto& g : generators())
        if (drawn(g) && n_spec(g)) sized.push_back(&g);
    } else {
      for (const auto* g : named)
        if (n_spec(*g) && std::find(sized.begin(), sized.end(), g) == sized.end()) sized.push_back(g);
    }
    if (const json* h = r_.optional(j, "heuristics")) {
      if (b->incremental)
        r_.fail(child(path, "heuristics"), "an incremental build consults no heuristic (the insertion order picks the "
                                           "planes); drop \"heuristics\"");
      b->heuristics = r_.heuristics(*h, child(path, "heuristics"));
    }
    sizes(j, path, sized, every_generator, *b);
    b->seeds = r_.seeds(j, path);
    b->shapes = {Shape::Strict};
    if (const json* shapes = r_.optional(j, "shapes")) {
      b->shapes.clear();
      std::map<std::string, std::string> seen;
      r_.each(*shapes, child(path, "shapes"), "leave \"shapes\" out for strict trees", [&](const json& s, const std::string& p) {
        const std::string name = r_.string(s, p);
        const auto shape = shape_named(name);
        if (!shape) r_.fail(p, "unknown shape '" + name + "' (known: strict, coarse, leafy)");
        if (b->incremental && *shape == Shape::Leafy) r_.fail(p, "a leafy tree is built recursively, not incrementally");
        r_.once(seen, name, p);
        b->shapes.push_back(*shape);
      });
    }
    if (const json* v = r_.optional(j, "validation")) b->validation = validation(*v, child(path, "validation"));
    else b->validation = {1, 0, 1};
    b->kernels = r_.kernels(j, path);
    const std::string refused = exact_refusal(*b, named);
    if (!refused.empty()) r_.fail(child(path, "kernels"), refused);
    return b;
  }

 private:
  struct ParsedScene {
    SceneSpec spec;
    const GeneratorInfo* generator = nullptr;  // nullptr for meshes
    std::string identity;                      // what makes two scenes of a block the same
  };

  // Why the block cannot run in the exact kernel it asks for, as `bspbench build --kernel exact`
  // refuses the same builds; empty when it can (or asks for float only).
  static std::string exact_refusal(const DrawBlock& b, const std::vector<const GeneratorInfo*>& named) {
    if (std::find(b.kernels.begin(), b.kernels.end(), Kernel::Exact) == b.kernels.end()) return {};
    if (b.incremental) return "the exact kernel builds recursively, not incrementally (leave \"exact\" out)";
    if (std::find(b.shapes.begin(), b.shapes.end(), Shape::Leafy) != b.shapes.end())
      return "the exact kernel builds strict and coarse trees, not leafy ones (leave \"exact\" or \"leafy\" out)";
    for (const auto* g : named)
      if (g->segments) return "the exact kernel builds 3D scenes; " + g->name + " is 2D segments";
    for (const auto& h : choices_or_all(b.heuristics))
      if (h.search) return "the exact kernel builds per node with a heuristic; " + h.name + " is a searching builder";
    return {};
  }

  // A mesh is read once here, so a missing, unreadable or empty one stops the suite before it runs.
  void check_mesh(const std::string& file, const std::string& path) const {
    r_.at(path, [&] { check_scene(read_mesh(file), file); });
  }

  ParsedScene scene(const json& j, const std::string& path) const {
    if (j.is_object()) {
      r_.check_keys(j, path, {"generator", "params"});
      const std::string name = r_.string(r_.required(j, path, "generator"), child(path, "generator"));
      const GeneratorInfo& g = r_.at(child(path, "generator"), [&]() -> const GeneratorInfo& { return find_generator(name); });
      ParamAssignments given;
      if (const json* p = r_.optional(j, "params")) given = r_.params(*p, child(path, "params"), g.params, "scene " + g.name, true);
      const std::string canonical = ParamSet::resolve(g.params, given, g.name).canonical();
      return {SceneSpec{g.name, std::move(given), {}}, &g, g.name + " " + canonical};
    }
    const std::string name = r_.string(j, path);
    if (is_file_scene(name)) {
      const std::string written = name.substr(kFileScenePrefix.size());
      if (written.empty()) r_.fail(path, "file: wants a path (relative to the suite file)");
      // Lexically normal, so the runs' commands read the same however the suite file was named.
      const fs::path file = (fs::path(written).is_absolute() ? fs::path(written) : r_.dir() / written).lexically_normal();
      std::error_code ec;
      if (!fs::is_regular_file(file, ec)) r_.fail(path, "no such file: " + file.string());
      check_mesh(file.string(), path);
      const std::string identity = "file " + fs::weakly_canonical(file, ec).string();
      return {SceneSpec{name, {}, file.string()}, nullptr, identity};
    }
    if (is_mesh_scene(name)) {
      const std::string file = r_.at(path, [&] { return mesh_scene_path(name); });
      check_mesh(file, path);
      return {SceneSpec{name, {}, file}, nullptr, "mesh " + name};
    }
    const GeneratorInfo& g = r_.at(path, [&]() -> const GeneratorInfo& { return find_generator(name); });
    return {SceneSpec{g.name}, &g, g.name + " " + ParamSet::resolve(g.params, {}, g.name).canonical()};
  }

  // "sizes" for the sized generators not in "scene_sizes"; "scene_sizes" per generator. A named
  // generator's sizes must lie in its range of n; with every generator (no "scenes"), each runs
  // the sizes in its range, as the built-in suites do.
  void sizes(const json& j, const std::string& path, const std::vector<const GeneratorInfo*>& sized,
             bool every_generator, DrawBlock& b) const {
    std::set<const GeneratorInfo*> own;
    if (const json* ss = r_.optional(j, "scene_sizes")) {
      const std::string sp = child(path, "scene_sizes");
      r_.expect(*ss, ss->is_object(), sp, "an object");
      if (ss->empty()) r_.fail(sp, "empty object (leave \"scene_sizes\" out)");
      for (const auto& item : ss->items()) {
        const std::string& name = item.key();
        const json& list = item.value();
        const std::string p = child(sp, name);
        const GeneratorInfo& g = r_.at(p, [&]() -> const GeneratorInfo& { return find_generator(name); });
        if (std::find(sized.begin(), sized.end(), &g) == sized.end())
          r_.fail(p, !n_spec(g) ? name + " takes no size" : name + " is not a scene of this block");
        const auto values = r_.sizes(list, p);
        r_.check_range(g, values, p);
        b.scene_sizes.push_back({g.name, values});
        own.insert(&g);
      }
    }
    const bool needed = std::any_of(sized.begin(), sized.end(), [&](const GeneratorInfo* g) { return !own.count(g); });
    const json* s = r_.optional(j, "sizes");
    if (!s) {
      if (needed) {
        const auto g = std::find_if(sized.begin(), sized.end(), [&](const GeneratorInfo* x) { return !own.count(x); });
        r_.fail(path, "missing key 'sizes' (" + (every_generator ? std::string("every 3D generator runs, and") : (*g)->name) +
                          " takes a size n)");
      }
      return;
    }
    const std::string p = child(path, "sizes");
    if (!needed)
      r_.fail(p, sized.empty() ? "no scene of this block takes a size (meshes and generators without n run once)"
                               : "every scene of this block that takes a size has its own in \"scene_sizes\"");
    b.sizes = r_.sizes(*s, p);
    if (!every_generator)
      for (const auto* g : sized)
        if (!own.count(g)) r_.check_range(*g, b.sizes, p);
  }

  ValidationPlan validation(const json& j, const std::string& path) const {
    r_.expect(j, j.is_object(), path, "an object");
    r_.check_keys(j, path, {"views", "reduce_above", "reduced_views"});
    ValidationPlan plan{1, 0, 1};
    if (const json* v = r_.optional(j, "views")) plan.views = static_cast<std::uint32_t>(r_.integer(*v, child(path, "views"), 0, kMaxViews));
    const json* above = r_.optional(j, "reduce_above");
    const json* reduced = r_.optional(j, "reduced_views");
    if ((above == nullptr) != (reduced == nullptr)) r_.fail(path, "\"reduce_above\" and \"reduced_views\" come together");
    if (above) {
      plan.reduce_above = r_.integer(*above, child(path, "reduce_above"), 1, std::numeric_limits<std::int64_t>::max());
      plan.reduced_views = static_cast<std::uint32_t>(r_.integer(*reduced, child(path, "reduced_views"), 0, plan.views));
    } else {
      plan.reduced_views = plan.views;
    }
    return plan;
  }

  const BlockReader& r_;
};

std::unique_ptr<const Block> parse_block(const BlockReader& reader, const json& block, const std::string& path) {
  return DrawBlockReader(reader).block(block, path);
}

// ---- the run ----

ValidationSettings validation_settings(const SceneRun& s) {
  ValidationSettings settings;
  settings.views = static_cast<int>(s.views);
  return settings;
}

json invariants_json(const Tree& tree, const Scene& scene) {
  const InvariantReport r = check_tree_invariants(tree, scene.polygons);
  return {{"violations", r.violations}, {"first_problems", r.first_problems}};
}

// null when the job asks for no views. A 2D tree is seen as walls from eyes in its plane.
json validation_json(const Tree& tree, const SceneRun& s, bool flat, json& timings) {
  if (s.views == 0) return nullptr;
  const ValidationSettings settings = validation_settings(s);
  json v = to_json(flat ? validate_segment_tree(tree, validation_eyes(tree.bounds, settings.views), settings)
                        : validate_tree(tree, settings));
  split_timings(v, timings, "validation_", kTimings);
  return v;
}

// The ray-shooting cross-check over at most kMaxShootRays of the validation's rays, evenly strided
// (deterministic); null when the job asks for no views.
json ray_shooting_json(const Tree& tree, const SceneRun& s) {
  if (s.views == 0) return nullptr;
  const ValidationSettings settings = validation_settings(s);
  const std::vector<Polygon> fragments = tree.fragments.to_polygons();
  std::vector<Ray> all;
  for (const Vec3& eye : validation_eyes(tree.bounds, settings.views)) {
    const std::vector<Ray> more = validation_rays(fragments, tree.bounds, eye, settings);
    all.insert(all.end(), more.begin(), more.end());
  }
  const std::size_t stride = (all.size() + kMaxShootRays - 1) / kMaxShootRays;
  std::vector<Ray> rays;
  for (std::size_t i = 0; i < all.size(); i += std::max<std::size_t>(stride, 1)) rays.push_back(all[i]);
  return to_json(check_ray_shooting(tree, EmbreeScene(fragments, tree.tol.plane_eps), rays));
}

// What the exact kernel does not build (a block's parser refuses it before anything runs); a leafy
// shape is refused by build_exact_tree.
void check_exact_build(const SceneRun& s, const Scene& scene) {
  if (s.incremental()) throw UsageError("the exact kernel builds recursively, not incrementally");
  if (all_segments(scene.polygons)) throw UsageError("the exact kernel builds 3D scenes; " + s.scene + " is 2D segments");
}

// The exact kernel's tree, built as `bspbench build --kernel exact` builds it.
ExactTree build_exact_once(const SceneRun& s, const Scene& scene) {
  return build_exact_tree(scene.polygons, *s.heuristic->splitter(s.seed), BuildOptions{.shape = s.shape});
}

json exact_invariants_json(const ExactTree& tree) {
  const ExactInvariantReport r = check_exact_invariants(tree);
  return {{"violations", r.violations}, {"first_problems", r.first_problems}};
}

// The exact order check from the job's views, eyes snapped to the grid; null with no views.
json exact_validation_json(const ExactTree& tree, const SceneRun& s, json& timings) {
  if (s.views == 0) return nullptr;
  json v = to_json(validate_exact_tree(tree, validation_settings(s)));
  split_timings(v, timings, "validation_", kTimings);
  return v;
}

// `hash` with the kernel joined when it is not float, so float keys stay as they were.
std::string with_kernel(const std::string& hash, Kernel kernel) {
  if (kernel == Kernel::Float) return hash;
  Hasher h;
  h.add_string(hash);
  h.add_string(kernel_name(kernel));
  return h.hex();
}

// Repeated builds in timed batches, each beside its reference (Embree's BVH build of the scene).
void time_builds(const std::function<void()>& build, const Scene& scene, double slowdown, json& timings) {
  const ReferenceBuild reference(scene.polygons);
  const TimedBatches batches = time_batches(build, slowdown, [&] { reference.run(); });
  timings["build_cpu_samples"] = batches.samples;
  timings["build_reference_samples"] = batches.reference;
  timings["build_cpu_builds"] = batches.runs;
  timings["build_cpu_seconds"] = batches.median();
}

// The tree's metrics (MetricsSettings' defaults with the job's seed for the metric rays), their
// timings moved to `timings`.
json metrics_json(const Tree& tree, const Scene& scene, std::uint64_t seed, json& timings) {
  MetricsSettings settings;
  settings.seed = seed;
  const double cpu = thread_cpu_seconds();
  json metrics = to_json(measure_drawing(tree, scene.polygons, settings));
  timings["metrics_cpu_seconds"] = thread_cpu_seconds() - cpu;
  split_timings(metrics, timings, "", kTimings);
  return metrics;
}

// The job's identity with what the scene turned out to be.
json scene_identity(json id, const Scene& scene) {
  id["n_polygons"] = scene.polygons.size();
  const json described = scene_json(scene);
  id["scene_hash"] = described["hash"];
  id["scene_bounds"] = described["bounds"];
  if (described.contains("load")) id["scene_load"] = described["load"];
  return id;
}

Tree build_once(const SceneRun& s, const Scene& scene) {
  BuildOptions options{.shape = s.shape};
  if (s.incremental()) {
    options.order = InsertOrder::Shuffled;
    options.order_seed = insertion_order_seed(s.seed);
    return build_drawing(scene.polygons, nullptr, options);
  }
  return s.heuristic->build(scene.polygons, options, s.seed);
}

}  // namespace

Tree build_drawing(std::span<const Polygon> polygons, Splitter* splitter, const BuildOptions& options) {
  return splitter ? build_tree(polygons, *splitter, options) : build_incremental_tree(polygons, options);
}

TreeMetrics measure_drawing(const Tree& tree, std::span<const Polygon> scene, const MetricsSettings& settings) {
  return all_segments(scene) ? measure_tree(tree) : measure_tree(tree, settings);
}

Jobs DrawBlock::expand() const {
  Jobs out;
  for (const auto& spec : scene_specs(*this)) {
    if (is_mesh(spec)) {
      expand_mesh(*this, spec, out);
      continue;
    }
    const GeneratorInfo& g = find_generator(spec.name);
    for (auto n : sizes_for(g, *this))
      for (const auto& h : heuristic_choices(*this))
        for (auto shape : shapes)
          for (auto kernel : kernels)
            for (auto seed : seeds)
              out.push_back(std::make_shared<DrawJob>(
                  SceneRun::generated(g, spec.params, h, shape, seed, n, validation.views_for(n)), kernel));
  }
  return out;
}

DrawJob::DrawJob(SceneRun spec, Kernel kernel) : spec_(std::move(spec)), kernel_(kernel) {
  set_identity(with_kernel(spec_.hash(spec_.key_scene_text()), kernel_), spec_.n);
}

// A generated scene by its content; a mesh has no nominal size, so its key says it all.
std::string DrawJob::measured_identity() const {
  return spec_.file ? key() : with_kernel(spec_.hash(spec_.content_hash()), kernel_);
}

nlohmann::json DrawJob::identity() const {
  json id = spec_.identity(kind());
  if (kernel_ == Kernel::Float) return id;
  id["kernel"] = kernel_name(kernel_);
  id["command"] = id["command"].get<std::string>() + " --kernel " + kernel_name(kernel_);
  return id;
}

// The record of the exact kernel's tree: RUN's metrics measured on the tree's view, with what the
// kernel did under metrics.exact; its invariants and order decided exactly; no ray-shooting
// cross-check (the walk decides in doubles).
nlohmann::json DrawJob::run_exact(const RunContext& context, const Scene& scene, double start) const {
  check_exact_build(spec_, scene);
  json timings = json::object();
  const ExactTree tree = build_exact_once(spec_, scene);
  time_builds([&] { build_exact_once(spec_, scene); }, scene, context.slowdown(spec_.heuristic_label()), timings);
  json metrics = metrics_json(tree.tree, scene, spec_.seed, timings);
  json exact = to_json(tree.exact);
  split_timings(exact, timings, "exact_", kTimings);
  metrics["exact"] = std::move(exact);
  json validation = exact_validation_json(tree, spec_, timings);
  return make_record(*this, scene_identity(identity(), scene), std::move(metrics), exact_invariants_json(tree),
                     std::move(validation), nullptr, std::move(timings), start);
}

nlohmann::json DrawJob::run(const RunContext& context) const {
  const double start = wall_seconds();
  const Scene scene = spec_.make_scene();
  if (kernel_ == Kernel::Exact) return run_exact(context, scene, start);
  json timings = json::object();
  const Tree tree = build_once(spec_, scene);
  time_builds([&] { build_once(spec_, scene); }, scene, context.slowdown(spec_.heuristic_label()), timings);
  const bool flat = all_segments(scene.polygons);
  json metrics = metrics_json(tree, scene, spec_.seed, timings);
  json invariants = invariants_json(tree, scene);
  json validation = validation_json(tree, spec_, flat, timings);
  json ray_shooting = flat ? nullptr : ray_shooting_json(tree, spec_);
  return make_record(*this, scene_identity(identity(), scene), std::move(metrics), std::move(invariants),
                     std::move(validation), std::move(ray_shooting), std::move(timings), start);
}

std::span<const TimingField> draw_timing_fields() { return kTimings; }

const Kind& draw_kind() {
  static const Kind kind{
      .name = "draw",
      .suite_key = "blocks",
      .parse = parse_block,
      .timings = kTimings,
      .group_by = kGroupBy,
      .growth_metrics = kGrowthMetrics,
      .growth_timings = kGrowthTimings,
      .size_growth_metrics = kSizeGrowthMetrics,
      .size_growth_timings = kSizeGrowthTimings,
      .growth_against_fragments = "build_cpu_seconds",
      .schema_section = "RUN",
  };
  return kind;
}

}  // namespace bsp::experiments
