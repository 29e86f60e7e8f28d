#include "experiments/kernel/kernel.h"

#include <algorithm>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "catalog.h"
#include "common/cpu_time.h"
#include "common/hash.h"
#include "common/rng.h"
#include "experiments/reference_build.h"
#include "geometry/snap.h"
#include "mesh_scenes.h"
#include "metrics/kernel_stats.h"
#include "metrics/tree_metrics.h"
#include "tree/build.h"
#include "tree/exact_build.h"
#include "validate/exact_invariants.h"
#include "validate/exact_order_check.h"
#include "validate/order_check.h"
#include "validate/tree_invariants.h"

namespace bsp::experiments {

namespace {

using nlohmann::json;

constexpr TimingField kTimings[] = {
    {"exact_build_cpu_samples", TimingRole::GatedSamples,
     "thread CPU seconds per exact build (snapping included), one per timed batch of at least 2 ms"},
    {"exact_build_reference_samples", TimingRole::ReferenceSamples,
     "thread CPU seconds per Embree BVH build of the same input, one batch before each timed batch: the gate divides each sample by it (experiments/reference_build.h)"},
    {"exact_build_cpu_median", TimingRole::SamplesMedian, "the median of exact_build_cpu_samples"},
    {"exact_build_cpu_runs", TimingRole::SampleCount, "exact builds timed: depends on the machine's speed"},
    {"float_build_cpu_seconds", TimingRole::Cpu, "thread CPU seconds of the float kernel's build of the snapped input, once"},
    {"exact_build_cpu_seconds", TimingRole::Cpu, "thread CPU seconds of the exact kernel's build (snapping included), once"},
    {"job_seconds", TimingRole::Wall, "wall time of the whole job"},
};
constexpr std::string_view kGrowthMetrics[] = {"float_fragments", "exact_fragments"};
constexpr std::string_view kGroupBy[] = {"plane_eps_relative", "perturbation"};

// The input with every vertex moved to its grid point: what the float kernel builds from, so both
// kernels start from the same points.
std::vector<Polygon> on_grid(std::span<const Polygon> input, const Grid& grid) {
  std::vector<Polygon> out(input.begin(), input.end());
  for (Polygon& p : out)
    for (Vertex& v : p.verts) v.p = grid.point(*grid.snap(v.p));
  return out;
}

// The float kernel's classification (with tolerance `eps`, the float tree's) of each snapped input
// polygon kept whole against up to kClassifyPlanes node planes of the exact tree, beside the exact
// one: how often they differ and how. Polygons snapping fanned are left out (the kernels split them
// differently).
json classification_differences(const ExactTree& exact, std::span<const Polygon> snapped, std::span<const Polygon> input,
                                double eps) {
  const SnappedScene scene = snap_polygons(input);
  std::vector<std::uint32_t> planes;
  const std::size_t every = std::max<std::size_t>(1, exact.tree.nodes.size() / kClassifyPlanes);
  for (std::size_t i = 0; i < exact.tree.nodes.size() && planes.size() < kClassifyPlanes; i += every)
    if (exact.tree.nodes[i].plane != kNull) planes.push_back(exact.tree.nodes[i].plane);
  std::vector<std::uint32_t> pieces(input.size(), 0);
  for (const PlanePolygon& p : scene.polygons) ++pieces[p.source];
  std::uint64_t tests = 0, differ = 0, flattened = 0, unsplit = 0, other = 0;
  PredicateCounters counters;
  for (const PlanePolygon& p : scene.polygons) {
    if (pieces[p.source] != 1 || snapped[p.source].verts.size() != p.size()) continue;
    for (std::uint32_t plane : planes) {
      ++tests;
      const Side truth = split(p, exact.plane(plane), counters).side;
      const Side approx = classify(snapped[p.source], exact.tree.planes[plane], eps);
      if (truth == approx) continue;
      ++differ;
      if (approx == Side::Coplanar) ++flattened;
      else if (truth == Side::Spanning) ++unsplit;
      else ++other;
    }
  }
  return {{"classify_tests", tests},
          {"classify_differences", differ},
          {"classify_flattened", flattened},
          {"classify_unsplit", unsplit},
          {"classify_other", other}};
}

json shape(const char* prefix, const Tree& tree) {
  const TreeMetrics m = measure_tree(tree);
  const std::string p = prefix;
  return {{p + "_fragments", m.fragments},         {p + "_splits", m.splits},
          {p + "_nodes", m.nodes},                 {p + "_max_depth", m.max_depth},
          {p + "_mean_depth", m.mean_depth},       {p + "_dropped", m.dropped_input + m.dropped_slivers},
          {p + "_dropped_area", tree.stats.dropped_area}};
}

json order_counts(const char* prefix, const ValidationReport& r) {
  const std::string p = prefix;
  return {{p + "_violations", r.violations},
          {p + "_ties", r.ties()},
          {p + "_hit_pairs", r.hit_pairs},
          {p + "_pairs_checked", r.pairs_checked}};
}

}  // namespace

std::vector<Polygon> perturbed(std::span<const Polygon> input, double relative, std::uint64_t seed) {
  std::vector<Polygon> out(input.begin(), input.end());
  if (relative == 0) return out;
  Box box;
  for (const Polygon& p : input)
    for (const Vertex& v : p.verts) box.add(v.p);
  const double reach = relative * box.diagonal();
  for (Polygon& p : out)
    for (Vertex& v : p.verts) {
      Hasher h;
      h.add_u64(seed);
      for (double x : {v.p.x, v.p.y, v.p.z}) h.add_double(x);
      Rng rng(h.value());
      v.p += Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)} * reach;
    }
  return out;
}

KernelComparison compare_kernels(std::span<const Polygon> original, Splitter& float_splitter, Splitter& exact_splitter,
                                 const KernelSettings& ks) {
  const std::vector<Polygon> input = perturbed(original, ks.perturbation, ks.seed);
  const double exact_start = thread_cpu_seconds();
  const ExactTree exact = build_exact_tree(input, exact_splitter);
  const double exact_seconds = thread_cpu_seconds() - exact_start;
  const std::vector<Polygon> snapped = on_grid(input, exact.grid);
  BuildOptions options;
  options.plane_eps_relative = ks.plane_eps_relative;
  const double float_start = thread_cpu_seconds();
  const Tree tree = build_tree(snapped, float_splitter, options);
  const double float_seconds = thread_cpu_seconds() - float_start;

  ValidationSettings settings;
  settings.views = static_cast<int>(ks.views);
  const ValidationReport float_order = validate_tree(tree, settings);
  const ExactValidationReport exact_order = validate_exact_tree(exact, settings);

  KernelComparison out;
  json& m = out.metrics;
  m = shape("float", tree);
  m.update(shape("exact", exact.tree));
  m.update(order_counts("float", float_order));
  m.update(order_counts("exact", exact_order.report));
  m["exact_refused_hits"] = exact_order.refused;
  m["exact_exhaustive_rays"] = exact_order.exhaustive_rays;
  m["exact_recovered_hits"] = exact_order.recovered;
  m["plane_eps"] = tree.tol.plane_eps;
  m.update(classification_differences(exact, snapped, input, tree.tol.plane_eps));
  const json stats = to_json(exact.exact);
  m["snap_max_displacement"] = stats["snap"]["max_displacement"];
  m["snap_fanned"] = stats["snap"]["fanned"];
  m["snap_degenerate"] = stats["snap"]["degenerate"];
  for (const char* k : {"filtered", "exact", "on_grid", "boxes", "filter_rate"}) m[std::string("predicates_") + k] = stats["predicates"][k];
  out.invariants = {{"violations", check_tree_invariants(tree, snapped).violations + check_exact_invariants(exact).violations}};
  // The exact kernel's order is ours to answer for; the float kernel's ties and violations are the
  // tolerance's, reported as metrics.
  out.validation = {{"violations", exact_order.report.violations}, {"rays", exact_order.report.rays}};
  out.timings = {{"float_build_cpu_seconds", float_seconds}, {"exact_build_cpu_seconds", exact_seconds}};
  return out;
}

namespace {

std::unique_ptr<const Block> parse_block(const BlockReader& r, const json& j, const std::string& path) {
  r.expect(j, j.is_object(), path, "an object");
  r.check_keys(j, path, {"scenes", "meshes", "sizes", "heuristics", "seeds", "views", "plane_eps", "perturbations"});
  auto b = std::make_unique<KernelBlock>();
  std::vector<const GeneratorInfo*> sized;
  const json* meshes = r.optional(j, "meshes");
  if (meshes) {
    const auto cached = available_meshes();
    for (const auto& name : r.names(*meshes, child(path, "meshes"), "leave \"meshes\" out for none", [](const std::string& name) {
           if (!is_mesh_scene(name)) throw UsageError("'" + name + "' is not a mesh:NAME scene");
         })) {
      if (std::any_of(cached.begin(), cached.end(), [&](const MeshEntry& m) { return "mesh:" + m.name == name; }))
        b->meshes.push_back(name);
      else
        std::cerr << "kernels: " << name << " is not in the mesh cache (generators/fetch_meshes.sh); skipped\n";
    }
  }
  if (meshes && !r.optional(j, "scenes") && r.optional(j, "sizes")) r.fail(path, "\"sizes\" without \"scenes\": meshes take no size");
  if (meshes && !r.optional(j, "scenes") && b->meshes.empty()) {
    std::cerr << "kernels: " << path << ": none of its meshes is fetched; the block is left out\n";
    return nullptr;
  }
  if (!meshes || r.optional(j, "scenes")) {
    b->scenes = r.generator_names(r.required(j, path, "scenes"), child(path, "scenes"), "kernel comparison", sized);
    b->sizes = r.generator_sizes(j, path, sized);
  }
  if (const json* h = r.optional(j, "heuristics")) b->heuristics = r.heuristics(*h, child(path, "heuristics"));
  b->seeds = r.seeds(j, path);
  if (const json* v = r.optional(j, "views")) b->views = static_cast<std::uint32_t>(r.integer(*v, child(path, "views"), 1, kMaxViews));
  const auto reals = [&](const char* key, double min, std::vector<double>& out) {
    const json* list = r.optional(j, key);
    if (!list) return;
    out.clear();
    r.each(*list, child(path, key), "at least one value",
           [&](const json& x, const std::string& at) { out.push_back(r.real(x, at, min, kMaxRelative)); });
  };
  reals("plane_eps", kMinRelative, b->plane_eps);
  reals("perturbations", 0.0, b->perturbations);
  return b;
}

}  // namespace

Jobs KernelBlock::expand() const {
  Jobs out;
  for (const auto& name : meshes) {
    const std::string path = mesh_scene_path(name);
    const SceneFile file{path, file_hash(path)};
    for (const auto& h : per_node_choices_or_all(heuristics, "a kernel block"))
      for (auto seed : seeds)
        for (double eps : plane_eps)
          for (double noise : perturbations)
            out.push_back(std::make_shared<KernelJob>(SceneRun{name, {}, file, h, Shape::Strict, seed, 0, views}, eps,
                                                      noise));
  }
  for (const auto& name : scenes) {
    const GeneratorInfo& g = find_generator(name);
    for (auto n : sizes_in_range(g, sizes))
      for (const auto& h : per_node_choices_or_all(heuristics, "a kernel block"))
        for (auto seed : seeds)
          for (double eps : plane_eps)
            for (double noise : perturbations)
              out.push_back(std::make_shared<KernelJob>(SceneRun::generated(g, {}, h, Shape::Strict, seed, n, views), eps,
                                                        noise));
  }
  return out;
}

KernelJob::KernelJob(SceneRun scene, double plane_eps_relative, double perturbation)
    : scene_(std::move(scene)), plane_eps_relative_(plane_eps_relative), perturbation_(perturbation) {
  Hasher h;
  h.add_string("kernel");
  h.add_string(scene_.hash(scene_.key_scene_text()));
  h.add_double(plane_eps_relative_);
  h.add_double(perturbation_);
  set_identity(h.hex(), scene_.n);
}

json KernelJob::identity() const {
  json id = scene_.identity("kernel");
  std::string command = "bspbench kernel --scene " + scene_.scene;
  if (scene_.n > 0) command += " --n " + std::to_string(scene_.n);
  id["command"] = command + " --seed " + std::to_string(scene_.seed) + scene_.heuristic->arguments() + " --views " +
                  std::to_string(scene_.views) + " --plane-eps " + exact_text(plane_eps_relative_) + " --perturb " +
                  exact_text(perturbation_);
  id["plane_eps_relative"] = plane_eps_relative_;
  id["perturbation"] = perturbation_;
  return id;
}

json KernelJob::run(const RunContext& context) const {
  const double start = wall_seconds();
  const Scene scene = scene_.make_scene();
  const KernelSettings settings{scene_.views, plane_eps_relative_, perturbation_, scene_.seed};
  KernelComparison c = compare_kernels(scene.polygons, *scene_.heuristic->splitter(scene_.seed),
                                       *scene_.heuristic->splitter(scene_.seed), settings);
  // The exact build in timed batches beside Embree's, what the gate watches.
  const ReferenceBuild reference(scene.polygons);
  const TimedBatches batches = time_batches(
      [&, input = perturbed(scene.polygons, perturbation_, scene_.seed)] {
        build_exact_tree(input, *scene_.heuristic->splitter(scene_.seed));
      },
      context.slowdown(scene_.heuristic->label), [&] { reference.run(); });
  c.timings["exact_build_cpu_samples"] = batches.samples;
  c.timings["exact_build_reference_samples"] = batches.reference;
  c.timings["exact_build_cpu_median"] = batches.median();
  c.timings["exact_build_cpu_runs"] = batches.runs;
  json id = identity();
  id["n_polygons"] = scene.polygons.size();
  id["scene_hash"] = scene_json(scene)["hash"];
  return make_record(*this, std::move(id), std::move(c.metrics), std::move(c.invariants), std::move(c.validation),
                     nullptr, std::move(c.timings), start);
}

const Kind& kernel_kind() {
  static const Kind kind{
      .name = "kernel",
      .suite_key = "kernels",
      .parse = parse_block,
      .timings = kTimings,
      .group_by = kGroupBy,
      .growth_metrics = kGrowthMetrics,
      .timing_group_word = "kernel",
      .schema_section = "KERNEL RUN",
  };
  return kind;
}

}  // namespace bsp::experiments
