// The sweep engine: suites take every registered heuristic and generator, and merge blocks every
// pair, size, heuristic, operation and seed; merge runs carry their cost and their proof; the journal survives
// interruptions (torn last line, resume without rerunning); deterministic fields do not depend on
// the thread count; shards partition a suite and merge back, rejecting duplicate, missing and
// foreign shards; aggregates recover a known power law; the declared timing fields alone decide what
// is a timing; the regression gate passes an identical report and fails a changed fragment count, a
// missing run, a violation, a ray-shooting mismatch and a group of build times significantly 1.6x
// slower, while 1.4x slower, faster, one outlier and a uniformly slower machine pass; on merge runs
// it fails a changed merge cost, a failed proof and a slower group of merges. A drawing block's
// exact kernel records the exact tree, keyed, aggregated and timed apart from the float runs. The
// complete example of analysis/SUITE_SCHEMA.md expands to the jobs its keys ask for.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "catalog.h"
#include "common/errors.h"
#include "metrics/kernel_stats.h"
#include "metrics/statistics.h"
#include "mesh_scenes.h"
#include "solid_pairs.h"
#include "split/registry.h"
#include "experiments/animate/animate.h"
#include "experiments/doom/doom.h"
#include "io/doom_iwads.h"
#include "experiments/doom/node_builders.h"
#include "experiments/draw/draw.h"
#include "experiments/heuristic_choice.h"
#include "experiments/merge/merge.h"
#include "experiments/occlude/occlude.h"
#include "experiments/kernel/kernel.h"
#include "experiments/optimal/optimal.h"
#include "experiments/reference_build.h"
#include "experiments/timing.h"
#include "gate/bench_gate.h"
#include "gate/regress.h"
#include "kinds/kinds.h"
#include "results/aggregate.h"
#include "results/record.h"
#include "results/report.h"
#include "results/shards.h"
#include "suite/catalog.h"
#include "suite/expand.h"
#include "suite/suite_file.h"
#include "sweep/journal.h"
#include "common/progress.h"
#include "sweep/runner.h"

using namespace bsp;
using namespace bsp::experiments;
using namespace bsp::gate;
using namespace bsp::results;
using namespace bsp::suite;
using namespace bsp::sweep;
namespace fs = std::filesystem;

namespace {

// A suite file's text, parsed as the sweep parses one.
Suite suite_of(const std::string& text) { return parse_suite_file(text, "test.json"); }

// 16 small jobs: enough for two sizes, two seeds and two of everything else, in a second or two.
Suite tiny_suite() {
  return suite_of(R"({"name": "tiny", "summary": "test suite", "blocks": [{"scenes": ["random-triangles", "cyclic-overlap"],
                      "heuristics": ["first", "random"], "sizes": [40, 80], "seeds": [1, 2]}]})");
}

fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() /
                       ("bspbench_sweep_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                        std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

nlohmann::json run_tiny(const Suite& suite, const fs::path& dir, int threads, std::optional<Shard> shard = {},
                     bool fresh = true) {
  SweepOptions o;
  o.threads = threads;
  o.shard = shard;
  o.journal_dir = (dir / "journal").string();
  o.fresh = fresh;
  return run_sweep(suite, o);
}

// A sweep of `suite` on 2 threads in a scratch directory, removed afterwards.
nlohmann::json sweep_once(const Suite& suite) {
  const fs::path dir = fs::temp_directory_path() / ("bspbench_sweep_" + suite.name + "_" + std::to_string(::getpid()));
  nlohmann::json r = run_tiny(suite, dir, 2);
  fs::remove_all(dir);
  return r;
}

// One tiny sweep shared by the gate tests (they only read it).
const nlohmann::json& tiny_report() {
  static const nlohmann::json report = sweep_once(tiny_suite());
  return report;
}

// 8 merge jobs: two spheres of 48 triangles each, two heuristics, two operations, two seeds.
Suite tiny_merge_suite() {
  return suite_of(R"({"name": "tiny-merge", "summary": "test suite", "merges": [{"pairs": ["spheres"],
                      "heuristics": ["first", "naylor"], "ops": ["union", "difference"], "sizes": [50], "seeds": [1, 2],
                      "points": 1000}]})");
}

const nlohmann::json& tiny_merge_report() {
  static const nlohmann::json report = sweep_once(tiny_merge_suite());
  return report;
}

// 8 animate jobs (city at 100, crystal, rebuild and merge, one and two spheres, two seeds, 4 frames)
// and 2 occlude jobs (architecture at 100, two seeds).
Suite tiny_dynamic_suite() {
  return suite_of(R"({"name": "tiny-dynamic", "summary": "test suite",
    "animations": [{"scenes": ["city"], "sizes": [100], "heuristics": ["crystal"], "strategies": ["rebuild", "merge"],
                    "moving": [1, 2], "speeds": [0.01], "seeds": [1, 2], "frames": 4, "object_n": 24,
                    "check_every": 1, "drift_every": 2, "views": 1}],
    "occlusions": [{"scenes": ["architecture"], "sizes": [100], "heuristics": ["crystal"], "seeds": [1, 2], "views": 2}]})");
}

const nlohmann::json& tiny_dynamic_report() {
  static const nlohmann::json report = sweep_once(tiny_dynamic_suite());
  return report;
}

// Suites with Doom blocks read the Freedoom IWADs as they expand (experiments/doom/doom.h); tests of them
// skip without the IWADs, as the other Doom tests do.
bool freedoom_installed() {
  return fs::exists(doom_iwad_path("freedoom1.wad")) && fs::exists(doom_iwad_path("freedoom2.wad"));
}
const std::string kNoFreedoom = "needs the Freedoom IWADs (apt-get install freedoom)";

// A suite of one Doom block, given as its JSON object.
Suite doom_only(const std::string& block) {
  return suite_of(R"({"name": "doom-test", "summary": "test suite", "doom": [)" + block + "]}");
}

// What a test asks of any job, whatever its kind.
struct JobFacts {
  std::string kind, key, scene, heuristic;
  std::uint64_t n = 0, seed = 0;
  Shape shape = Shape::Strict;
  bool incremental = false, file = false;
  std::uint32_t validation_views = 0;
  ParamAssignments scene_params;
  std::optional<SetOp> op;
  std::optional<DoomBuilder::Kind> doom;
  std::string map;
};

JobFacts facts(const Job& job) {
  JobFacts f;
  f.kind = job.kind();
  f.key = job.key();
  f.n = job.n();
  const auto scene = [&](const SceneRun& s) {
    f.scene = s.scene;
    f.heuristic = s.heuristic_label();
    f.seed = s.seed;
    f.shape = s.shape;
    f.incremental = s.incremental();
    f.file = s.file.has_value();
    f.validation_views = s.views;
    f.scene_params = s.scene_params;
  };
  if (const auto* d = dynamic_cast<const DrawJob*>(&job)) scene(d->spec());
  if (const auto* a = dynamic_cast<const AnimateJob*>(&job)) scene(a->scene());
  if (const auto* o = dynamic_cast<const OccludeJob*>(&job)) scene(o->scene());
  if (const auto* k = dynamic_cast<const KernelJob*>(&job)) scene(k->scene());
  if (const auto* o = dynamic_cast<const OptimalJob*>(&job)) scene(o->scene());
  if (const auto* m = dynamic_cast<const MergeJob*>(&job)) {
    f.scene = m->spec().pair;
    f.heuristic = m->spec().heuristic.label;
    f.seed = m->spec().seed;
    f.op = m->spec().op;
  }
  if (const auto* d = dynamic_cast<const DoomJob*>(&job)) {
    f.scene = d->spec().iwad;
    f.heuristic = d->spec().label;
    f.seed = d->spec().seed;
    f.shape = Shape::Leafy;
    f.doom = d->spec().builder.kind;
    f.map = d->spec().map;
  }
  return f;
}

// The blocks of `suite` of one kind.
std::size_t blocks_of(const Suite& suite, std::string_view kind) {
  return static_cast<std::size_t>(
      std::count_if(suite.blocks.begin(), suite.blocks.end(), [&](const SuiteBlock& b) { return b.kind->name == kind; }));
}

// 8 Doom jobs: freedoom2's MAP01 and MAP02 built by crystal and naylor (seed 1, one view), by ZDBSP,
// and as shipped.
Suite tiny_doom_suite() {
  return doom_only(R"({"iwads": ["freedoom2.wad"], "maps": ["MAP01", "MAP02"], "heuristics": ["crystal", "naylor"],
                        "builders": ["zdbsp"], "seeds": [1], "views": 1})");
}

const nlohmann::json& tiny_doom_report() {
  static const nlohmann::json report = sweep_once(tiny_doom_suite());
  return report;
}

bool doom_runs_possible() { return freedoom_installed() && !find_builder("zdbsp").path.empty(); }
const std::string kNoDoomRuns = "needs the Freedoom IWADs and ZDBSP (apt-get install freedoom zdbsp)";

// Gives every run the same calibration and five samples of `field` with a known spread around
// `time` (a job's own scale), times `factor` for the runs of `heuristic` (every run when empty).
void set_samples(nlohmann::json& report, const std::string& field, double factor, const std::string& heuristic = "",
                 double calibration = 0.1) {
  constexpr double kSpread[] = {0.98, 0.99, 1.0, 1.01, 1.02};
  double time = 1e-3;
  for (auto& run : report["runs"]) {
    time *= 1.7;  // jobs of different sizes
    const double f = heuristic.empty() || run["id"]["heuristic"] == heuristic ? factor : 1.0;
    nlohmann::json samples = nlohmann::json::array(), references = nlohmann::json::array();
    for (double s : kSpread) {
      samples.push_back(time * s * f * calibration / 0.1);
      references.push_back(2e-3 * calibration / 0.1);  // the machine's speed, as the calibration says
    }
    run["timings"][field] = samples;
    run["timings"][field.substr(0, field.find("_cpu_samples")) + "_reference_samples"] = references;
    run["calibration_seconds"] = calibration;
  }
}

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

std::size_t solid_count() {
  return static_cast<std::size_t>(std::count_if(generators().begin(), generators().end(),
                                                [](const auto& g) { return g.closed_solid; }));
}

// The scenes a suite block without a scene list runs: the catalog but its closed solids and 2D scenes.
std::size_t drawn_scene_count() {
  return static_cast<std::size_t>(std::count_if(generators().begin(), generators().end(),
                                                [](const auto& g) { return !g.closed_solid && !g.segments; }));
}

// Built-in suites load on a machine that has not fetched the sample meshes: a block of meshes
// only, none fetched, is left out (said on stderr), and the rest of the suite runs.
TEST(SweepSuites, KernelSuiteLoadsWithoutTheMeshCache) {
  const std::filesystem::path empty = std::filesystem::temp_directory_path() / ("bspbench-no-meshes-" + std::to_string(getpid()));
  std::filesystem::create_directories(empty);
  const char* before = std::getenv("BSPBENCH_MESH_DIR");
  const std::string saved = before ? before : "";
  setenv("BSPBENCH_MESH_DIR", empty.c_str(), 1);
  experiments::Jobs jobs;
  EXPECT_NO_THROW(jobs = expand(find_suite("kernel")));
  if (before) setenv("BSPBENCH_MESH_DIR", saved.c_str(), 1);
  else unsetenv("BSPBENCH_MESH_DIR");
  std::filesystem::remove_all(empty);
  EXPECT_FALSE(jobs.empty());
  for (const auto& job : jobs) EXPECT_EQ(job->identity().dump().find("mesh:"), std::string::npos) << job->identity().dump();
}

TEST(SweepSuites, EveryRegisteredHeuristicAndGeneratorIsSweptOnceEach) {
  if (!freedoom_installed()) GTEST_SKIP() << kNoFreedoom;
  for (const auto& name : builtin_suite_names()) {
    SCOPED_TRACE(name);
    const Suite suite = find_suite(name);
    const auto jobs = expand(suite);
    std::set<std::string> keys, scenes, heuristics_seen, merge_heuristics, doom_heuristics;
    for (const auto& job : jobs) {
      const JobFacts j = facts(*job);
      keys.insert(j.key);
      // CSG programs are not generated scenes, and a csg block names the solid-tree heuristics it
      // compares; an optimal block names a few small scenes of any family, the solver's reach.
      if (j.kind == "csg" || j.kind == "optimal") continue;
      if (j.op) {
        merge_heuristics.insert(j.heuristic);
        continue;
      }
      if (j.doom) {
        if (*j.doom == DoomBuilder::Kind::Heuristic) doom_heuristics.insert(j.heuristic);
        continue;
      }
      if (!is_mesh_scene(j.scene)) scenes.insert(j.scene);
      if (!j.incremental) heuristics_seen.insert(split_heuristic_label(j.heuristic).name);
    }
    EXPECT_EQ(keys.size(), jobs.size());
    // A suite of 3D scenes runs every one of them; 2D scenes (segments) run in suites of their own,
    // which run every 2D generator.
    const auto flat = static_cast<std::size_t>(std::count_if(scenes.begin(), scenes.end(), [](const std::string& name) {
      return find_generator(name).segments;
    }));
    if (blocks_of(suite, "draw") > 0) {
      EXPECT_EQ(scenes.size() - flat, flat == scenes.size() ? 0 : drawn_scene_count());
      if (flat == scenes.size()) {
        EXPECT_EQ(flat, generators().size() - drawn_scene_count() - solid_count());
      }
    }
    // The kernel suite draws and merges with a few heuristics of distinct kinds, as it compares the kernels.
    const bool every_heuristic = blocks_of(suite, "kernel") == 0;
    if (blocks_of(suite, "draw") > 0 && every_heuristic) {
      EXPECT_EQ(heuristics_seen.size(), heuristics().size());
    }
    if (blocks_of(suite, "merge") > 0 && every_heuristic) {
      EXPECT_EQ(merge_heuristics.size(), heuristics().size());
    }
    // Doom maps: every registered heuristic and every Doom preset.
    if (blocks_of(suite, "doom") > 0) {
      EXPECT_EQ(doom_heuristics.size(), heuristics().size() + doom_presets().size());
    }
  }
}

// Per IWAD and map, a Doom block runs every heuristic label x seed, and each external builder and the
// shipped nodes once, whatever the seeds. Presets resolve to their heuristic's parameters, and every
// command repeats its run. A map the IWAD lacks, an unknown builder and a missing IWAD stop the
// suite as it expands.
TEST(SweepSuites, DoomBlocksRunHeuristicsPerSeedAndEachBuilderOncePerMap) {
  if (!freedoom_installed()) GTEST_SKIP() << kNoFreedoom;
  const auto block = [](const std::string& maps, const std::string& builders, const std::string& iwad) {
    return R"({"iwads": [")" + iwad + R"("], "maps": [)" + maps +
           R"(], "heuristics": ["crystal", "weighted:candidates=0,sample=64", "doom-splits"], "builders": [)" + builders +
           R"(], "seeds": [1, 2], "views": 2})";
  };
  const auto jobs = expand(doom_only(block(R"("MAP01", "MAP02")", R"("zdbsp", "glbsp")", "freedoom2.wad")));
  EXPECT_EQ(jobs.size(), 2u * (3 * 2 + 2 + 1));
  std::set<std::string> keys;
  for (const auto& job : jobs) {
    const JobFacts j = facts(*job);
    keys.insert(j.key);
    ASSERT_EQ(j.kind, "doom");
    const nlohmann::json id = job->identity();
    const std::string command = id["command"];
    SCOPED_TRACE(command);
    EXPECT_EQ(command.rfind("bspbench doom --iwad freedoom2.wad --maps " + j.map + " --heuristics ", 0), 0u);
    EXPECT_EQ(id["builder"], j.heuristic);
    if (*j.doom == DoomBuilder::Kind::Heuristic) {
      EXPECT_EQ(id["builder_kind"], "heuristic");
      EXPECT_NE(command.find(" --seed " + std::to_string(j.seed) + " --views 2 --json"), std::string::npos);
    } else {
      EXPECT_TRUE(id["seed"].is_null() && id["views"].is_null());
      EXPECT_EQ(id["heuristic_params"], nlohmann::json::object());
    }
    if (j.heuristic == "doom-splits") {
      EXPECT_EQ(id["preset"], "doom-splits");
      EXPECT_EQ(id["heuristic_params"]["min_relation"], 0.05);
      EXPECT_NE(command.find("--heuristics doom-splits "), std::string::npos);
    }
    if (j.heuristic[0] == 'w') {
      EXPECT_NE(command.find("--heuristics weighted:candidates=0:sample=64 "), std::string::npos);
    }
    if (j.heuristic == "zdbsp") {
      EXPECT_NE(command.find("--heuristics '' --builders zdbsp --json"), std::string::npos);
    }
  }
  EXPECT_EQ(keys.size(), jobs.size());

  EXPECT_THROW(expand(doom_only(block(R"("MAP01", "MAP99")", R"("zdbsp")", "freedoom2.wad"))), InputError);
  // An unknown builder is refused as the file is read.
  EXPECT_THROW(doom_only(block(R"("MAP01")", R"("bsp5")", "freedoom2.wad")), InputError);
  try {
    expand(doom_only(block(R"("MAP01")", R"("zdbsp")", "doom3.wad")));
    ADD_FAILURE() << "a missing IWAD expanded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(doom_iwad_path("doom3.wad")), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("apt-get install freedoom"), std::string::npos) << e.what();
  }
}

// A merge block runs every pair x size x heuristic x operation x seed, a size outside a pair's
// range is skipped, and a pair without sizes (the sponges: their level sets the count) runs once.
TEST(SweepSuites, MergeBlocksExpandToPairSizeHeuristicOperationAndSeed) {
  const Suite suite = suite_of(R"({"name": "merges", "merges": [{"heuristics": ["first", "naylor"], "sizes": [50, 1000000000000],
                                    "seeds": [1, 2], "points": 100}]})");
  experiments::Jobs jobs;
  for (auto& j : expand(suite))
    if (facts(*j).scene == "spheres" || facts(*j).scene == "sponges") jobs.push_back(j);
  EXPECT_EQ(jobs.size(), (1 + 1) * 2u * 4 * 2);
  std::set<std::string> keys;
  for (const auto& job : jobs) {
    const JobFacts j = facts(*job);
    keys.insert(j.key);
    ASSERT_TRUE(j.op.has_value());
    EXPECT_EQ(j.n, j.scene == "spheres" ? 50u : 0u);
    const nlohmann::json id = job->identity();
    EXPECT_EQ(id["kind"], "merge");
    EXPECT_EQ(id["operands"].size(), 2u);
    // The second operand is drawn and rotated with its own seed.
    EXPECT_EQ(id["operands"][1]["params"]["seed"], j.seed + kSecondSeedOffset);
    EXPECT_NE(id["command"].get<std::string>().find(" --op " + std::string(set_op_name(*j.op))), std::string::npos);
  }
  EXPECT_EQ(keys.size(), jobs.size());
}

// The float and the exact job of a block's expansion in both kernels, in either order.
std::pair<const Job&, const Job&> float_and_exact(const experiments::Jobs& both) {
  const bool exact_first = both[0]->identity().contains("kernel");
  return {*both[exact_first ? 1 : 0], *both[exact_first ? 0 : 1]};
}

// "kernels" in a merge block doubles its jobs; a float job's key is the key it had before kernels
// existed (so baselines keep matching), and an exact one's names the kernel.
TEST(SweepSuites, MergeKernelsJoinTheKeyOnlyWhenExact) {
  const auto jobs_of = [](const std::string& kernels) {
    return expand(suite_of(R"({"name": "m", "merges": [{"pairs": ["spheres"], "heuristics": ["first"], "ops": ["union"],
                                "sizes": [50], "seeds": [1], "points": 10)" + kernels + "}]}"));
  };
  const auto plain = jobs_of(""), both = jobs_of(R"(, "kernels": ["float", "exact"])");
  ASSERT_EQ(plain.size(), 1u);
  ASSERT_EQ(both.size(), 2u);
  const auto [floating, exact] = float_and_exact(both);
  EXPECT_EQ(facts(floating).key, facts(*plain[0]).key);
  EXPECT_NE(facts(exact).key, facts(*plain[0]).key);
  EXPECT_FALSE(floating.identity().contains("kernel"));
  EXPECT_EQ(exact.identity()["kernel"], "exact");
  EXPECT_NE(exact.identity()["command"].get<std::string>().find("--kernel exact"), std::string::npos);
  // Both run and record their proofs: the exact one with its volume equal to CGAL's exact one.
  const nlohmann::json report = sweep_once(suite_of(R"({"name": "m", "merges": [{"pairs": ["spheres"], "heuristics": ["first"],
      "ops": ["union"], "sizes": [50], "seeds": [1], "points": 10, "kernels": ["float", "exact"]}]})"));
  EXPECT_EQ(report["summary"]["failures"], 0) << report["failures"].dump();
  ASSERT_EQ(report["runs"].size(), 2u);
  for (const auto& run : report["runs"])
    if (run["id"].contains("kernel")) {
      EXPECT_EQ(run["validation"]["volume_equal"], true);
      EXPECT_EQ(run["invariants"]["border_edges"], 0);
    }
  try {
    jobs_of(R"(, "kernels": ["fixed"])");
    FAIL() << "an unknown kernel was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown kernel 'fixed'"), std::string::npos) << e.what();
  }
}

// A drawing block of near-degenerate at 100 polygons with crystal, two views, and `kernels` (a
// suite file's text after the block's other keys, "" for none).
Suite near_degenerate_suite(const std::string& kernels) {
  return suite_of(R"({"name": "d", "blocks": [{"scenes": ["near-degenerate"], "heuristics": ["crystal"], "sizes": [100],
                      "seeds": [1], "validation": {"views": 2})" + kernels + "}]}");
}

// The one float and the one exact drawing run of a sweep of near_degenerate_suite in both kernels,
// shared by the tests that only read it.
const nlohmann::json& both_kernels_report() {
  static const nlohmann::json report = sweep_once(near_degenerate_suite(R"(, "kernels": ["float", "exact"])"));
  return report;
}

const nlohmann::json& run_of_kernel(const nlohmann::json& report, bool exact) {
  for (const auto& run : report["runs"])
    if (run["id"].contains("kernel") == exact) return run;
  throw std::runtime_error(exact ? "no exact run" : "no float run");
}

// "kernels" in a drawing block doubles its jobs; a float job's key is the key it had before kernels
// existed (so the baseline keeps matching), and an exact one's names the kernel, as do its identity,
// its command and what makes it a run of its own.
TEST(SweepSuites, DrawKernelsJoinTheKeyOnlyWhenExact) {
  const auto plain = expand(near_degenerate_suite(""));
  const auto both = expand(near_degenerate_suite(R"(, "kernels": ["float", "exact"])"));
  ASSERT_EQ(plain.size(), 1u);
  ASSERT_EQ(both.size(), 2u);
  const auto [floating, exact] = float_and_exact(both);
  EXPECT_EQ(facts(floating).key, facts(*plain[0]).key);
  EXPECT_EQ(floating.identity(), plain[0]->identity());
  EXPECT_NE(facts(exact).key, facts(*plain[0]).key);
  EXPECT_NE(exact.measured_identity(), floating.measured_identity());
  EXPECT_EQ(exact.identity()["kernel"], "exact");
  EXPECT_EQ(exact.identity()["command"], floating.identity()["command"].get<std::string>() + " --kernel exact");
  EXPECT_EQ(dynamic_cast<const DrawJob&>(exact).kernel(), Kernel::Exact);
  EXPECT_EQ(expand(near_degenerate_suite(R"(, "kernels": ["exact"])")).size(), 1u);
}

// The block's parser refuses an unknown kernel, and the exact kernel where `bspbench build --kernel
// exact` refuses it: incremental builds, leafy trees, 2D scenes; each with one line at the key.
TEST(SweepSuites, DrawKernelsRefuseWhatTheExactKernelDoesNotBuild) {
  const auto refused = [](const std::string& text) -> std::string {
    try {
      suite_of(text);
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  const std::string head = R"({"name": "d", "blocks": [{"sizes": [100], )";
  EXPECT_EQ(refused(head + R"("scenes": ["near-degenerate"], "kernels": ["float", "fixed"]}]})"),
            "test.json: blocks[0].kernels[1]: unknown kernel 'fixed' (float or exact)");
  EXPECT_EQ(refused(head + R"("scenes": ["near-degenerate"], "kernels": []}]})"),
            "test.json: blocks[0].kernels: empty list (leave \"kernels\" out for float only)");
  EXPECT_EQ(refused(head + R"("scenes": ["near-degenerate"], "incremental": true, "kernels": ["exact"]}]})"),
            "test.json: blocks[0].kernels: the exact kernel builds recursively, not incrementally (leave \"exact\" out)");
  EXPECT_EQ(refused(head + R"("scenes": ["near-degenerate"], "shapes": ["strict", "leafy"], "kernels": ["exact"]}]})"),
            "test.json: blocks[0].kernels: the exact kernel builds strict and coarse trees, not leafy ones (leave "
            "\"exact\" or \"leafy\" out)");
  EXPECT_EQ(refused(head + R"("scenes": ["near-degenerate", "random-segments"], "kernels": ["float", "exact"]}]})"),
            "test.json: blocks[0].kernels: the exact kernel builds 3D scenes; random-segments is 2D segments");
  // Float alone asks nothing of the exact kernel.
  EXPECT_EQ(refused(head + R"("scenes": ["random-segments"], "incremental": true, "kernels": ["float"]}]})"), "accepted");
}

// An exact drawing run is the exact kernel's tree: its metrics are those of build_exact_tree's view
// (fragments, nodes and depth equal), measured as `bspbench build --kernel exact` measures them,
// with the kernel's stats beside them and their wall times among the timings; its invariants and
// order are checked exactly (plane_eps 0), with no violation and no ray-shooting cross-check.
TEST(SweepRecord, AnExactDrawingRunRecordsTheExactTree) {
  const nlohmann::json& report = both_kernels_report();
  ASSERT_EQ(report["summary"]["failures"], 0) << report["failures"].dump();
  ASSERT_EQ(report["runs"].size(), 2u);
  const nlohmann::json& run = run_of_kernel(report, true);
  const auto jobs = expand(near_degenerate_suite(R"(, "kernels": ["exact"])"));
  const Scene scene = dynamic_cast<const DrawJob&>(*jobs[0]).spec().make_scene();
  const ExactTree tree = build_exact_tree(scene.polygons, *make_splitter("crystal", {}, 1));
  const TreeMetrics expected = measure_tree(tree.tree);
  EXPECT_EQ(run["metrics"]["fragments"], expected.fragments);
  EXPECT_EQ(run["metrics"]["nodes"], expected.nodes);
  EXPECT_EQ(run["metrics"]["max_depth"], expected.max_depth);
  nlohmann::json stats = to_json(tree.exact);
  for (const char* timing : {"snap_seconds", "load_seconds", "view_seconds"}) {
    stats.erase(timing);
    EXPECT_TRUE(run["timings"].contains(std::string("exact_") + timing)) << timing;
  }
  EXPECT_EQ(run["metrics"]["exact"], stats);
  EXPECT_EQ(run["invariants"]["violations"], 0) << run["invariants"].dump();
  EXPECT_EQ(run["validation"]["violations"], 0);
  EXPECT_EQ(run["validation"]["views"], 2);
  EXPECT_EQ(run["validation"]["plane_eps"], 0.0);
  EXPECT_TRUE(run["validation"].contains("refused_hits"));
  EXPECT_TRUE(run["ray_shooting"].is_null());
  EXPECT_EQ(run["timings"]["build_cpu_samples"].size(), 5u);
  // The float run has none of it, and checks its order within a tolerance.
  const nlohmann::json& floating = run_of_kernel(report, false);
  EXPECT_FALSE(floating["metrics"].contains("exact"));
  EXPECT_GT(floating["validation"]["plane_eps"].get<double>(), 0.0);
  EXPECT_FALSE(floating["ray_shooting"].is_null());
  // The report's tables can explain every timing of the exact run.
  std::ifstream in(std::string(BSPBENCH_SOURCE_DIR) + "/analysis/metric_docs.json");
  const nlohmann::json docs = nlohmann::json::parse(in)["metrics"];
  for (const auto& [key, value] : run["timings"].items()) {
    if (value.is_number()) {
      EXPECT_TRUE(docs.contains(key)) << key << " is not in metric_docs.json";
    }
  }
}

// Float and exact drawing runs aggregate apart (the exact group's head names its kernel, the float
// one's is as before kernels existed), and the gate times them in groups of their own.
TEST(SweepRecord, ExactDrawingRunsAggregateAndAreTimedApart) {
  const nlohmann::json& report = both_kernels_report();
  ASSERT_EQ(report["aggregates"].size(), 2u);
  std::set<std::string> kernels;
  for (const auto& agg : report["aggregates"]) {
    kernels.insert(agg.value("kernel", "none"));
    ASSERT_EQ(agg["by_n"].size(), 1u);
    EXPECT_EQ(agg["by_n"][0]["runs"], 1);
  }
  EXPECT_EQ(kernels, (std::set<std::string>{"exact", "none"}));
  const RegressResult r = compare_reports(report, report, {});
  EXPECT_FALSE(r.failed());
  std::set<std::string> groups;
  for (const auto& t : r.timing_tests) groups.insert(t.group);
  EXPECT_EQ(groups, (std::set<std::string>{"near-degenerate crystal strict", "near-degenerate crystal strict exact"}));
}

// The scorers whose sources score every plane run that way too, beside their sampled defaults, in
// every suite but smoke; the label is the variant, and its parameters reach the build.
TEST(SweepSuites, ExhaustiveVariantsRunBesideTheSampledDefaults) {
  if (!freedoom_installed()) GTEST_SKIP() << kNoFreedoom;
  for (const char* name : {"quick", "default", "full"}) {
    std::set<std::string> variants;
    for (const auto& job : expand(find_suite(name))) {
      const JobFacts j = facts(*job);
      const nlohmann::json id = job->identity();
      if (j.heuristic.find(':') == std::string::npos) continue;
      variants.insert(j.heuristic);
      EXPECT_EQ(id["heuristic_params"]["candidates"], 0) << j.heuristic;
      EXPECT_NE(id["command"].get<std::string>().find(" --param candidates=0"), std::string::npos) << id["command"];
    }
    EXPECT_EQ(variants, (std::set<std::string>{"balanced:candidates=0", "min-relation:candidates=0",
                                               "weighted:candidates=0", "quake:candidates=0"}))
        << name;
  }
}

// architecture builds one 136-polygon building at every n up to 300: the quick suite draws it once
// per heuristic, shape and seed, at the smallest of those sizes, while every other scene keeps each size.
TEST(SweepSuites, SizesThatMakeTheSameSceneRunOnce) {
  if (!freedoom_installed()) GTEST_SKIP() << kNoFreedoom;
  std::map<std::string, std::set<std::uint64_t>> sizes;
  for (const auto& job : expand(find_suite("quick")))
    if (const JobFacts j = facts(*job); j.kind == "draw" && j.heuristic == "crystal" && j.shape == Shape::Strict && j.seed == 1)
      sizes[j.scene].insert(j.n);
  EXPECT_EQ(sizes["architecture"], (std::set<std::uint64_t>{100, 1000}));
  EXPECT_EQ(sizes["random-disjoint"], (std::set<std::uint64_t>{100, 300, 1000}));
}

// Growth against n is reported as the heuristic's only on scenes that keep their density; the
// catalog says which, and every run's identity carries it to the report.
TEST(SweepSuites, RunsSayWhetherTheirSceneKeepsItsDensity) {
  std::map<std::string, bool> density;
  for (const auto& job : expand(find_suite("smoke")))
    if (const JobFacts j = facts(*job); !j.op) density[j.scene] = job->identity()["constant_density"];
  for (const char* grows : {"random-triangles", "saddle-grid", "orthogonal-stacks", "coplanar-heavy"})
    EXPECT_FALSE(density.at(grows)) << grows;
  for (const char* constant : {"random-disjoint", "sphere-field", "architecture", "city", "terrain"})
    EXPECT_TRUE(density.at(constant)) << constant;
}

TEST(SweepSuites, HeuristicVariantLabelsParseAndBadOnesAreRejected) {
  const HeuristicChoice plain = HeuristicChoice::parse("crystal");
  EXPECT_EQ(plain.name, "crystal");
  EXPECT_TRUE(plain.params.empty());
  const HeuristicChoice v = HeuristicChoice::parse("weighted:candidates=0,sample=64");
  EXPECT_EQ(v.label, "weighted:candidates=0,sample=64");
  EXPECT_EQ(v.name, "weighted");
  EXPECT_EQ(v.params, (ParamAssignments{{"candidates", "0"}, {"sample", "64"}}));
  EXPECT_EQ(v.resolved.integer("candidates"), 0);
  EXPECT_EQ(v.arguments(), " --heuristic weighted --param candidates=0 --param sample=64");
  EXPECT_THROW(HeuristicChoice::parse("weighted:candidates"), UsageError);
  EXPECT_THROW(HeuristicChoice::parse("weighted:sample=-1"), UsageError);
  EXPECT_THROW(HeuristicChoice::parse("nosuch"), UsageError);
  EXPECT_EQ(HeuristicChoice::of("weighted", {{"candidates", "0"}}).label, "weighted:candidates=0");
}

// CI gates on the quick suite, so coarse leaves and the incremental build (one job per scene, size,
// shape and seed, not one per heuristic) must be in it, on every scene.
TEST(SweepSuites, QuickSuiteGatesCoarseLeavesAndTheIncrementalBuildOnEveryScene) {
  if (!freedoom_installed()) GTEST_SKIP() << kNoFreedoom;
  std::set<std::string> coarse_scenes, incremental_scenes;
  std::map<std::string, int> incremental_per_scene;
  for (const auto& job : expand(find_suite("quick"))) {
    const JobFacts j = facts(*job);
    if (j.kind != "draw") continue;
    if (j.shape == Shape::Coarse && !j.incremental) coarse_scenes.insert(j.scene);
    if (!j.incremental) continue;
    EXPECT_EQ(j.heuristic, "incremental");
    incremental_scenes.insert(j.scene);
    ++incremental_per_scene[j.scene];
  }
  EXPECT_EQ(coarse_scenes.size(), drawn_scene_count());
  EXPECT_EQ(incremental_scenes.size(), drawn_scene_count());
  for (const auto& [scene, count] : incremental_per_scene) EXPECT_LE(count, 2 * 2 * 2) << scene;  // sizes x shapes x seeds
}

// Which fields are timings each kind declares (experiments/kind.h), not guessed from a name: a
// field ending in _seconds that is not declared stays in the metrics and is compared exactly.
TEST(SweepRecord, DeclaredTimingFieldsAloneAreMovedOutOfTheMetrics) {
  const auto fields = draw_timing_fields();
  nlohmann::json metrics{{"fragments", 7}, {"build_seconds", 0.25}, {"renamed_build_seconds", 0.5}};
  nlohmann::json timings = nlohmann::json::object();
  split_timings(metrics, timings, "", fields);
  EXPECT_EQ(timings, (nlohmann::json{{"build_seconds", 0.25}}));
  EXPECT_EQ(metrics, (nlohmann::json{{"fragments", 7}, {"renamed_build_seconds", 0.5}}));
  nlohmann::json validation{{"seconds", 1.0}, {"rays_per_second", 2.0}, {"violations", 0}};
  split_timings(validation, timings, "validation_", fields);
  EXPECT_TRUE(timings.contains("validation_seconds") && timings.contains("validation_rays_per_second"));
  EXPECT_EQ(validation, (nlohmann::json{{"violations", 0}}));
  EXPECT_EQ(experiments::find_timing_field(fields, "renamed_build_seconds"), nullptr);
  EXPECT_EQ(timing_field_name(fields, TimingRole::GatedSamples), "build_cpu_samples");
  // The gate finds each kind's gated samples, and their references, through the kinds' registry.
  EXPECT_EQ(timing_of_role({{"kind", "merge"}}, TimingRole::GatedSamples), "merge_cpu_samples");
  EXPECT_EQ(timing_of_role({{"kind", "animate"}}, TimingRole::GatedSamples), "update_cpu_samples");
  EXPECT_EQ(timing_of_role(nlohmann::json::object(), TimingRole::GatedSamples), "build_cpu_samples");
  EXPECT_EQ(timing_of_role({{"kind", "doom"}}, TimingRole::ReferenceSamples), "doom_reference_samples");
}

// The in-run reference: a 2D segment stands up as a wall of two triangles, a polygon fans into
// n - 2 of them, anything smaller adds none; the build runs. Every timed batch has its reference.
TEST(ReferenceBuild, SegmentsStandAsWallsAndPolygonsFanIntoTriangles) {
  const auto poly = [](std::initializer_list<Vec3> points) {
    Polygon p;
    for (const Vec3& v : points) p.verts.push_back({v});
    return p;
  };
  const std::vector<Polygon> input{poly({{0, 0, 0}, {1, 0, 0}}), poly({{1, 0, 0}, {1, 2, 0}}),
                                   poly({{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {-1, 0.5, 1}}),
                                   poly({{5, 5, 5}})};
  const ReferenceBuild reference(input);
  EXPECT_EQ(reference.triangles(), 2u + 2u + 3u);
  EXPECT_NO_THROW(reference.run());
  const TimedBatches batches = time_batches([] {}, 1.0, [&] { reference.run(); });
  ASSERT_EQ(batches.samples.size(), static_cast<std::size_t>(kBatches));
  ASSERT_EQ(batches.reference.size(), batches.samples.size());
  for (double r : batches.reference) EXPECT_GT(r, 0.0);
  EXPECT_TRUE(time_batches([] {}).reference.empty());
}

// The run record of one job: build samples per experiments/timing.h (short builds repeated in each batch),
// the ray-shooting cross-check recorded,
// and every timing it carries declared.
TEST(SweepRecord, RunRecordHoldsBuildSamplesAndTheRayShootingCheck) {
  const nlohmann::json& run = tiny_report()["runs"][0];
  const auto& samples = run["timings"]["build_cpu_samples"];
  ASSERT_EQ(samples.size(), static_cast<std::size_t>(kBatches));
  // A 40- or 80-polygon build takes far less than kMinBatchSeconds, so every batch repeats it.
  EXPECT_GT(run["timings"]["build_cpu_builds"].get<std::uint64_t>(), 2u * kBatches);
  // One reference sample per batch: the gate divides each sample by its own.
  const auto& references = run["timings"]["build_reference_samples"];
  ASSERT_EQ(references.size(), samples.size());
  for (const auto& r : references) EXPECT_GT(r.get<double>(), 0.0);
  EXPECT_GT(run["ray_shooting"]["rays"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(run["ray_shooting"]["mismatches"], 0);
  for (const auto& [k, v] : run["timings"].items()) EXPECT_NE(find_timing_field(run["id"], k), nullptr) << k;
}

// A merge run: the operands' trees and the merge cost as metrics, the boundary's closure as
// invariants, the proof against CGAL as validation (every point accounted for), merge samples timed
// as builds are, and every timing declared.
TEST(SweepRecord, MergeRunHoldsItsCostItsProofAndMergeSamples) {
  const nlohmann::json& report = tiny_merge_report();
  ASSERT_EQ(report["runs"].size(), 8u);
  EXPECT_EQ(report["failures"].size(), 0u);
  for (const auto& run : report["runs"]) {
    const auto& id = run["id"];
    SCOPED_TRACE(id["command"].get<std::string>());
    EXPECT_EQ(id["n_polygons"], id["operands"][0]["n_polygons"].get<std::uint64_t>() +
                                    id["operands"][1]["n_polygons"].get<std::uint64_t>());
    const auto& m = run["metrics"];
    EXPECT_GT(m["partition_calls"].get<std::uint64_t>(), 0u);
    EXPECT_LE(m["after_nodes"].get<std::uint64_t>(), m["before_nodes"].get<std::uint64_t>());
    EXPECT_GT(m["result_volume"].get<double>(), 0.0);
    const auto& v = run["validation"];
    EXPECT_EQ(v["violations"], 0);
    EXPECT_EQ(v["points"], 1000);
    EXPECT_EQ(v["compared"].get<std::uint64_t>() + v["on_operand_surface"].get<std::uint64_t>() +
                  v["within_plane_eps"].get<std::uint64_t>(),
              1000u);
    EXPECT_EQ(run["invariants"]["violations"], 0);
    EXPECT_EQ(run["invariants"]["border_edges"], 0);
    EXPECT_EQ(run["timings"]["merge_cpu_samples"].size(), static_cast<std::size_t>(kBatches));
    EXPECT_EQ(run["timings"]["merge_reference_samples"].size(), static_cast<std::size_t>(kBatches));
    for (const auto& [k, value] : run["timings"].items()) EXPECT_NE(find_timing_field(run["id"], k), nullptr) << k;
  }
  // Aggregates group merges by pair, heuristic and operation.
  EXPECT_EQ(report["aggregates"].size(), 4u);
  EXPECT_EQ(report["aggregates"][0]["kind"], "merge");
  EXPECT_TRUE(report["aggregates"][0].contains("operation"));
}

// Animate runs: the frames' sizes, work and drift as metrics, the checked frames' violations, one
// update sample per frame after the first, and the animate command that repeats the run. Occlude
// runs: what culling emitted, the Embree proof, and timed batches of culling.
TEST(SweepRecord, AnimateAndOccludeRunsHoldTheirMeasuresProofsAndSamples) {
  const nlohmann::json& report = tiny_dynamic_report();
  ASSERT_EQ(report["runs"].size(), 10u);
  ASSERT_EQ(report["failures"].size(), 0u);
  std::size_t animate = 0, occlude = 0;
  for (const auto& run : report["runs"]) {
    const auto& id = run["id"];
    EXPECT_EQ(run["invariants"]["violations"], 0);
    EXPECT_EQ(run["validation"]["violations"], 0);
    if (id["kind"] == "animate") {
      ++animate;
      EXPECT_EQ(run["timings"]["update_cpu_samples"].size(), 3u);
      EXPECT_EQ(run["metrics"]["frames_checked"], 4);
      EXPECT_TRUE(run["metrics"].contains("drift_fragments_ratio"));
      EXPECT_GT(run["metrics"]["moving_fraction"].get<double>(), 0);
      EXPECT_NE(id["command"].get<std::string>().find("--strategy " + id["strategy"].get<std::string>()), std::string::npos);
    } else {
      ASSERT_EQ(id["kind"], "occlude");
      ++occlude;
      EXPECT_GT(run["metrics"]["emitted"].get<std::uint64_t>(), 0u);
      EXPECT_GE(run["metrics"]["emitted"].get<std::uint64_t>(), run["metrics"]["seen_by_embree"].get<std::uint64_t>());
      EXPECT_GT(run["validation"]["rays"].get<std::uint64_t>(), 0u);
      EXPECT_EQ(run["timings"]["occlude_cpu_samples"].size(), static_cast<std::size_t>(kBatches));
    }
  }
  EXPECT_EQ(animate, 8u);
  EXPECT_EQ(occlude, 2u);
}

// The gate on animate and occlude runs: a changed result fails, a frame's order violation fails, and
// slower updates fail their strategy's group.
TEST(RegressGateDynamic, ChangedWorkOrAViolationFailsAndSlowerUpdatesFailTheirStrategy) {
  nlohmann::json baseline = tiny_dynamic_report(), current = tiny_dynamic_report();
  for (auto* r : {&baseline, &current}) {
    set_samples(*r, "update_cpu_samples", 1.0);
    set_samples(*r, "occlude_cpu_samples", 1.0);
  }
  RegressResult r = compare_reports(baseline, current, {});
  EXPECT_FALSE(r.failed());
  EXPECT_EQ(r.timing_groups, 3u);  // rebuild, merge, occlude
  std::size_t animate_run = 0;
  while (current["runs"][animate_run]["id"]["kind"] != "animate") ++animate_run;
  nlohmann::json changed = current;
  auto& built = changed["runs"][animate_run]["metrics"]["work_nodes_built"];
  built = built.get<std::uint64_t>() + 1;
  r = compare_reports(baseline, changed, {});
  ASSERT_TRUE(r.failed());
  EXPECT_EQ(r.changes[0].field, "metrics.work_nodes_built");
  nlohmann::json violated = current, violated_base = baseline;
  violated["runs"][animate_run]["validation"]["violations"] = 1;
  violated_base["runs"][animate_run]["validation"]["violations"] = 1;
  EXPECT_TRUE(compare_reports(violated_base, violated, {}).failed());
  for (auto& run : current["runs"])
    if (run["id"].value("strategy", "") == "merge")
      for (auto& x : run["timings"]["update_cpu_samples"]) x = x.get<double>() * 1.6;
  r = compare_reports(baseline, current, {});
  ASSERT_TRUE(r.failed());
  ASSERT_EQ(r.changes.size(), 1u);
  EXPECT_EQ(r.changes[0].field, "timings.update_cpu_samples");
  EXPECT_EQ(r.changes[0].run, "city crystal merge");
}

// Doom runs: every builder's nodes measured and checked alike; ours also proved by Embree and timed
// in batches of builds, ZDBSP's five runs timed, the shipped nodes not timed; every timing declared.
// Aggregates pool an IWAD's maps per builder.
TEST(SweepRecord, DoomRunsHoldTheirNodesTheirChecksAndTheirSamples) {
  if (!doom_runs_possible()) GTEST_SKIP() << kNoDoomRuns;
  const nlohmann::json& report = tiny_doom_report();
  ASSERT_EQ(report["runs"].size(), 8u);
  ASSERT_EQ(report["failures"].size(), 0u);
  EXPECT_EQ(report["summary"]["invariant_violations"], 0);
  std::map<std::string, std::set<std::uint64_t>> sides_per_map;
  for (const auto& run : report["runs"]) {
    const auto& id = run["id"];
    SCOPED_TRACE(id["command"].get<std::string>());
    ASSERT_EQ(id["kind"], "doom");
    sides_per_map[id["map"]].insert(id["n_polygons"].get<std::uint64_t>());
    EXPECT_EQ(id["map_hash"].get<std::string>().size(), 16u);
    const auto& m = run["metrics"];
    EXPECT_EQ(m["segs"].get<std::int64_t>(), id["n_polygons"].get<std::int64_t>() + m["splits"].get<std::int64_t>());
    EXPECT_GT(m["max_depth"].get<std::uint64_t>(), 0u);
    EXPECT_EQ(run["invariants"]["violations"], 0);
    EXPECT_FALSE(run.contains("error"));
    const auto& t = run["timings"];
    for (const auto& [k, v] : t.items()) EXPECT_NE(find_timing_field(id, k), nullptr) << k;
    if (id["builder_kind"] == "heuristic") {
      EXPECT_EQ(m["mixed_leaves"], 0);
      EXPECT_TRUE(m.contains("rounding_max_shift"));
      EXPECT_EQ(run["validation"]["violations"], 0);
      EXPECT_GT(run["validation"]["rays"].get<std::uint64_t>(), 0u);
      EXPECT_EQ(t["doom_cpu_samples"].size(), static_cast<std::size_t>(kBatches));
      EXPECT_GE(t["doom_cpu_runs"].get<std::uint64_t>(), static_cast<std::uint64_t>(kBatches));
    } else if (id["builder_kind"] == "external") {
      EXPECT_TRUE(run["validation"].is_null());
      EXPECT_EQ(t["builder_cpu_samples"].size(), static_cast<std::size_t>(kBatches));
      EXPECT_NE(id["builder_version"].get<std::string>().find("ZDBSP"), std::string::npos);
    } else {
      EXPECT_EQ(id["builder_kind"], "shipped");
      EXPECT_EQ(t.size(), 1u);  // job_seconds
    }
  }
  // Every builder starts from the same linedef sides of a map.
  for (const auto& [map, sides] : sides_per_map) EXPECT_EQ(sides.size(), 1u) << map;
  std::size_t doom_groups = 0;
  for (const auto& g : report["aggregates"]) {
    if (g["kind"] != "doom") continue;
    ++doom_groups;
    EXPECT_EQ(g["by_n"][0]["runs"], 2);  // the two maps
    EXPECT_FALSE(g["growth"]["segs"].is_null()) << g["heuristic"];
  }
  EXPECT_EQ(doom_groups, 4u);  // crystal, naylor, zdbsp, shipped
}

// BSPBENCH_PLANT_SLOWDOWN names a heuristic label, and reaches the timed builds of its Doom runs.
TEST(SweepRecord, PlantedSlowdownOfAHeuristicSlowsItsDoomBuilds) {
  if (!freedoom_installed()) GTEST_SKIP() << kNoFreedoom;
  const auto jobs = expand(doom_only(R"({"iwads": ["freedoom2.wad"], "maps": ["MAP01"], "heuristics": ["crystal"], "views": 1})"));
  const Job& ours = *jobs.front();
  ASSERT_EQ(facts(ours).heuristic, "crystal");
  const double plain = ours.run({})["timings"]["doom_cpu_seconds"].get<double>();
  const double planted = ours.run({PlantedSlowdown{"crystal", 3}})["timings"]["doom_cpu_seconds"].get<double>();
  EXPECT_GT(planted / plain, 2.0) << plain << " s, planted " << planted << " s";
}

// The gate on Doom runs: a changed split count fails, and so does a structural violation in our
// nodes, but not one in the shipped nodes (a fact about them: MAP09's shipped nodes put a seg 7.6
// units on the wrong side); builds of one heuristic 1.6x slower fail its group alone.
TEST(RegressGateDoom, ChangedSplitsOrOurViolationFailsAShippedViolationDoesNotAndSlowerBuildsFail) {
  if (!doom_runs_possible()) GTEST_SKIP() << kNoDoomRuns;
  nlohmann::json baseline = tiny_doom_report(), current = tiny_doom_report();
  for (auto* report : {&baseline, &current}) {
    set_samples(*report, "doom_cpu_samples", 1.0);
    for (auto& run : (*report)["runs"])
      if (run["id"]["builder_kind"] != "heuristic") run["timings"].erase("doom_cpu_samples");
  }
  RegressResult r = compare_reports(baseline, current, {});
  EXPECT_FALSE(r.failed());
  EXPECT_EQ(r.timing_groups, 2u);  // crystal and naylor, each pooling both maps
  const auto index_of = [&](const std::string& builder_kind) {
    std::size_t i = 0;
    while (current["runs"][i]["id"]["builder_kind"] != builder_kind) ++i;
    return i;
  };
  const std::size_t ours = index_of("heuristic"), shipped = index_of("shipped");

  nlohmann::json changed = current;
  auto& splits = changed["runs"][ours]["metrics"]["splits"];
  splits = splits.get<std::int64_t>() + 1;
  r = compare_reports(baseline, changed, {});
  ASSERT_TRUE(r.failed());
  EXPECT_EQ(r.changes[0].field, "metrics.splits");

  const auto violated = [&](std::size_t run) {
    nlohmann::json base = baseline, cur = current;
    base["runs"][run]["invariants"]["violations"] = 1;
    cur["runs"][run]["invariants"]["violations"] = 1;
    return compare_reports(base, cur, {}).failed();
  };
  EXPECT_TRUE(violated(ours));
  EXPECT_FALSE(violated(shipped));
  nlohmann::json runs = current["runs"];
  runs[shipped]["invariants"]["violations"] = 1;
  const nlohmann::json summary =
      assemble_report(current["suite"], current["shards"], runs, nlohmann::json::array())["summary"];
  EXPECT_EQ(summary["invariant_violations"], 0);
  EXPECT_EQ(summary["others_violations"], 1);

  for (auto& run : current["runs"])
    if (run["id"]["heuristic"] == "crystal")
      for (auto& x : run["timings"]["doom_cpu_samples"]) x = x.get<double>() * 1.6;
  r = compare_reports(baseline, current, {});
  ASSERT_TRUE(r.failed());
  ASSERT_EQ(r.changes.size(), 1u);
  EXPECT_EQ(r.changes[0].field, "timings.doom_cpu_samples");
  EXPECT_EQ(r.changes[0].run, "freedoom2.wad crystal doom");
}

TEST(SweepShards, PartitionTheSuiteDeterministically) {
  if (!freedoom_installed()) GTEST_SKIP() << kNoFreedoom;
  const auto jobs = expand(find_suite("quick"));
  std::multiset<std::string> seen;
  for (std::uint32_t i = 0; i < 3; ++i)
    for (const auto& j : shard_jobs(jobs, {i, 3})) seen.insert(j->key());
  EXPECT_EQ(seen.size(), jobs.size());
  EXPECT_EQ(std::set<std::string>(seen.begin(), seen.end()).size(), jobs.size());
  EXPECT_EQ(shard_jobs(jobs, parse_shard("1/3")).front()->key(), jobs[1]->key());
  for (const char* bad : {"3/3", "1", "a/3", "1/0", "-1/3", "1/3x"}) EXPECT_THROW(parse_shard(bad), UsageError) << bad;
}

TEST(SweepJournal, TornLastLineIsDroppedAndTheNextAppendStartsAFreshLine) {
  const fs::path dir = scratch_dir();
  const fs::path path = dir / "j.jsonl";
  std::ofstream(path) << R"({"key":"a","x":1})" << "\n" << R"({"key":"b","x":2})" << "\n" << R"({"key":"c","x)";
  {
    Journal j(path.string());
    ASSERT_EQ(j.records().size(), 2u);
    EXPECT_EQ(j.torn_lines(), 1u);
    j.append({{"key", "d"}});
  }
  const Journal again(path.string());
  ASSERT_EQ(again.records().size(), 3u);
  EXPECT_EQ(again.records()[2]["key"], "d");
  EXPECT_EQ(again.torn_lines(), 0u);
  fs::remove_all(dir);
}

TEST(SweepJournal, DamagedLineBeforeTheLastIsAnInputError) {
  const fs::path dir = scratch_dir();
  const fs::path path = dir / "j.jsonl";
  std::ofstream(path) << R"({"key":"a"})" << "\n" << "garbage\n" << R"({"key":"b"})" << "\n";
  EXPECT_THROW(Journal(path.string()), InputError);
  fs::remove_all(dir);
}

TEST(SweepProgress, TerminalRewritesOneLineAndPlainOutputPrintsWholeLines) {
  std::ostringstream tty, plain;
  Progress on_tty(tty, true, "sweep", "jobs", 4, 4.0), on_log(plain, false, "sweep", "jobs", 4, 4.0);
  for (int i = 0; i < 4; ++i) {
    on_tty.job_done(1.0);
    on_log.job_done(1.0);  // well within kPlainInterval: no line yet
  }
  on_tty.finish();
  on_log.finish();
  const std::string t = tty.str(), p = plain.str();
  EXPECT_EQ(std::count(t.begin(), t.end(), '\r'), 5);
  EXPECT_NE(t.find("3/4 jobs"), std::string::npos);
  EXPECT_NE(t.find("left"), std::string::npos);
  EXPECT_EQ(p.find('\r'), std::string::npos);
  EXPECT_EQ(std::count(p.begin(), p.end(), '\n'), 1);
  EXPECT_NE(p.find("4/4 jobs"), std::string::npos);
  EXPECT_EQ(p.rfind("sweep: ", 0), 0u);
}

TEST(SweepRunner, InterruptedSweepResumesWithoutRerunningFinishedJobs) {
  const fs::path dir = scratch_dir();
  const nlohmann::json complete = run_tiny(tiny_suite(), dir, 2);
  // Simulate kill -9 after five jobs, in the middle of writing the sixth.
  SweepOptions o;
  o.journal_dir = (dir / "journal").string();
  const fs::path journal = journal_path(tiny_suite(), o);
  const auto lines = lines_of(journal);
  ASSERT_EQ(lines.size(), complete["runs"].size());
  {
    std::ofstream out(journal, std::ios::trunc);
    for (int i = 0; i < 5; ++i) out << lines[i] << "\n";
    out << lines[5].substr(0, lines[5].size() / 2);
  }
  const nlohmann::json resumed = run_tiny(tiny_suite(), dir, 2, {}, false);
  EXPECT_EQ(deterministic_view(resumed), deterministic_view(complete));
  // The five journaled runs were taken as they were, timings included; the others ran again.
  std::set<std::string> kept;
  for (int i = 0; i < 5; ++i) kept.insert(nlohmann::json::parse(lines[i]).dump());
  std::size_t identical = 0;
  for (const auto& r : resumed["runs"]) identical += kept.count(r.dump());
  EXPECT_EQ(identical, 5u);
  EXPECT_EQ(lines_of(journal).size(), complete["runs"].size());
  fs::remove_all(dir);
}

TEST(SweepRunner, DeterministicFieldsDoNotDependOnTheThreadCount) {
  const fs::path dir = scratch_dir();
  const nlohmann::json one = run_tiny(tiny_suite(), dir / "1", 1);
  const nlohmann::json two = run_tiny(tiny_suite(), dir / "2", 2);
  EXPECT_EQ(one["summary"]["runs"], 16);
  EXPECT_TRUE(one["summary"]["complete"].get<bool>());
  EXPECT_EQ(deterministic_view(one), deterministic_view(two));
  EXPECT_NE(one["runs"][0]["timings"], nullptr);
  EXPECT_EQ(deterministic_view(run_tiny(tiny_merge_suite(), dir / "m1", 1)), deterministic_view(tiny_merge_report()));
  fs::remove_all(dir);
}

TEST(MergeReports, ShardsMergeToTheUnshardedReportAndBadSetsAreRejected) {
  const fs::path dir = scratch_dir();
  std::vector<NamedReport> shards;
  for (std::uint32_t i = 0; i < 3; ++i)
    shards.push_back({"shard" + std::to_string(i), run_tiny(tiny_suite(), dir, 2, Shard{i, 3})});
  EXPECT_EQ(deterministic_view(combine_shards(shards)), deterministic_view(tiny_report()));
  EXPECT_EQ(combine_shards(shards)["shards"].size(), 3u);

  auto duplicate = shards;
  duplicate[2] = duplicate[1];
  EXPECT_THROW(combine_shards(duplicate), InputError);
  auto missing = shards;
  missing.pop_back();
  EXPECT_THROW(combine_shards(missing), InputError);
  auto foreign = shards;
  foreign[1].report["suite"]["definition_hash"] = "0000000000000000";
  EXPECT_THROW(combine_shards(foreign), InputError);
  fs::remove_all(dir);
}

TEST(Aggregates, GrowthExponentOfAnExactPowerLawIsRecovered) {
  nlohmann::json runs = nlohmann::json::array();
  int key = 0;
  for (double n : {100.0, 1000.0, 10000.0})
    for (int seed = 1; seed <= 2; ++seed)
      runs.push_back({{"key", std::to_string(key++)},
                      {"id", {{"scene", "s"}, {"heuristic", "h"}, {"shape", "strict"}, {"scene_params", {{"n", n}}},
                              {"n", static_cast<std::uint64_t>(n)}, {"n_polygons", n}}},
                      {"metrics", {{"fragments", 3 * n * n}, {"nodes", 2 * n}}},
                      {"timings", {{"build_seconds", 1e-6 * n * std::sqrt(n)}}},
                      {"validation", nullptr}});
  const nlohmann::json agg = aggregate_runs(runs);
  ASSERT_EQ(agg.size(), 1u);
  EXPECT_NEAR(agg[0]["growth"]["fragments"]["exponent"].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(agg[0]["growth"]["nodes"]["exponent"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(agg[0]["timing_growth"]["build_seconds"]["exponent"].get<double>(), 1.5, 1e-12);
  EXPECT_NEAR(agg[0]["growth"]["fragments"]["r2"].get<double>(), 1.0, 1e-12);
  ASSERT_EQ(agg[0]["by_n"].size(), 3u);
  EXPECT_EQ(agg[0]["by_n"][0]["metrics"]["fragments"]["mean"].get<double>(), 3e4);
}

// Seeds are replicates: the fit over sizes goes through each size's geometric mean, so its interval
// has one point per size whatever the seeds; zero values are left out, and two sizes give no fit.
TEST(Aggregates, GrowthOverSizesFitsGeometricMeansWithAnInterval) {
  nlohmann::json runs = nlohmann::json::array();
  int key = 0;
  const std::vector<double> sizes{100, 1000, 10000, 100000};
  const std::vector<double> wobble{1.0, 1.3, 0.8, 1.1};  // off the power law, so the interval has a width
  for (std::size_t i = 0; i < sizes.size(); ++i)
    for (int seed = 1; seed <= 3; ++seed) {
      // Seeds spread by a factor growing with n: geometric mean 1, an arithmetic mean would tilt the fit.
      const double n = sizes[i], f = 2.0 + static_cast<double>(i), spread = seed == 1 ? f : seed == 2 ? 1 / f : 1.0;
      runs.push_back({{"key", std::to_string(key++)},
                      {"id", {{"scene", "s"}, {"heuristic", "h"}, {"shape", "strict"}, {"scene_params", {{"n", n}}},
                              {"n", static_cast<std::uint64_t>(n)}, {"n_polygons", n}}},
                      {"metrics", {{"fragments", 3 * n * n * wobble[i] * spread}, {"splits", i == 0 && seed == 3 ? 0.0 : n}}},
                      {"timings", {{"build_cpu_seconds", 1e-6 * n}}},
                      {"validation", nullptr}});
    }
  const nlohmann::json over = aggregate_runs(runs)[0]["growth_over_sizes"];
  std::vector<double> y;
  for (std::size_t i = 0; i < sizes.size(); ++i) y.push_back(3 * sizes[i] * sizes[i] * wobble[i]);
  const PowerFit expected = fit_power_law(sizes, y);
  const auto& fragments = over["growth"]["fragments"];
  EXPECT_NEAR(fragments["exponent"].get<double>(), expected.exponent, 1e-12);
  EXPECT_NEAR(fragments["ci95"][0].get<double>(), expected.exponent - expected.half_width, 1e-12);
  EXPECT_NEAR(fragments["ci95"][1].get<double>(), expected.exponent + expected.half_width, 1e-12);
  EXPECT_GT(expected.half_width, 0.01);
  EXPECT_EQ(fragments["sizes"], 4);
  EXPECT_NEAR(over["growth"]["splits"]["exponent"].get<double>(), 1.0, 1e-12);  // the zero is left out
  EXPECT_NEAR(over["timing_growth"]["build_cpu_seconds"]["exponent"].get<double>(), 1.0, 1e-12);
  // deterministic_view keeps the metric fits and drops the timing ones, as it drops timing_growth.
  const nlohmann::json view = deterministic_view(aggregate_runs(runs))[0]["growth_over_sizes"];
  EXPECT_TRUE(view.contains("growth"));
  EXPECT_FALSE(view.contains("timing_growth"));
  nlohmann::json two_sizes = nlohmann::json::array();
  for (const auto& r : runs)
    if (r["id"]["n"] != 100000) two_sizes.push_back(r);
  two_sizes.erase(two_sizes.begin(), two_sizes.begin() + 3);
  EXPECT_TRUE(aggregate_runs(two_sizes)[0]["growth_over_sizes"]["growth"]["fragments"].is_null());
}

class RegressGate : public ::testing::Test {
 protected:
  nlohmann::json baseline = tiny_report();
  nlohmann::json current = tiny_report();

  static void set_build_samples(nlohmann::json& report, double factor, const std::string& heuristic = "",
                                double calibration = 0.1) {
    set_samples(report, "build_cpu_samples", factor, heuristic, calibration);
  }
  void SetUp() override {
    set_build_samples(baseline, 1.0);
    set_build_samples(current, 1.0);
  }
  RegressResult gate() const { return compare_reports(baseline, current, {}); }
  bool fails() const { return gate().failed(); }
};

TEST_F(RegressGate, IdenticalReportPasses) {
  const RegressResult r = gate();
  EXPECT_FALSE(r.failed());
  EXPECT_EQ(r.runs_compared, 16u);
  EXPECT_GT(r.values_compared, 16u * 20);
  EXPECT_EQ(r.timing_groups, 4u);  // 2 scenes x 2 heuristics, each pooling 2 sizes x 2 seeds
  EXPECT_EQ(r.timing_samples, 16u * kBatches);
}

TEST_F(RegressGate, OneChangedFragmentCountFails) {
  current["runs"][7]["metrics"]["fragments"] = current["runs"][7]["metrics"]["fragments"].get<std::uint64_t>() + 1;
  const RegressResult r = gate();
  ASSERT_TRUE(r.failed());
  ASSERT_EQ(r.changes.size(), 1u);
  EXPECT_EQ(r.changes[0].field, "metrics.fragments");
}

TEST_F(RegressGate, FloatWithinTheRelativeToleranceMatchesAndBeyondItFails) {
  auto& e = current["runs"][0]["metrics"]["e_line"];
  const double v = e.get<double>();
  e = v * (1 + 0.5 * kFloatRelative);
  EXPECT_FALSE(fails());
  e = v * (1 + 4 * kFloatRelative);
  EXPECT_TRUE(fails());
}

// An undeclared field named like a timing is a result, compared exactly (record.h).
TEST_F(RegressGate, UndeclaredSecondsFieldIsComparedExactly) {
  baseline["runs"][0]["metrics"]["renamed_build_seconds"] = 0.5;
  current["runs"][0]["metrics"]["renamed_build_seconds"] = 0.5000001;
  const RegressResult r = gate();
  ASSERT_TRUE(r.failed());
  EXPECT_EQ(r.changes[0].field, "metrics.renamed_build_seconds");
}

TEST_F(RegressGate, GroupSignificantlySlowerByTheToleranceFailsAloneAndSmallerSlowdownsPass) {
  set_build_samples(current, 1.6, "random");
  const RegressResult r = gate();
  ASSERT_TRUE(r.failed());
  ASSERT_EQ(r.changes.size(), 2u);  // the two scenes' "random" groups, nothing else
  for (const auto& c : r.changes) {
    EXPECT_EQ(c.what, "slower");
    EXPECT_NE(c.run.find(" random "), std::string::npos) << c.run;
    EXPECT_EQ(c.field, "timings.build_cpu_samples");
  }
  set_build_samples(current, 1.4, "random");  // significant, but below the 1.5 tolerance
  EXPECT_FALSE(fails());
  EXPECT_TRUE(compare_reports(baseline, current, {.time_tolerance = 1.3}).failed());
}

TEST_F(RegressGate, SpeedUpIsANoteNotAFailure) {
  set_build_samples(current, 0.5, "first");
  const RegressResult r = gate();
  EXPECT_FALSE(r.failed());
  ASSERT_EQ(r.changes.size(), 2u);
  EXPECT_EQ(r.changes[0].what, "faster");
}

// One sample of one run hit by a context switch moves neither the median nor the rank test enough.
TEST_F(RegressGate, OneOutlierSampleDoesNotFail) {
  current["runs"][3]["timings"]["build_cpu_samples"][2] = 100.0;
  EXPECT_FALSE(fails());
  // Wall times are reported, not gated.
  current["runs"][3]["timings"]["build_seconds"] = 100.0;
  EXPECT_FALSE(fails());
}

TEST_F(RegressGate, SlowerMachineWithSlowerCalibrationPasses) {
  set_build_samples(current, 1.0, "", 0.4);  // every time and the calibration four times longer
  EXPECT_FALSE(fails());
}

// Reference samples (experiments/timing.h) for the build samples of `report`'s runs: 2 ms per build
// of the reference, times `slow` for the runs `slowed` picks, as a host slows both alike.
void set_references(nlohmann::json& report, double slow, const std::function<bool(std::size_t)>& slowed) {
  for (std::size_t i = 0; i < report["runs"].size(); ++i) {
    auto& t = report["runs"][i]["timings"];
    nlohmann::json refs = nlohmann::json::array();
    for (std::size_t k = 0; k < t["build_cpu_samples"].size(); ++k) {
      if (slowed(i)) t["build_cpu_samples"][k] = t["build_cpu_samples"][k].get<double>() * slow;
      refs.push_back(2e-3 * (slowed(i) ? slow : 1.0));
    }
    t["build_reference_samples"] = refs;
  }
}

// The machine runs 1.7 times slower for half the current sweep (every heuristic alike, as a host's
// load does), after the calibration was taken: the references timed beside the batches slowed too,
// so no group fails. Without them (the same samples judged by the calibration) groups fail, and a
// heuristic made 1.6 times slower under the same load still fails alone.
TEST_F(RegressGate, HostSlowdownDuringTheSweepCancelsAgainstTheInRunReference) {
  const auto second_half = [&](std::size_t i) { return i >= current["runs"].size() / 2; };
  set_references(baseline, 1.0, [](std::size_t) { return false; });
  set_references(current, 1.7, second_half);
  RegressResult r = gate();
  EXPECT_FALSE(r.failed());
  EXPECT_EQ(r.timing_pairs_by_reference, 16u);
  for (auto& run : current["runs"]) run["timings"].erase("build_reference_samples");
  r = gate();
  EXPECT_TRUE(r.failed());
  EXPECT_EQ(r.timing_pairs_by_reference, 0u);

  set_build_samples(current, 1.6, "random");
  set_references(current, 1.7, second_half);
  r = gate();
  ASSERT_TRUE(r.failed());
  for (const auto& c : r.changes) EXPECT_NE(c.run.find(" random "), std::string::npos) << c.run;
}

// A baseline from before the references: both sides are divided by their calibrations, whatever
// the current references say.
TEST_F(RegressGate, BaselineWithoutReferencesComparesBothSidesByCalibration) {
  for (auto& run : baseline["runs"]) run["timings"].erase("build_reference_samples");
  set_references(current, 1000.0, [](std::size_t i) { return i % 2 == 0; });
  for (std::size_t i = 0; i < current["runs"].size(); i += 2)  // only the references stay 1000x
    for (auto& x : current["runs"][i]["timings"]["build_cpu_samples"]) x = x.get<double>() / 1000.0;
  const RegressResult r = gate();
  EXPECT_FALSE(r.failed());
  EXPECT_EQ(r.timing_pairs, 16u);
  EXPECT_EQ(r.timing_pairs_by_reference, 0u);
}

TEST_F(RegressGate, MissingRunViolationsAndRayShootingMismatchesFailButANewRunDoesNot) {
  current["runs"].erase(current["runs"].begin() + 2);
  EXPECT_TRUE(fails());
  current = tiny_report();
  current["runs"][1]["validation"]["violations"] = 1;
  baseline["runs"][1]["validation"]["violations"] = 1;
  EXPECT_TRUE(fails());
  current = tiny_report();
  baseline = tiny_report();
  current["runs"][1]["ray_shooting"]["mismatches"] = 2;
  baseline["runs"][1]["ray_shooting"]["mismatches"] = 2;
  EXPECT_TRUE(fails());
  current = tiny_report();
  baseline = tiny_report();
  baseline["runs"].erase(baseline["runs"].begin() + 2);
  EXPECT_FALSE(fails());
}

// The gate on merge runs: results compared exactly like a drawing run's, a failed proof fails, and
// merge samples are judged per pair x heuristic x operation.
TEST(RegressGateMerges, ChangedMergeCostOrAFailedProofFailsAndSlowerMergesFailTheirGroups) {
  nlohmann::json baseline = tiny_merge_report(), current = tiny_merge_report();
  set_samples(baseline, "merge_cpu_samples", 1.0);
  set_samples(current, "merge_cpu_samples", 1.0);
  RegressResult r = compare_reports(baseline, current, {});
  EXPECT_FALSE(r.failed());
  EXPECT_EQ(r.timing_groups, 4u);  // 2 heuristics x 2 operations, each pooling 2 seeds

  nlohmann::json changed = current;
  auto& calls = changed["runs"][3]["metrics"]["partition_calls"];
  calls = calls.get<std::uint64_t>() + 1;
  r = compare_reports(baseline, changed, {});
  ASSERT_TRUE(r.failed());
  ASSERT_EQ(r.changes.size(), 1u);
  EXPECT_EQ(r.changes[0].field, "metrics.partition_calls");

  nlohmann::json unproved = current, unproved_base = baseline;
  unproved["runs"][2]["validation"]["violations"] = 1;
  unproved_base["runs"][2]["validation"]["violations"] = 1;
  EXPECT_TRUE(compare_reports(unproved_base, unproved, {}).failed());

  set_samples(current, "merge_cpu_samples", 1.6, "naylor");
  r = compare_reports(baseline, current, {});
  ASSERT_TRUE(r.failed());
  ASSERT_EQ(r.changes.size(), 2u);  // naylor's union and difference groups
  for (const auto& c : r.changes) {
    EXPECT_EQ(c.what, "slower");
    EXPECT_EQ(c.field, "timings.merge_cpu_samples");
    EXPECT_EQ(c.run.rfind("spheres naylor ", 0), 0u) << c.run;
  }
}

TEST(SweepReport, ReadingRejectsOtherSchemasVersionsAndDamagedRecords) {
  const fs::path dir = scratch_dir();
  const auto write_and_read = [&](const nlohmann::json& j) {
    std::ofstream(dir / "r.json") << j.dump();
    return read_report((dir / "r.json").string());
  };
  EXPECT_NO_THROW(write_and_read(tiny_report()));
  nlohmann::json other = tiny_report();
  other["version"] = kReportVersion + 1;
  EXPECT_THROW(write_and_read(other), InputError);
  other = tiny_report();
  other["schema"] = "something-else";
  EXPECT_THROW(write_and_read(other), InputError);
  other = tiny_report();
  other["runs"][0].erase("metrics");
  EXPECT_THROW(write_and_read(other), InputError);
  other = tiny_report();
  other["runs"][0]["id"]["kind"] = 3;
  EXPECT_THROW(write_and_read(other), InputError);
  EXPECT_NO_THROW(write_and_read(tiny_merge_report()));
  EXPECT_NO_THROW(write_and_read(tiny_dynamic_report()));
  for (const char* damage : {"strategy", "moving", "speed"}) {
    other = tiny_dynamic_report();
    for (auto& run : other["runs"])
      if (run["id"]["kind"] == "animate") run["id"].erase(damage);
    EXPECT_THROW(write_and_read(other), InputError) << damage;
  }
  for (const char* damage : {"operation", "operands"}) {
    other = tiny_merge_report();
    other["runs"][0]["id"].erase(damage);
    EXPECT_THROW(write_and_read(other), InputError) << damage;
  }
  std::ofstream(dir / "r.json") << "{not json";
  EXPECT_THROW(read_report((dir / "r.json").string()), InputError);
  EXPECT_THROW(read_report((dir / "missing.json").string()), InputError);
  fs::remove_all(dir);
}

// --- the benchmark gate (gate/bench_gate.h) -----------------------------------------------------

namespace {

nlohmann::json bench_output(double build_vs_embree, double speedup, double fragments, double peak = 1.9,
                            double vs_rays = 3.6, double vs_sort = 0.3, double machinery = -1) {
  if (machinery < 0) machinery = 0.6 * build_vs_embree;  // the build's bill in the proportion of its whole
  nlohmann::json doc;
  doc["context"] = {{"date", "today"}};
  doc["benchmarks"] = nlohmann::json::array();
  doc["benchmarks"].push_back({{"name", "scaling/build/random-disjoint/n:100000/crystal/threads:2/real_time"},
                               {"run_type", "iteration"},
                               {"build_vs_embree", build_vs_embree},
                               {"choose_vs_embree", build_vs_embree - machinery},
                               {"machinery_vs_embree", machinery},
                               {"speedup", speedup},
                               {"build_peak_vs_tree", peak},
                               {"fragments", fragments},
                               {"bytes_per_fragment", 211.0}});
  doc["benchmarks"].push_back({{"name", "scaling/traverse/random-disjoint/n:100000/crystal/real_time"},
                               {"run_type", "iteration"},
                               {"traverse_vs_embree_rays", vs_rays},
                               {"traverse_vs_sort", vs_sort},
                               {"fragments", fragments}});
  return doc;
}

bool any_change(const bsp::gate::RegressResult& r, const std::string& what, const std::string& field) {
  return std::any_of(r.changes.begin(), r.changes.end(), [&](const auto& c) { return c.what == what && c.field == field; });
}

}  // namespace

TEST(BenchGate, IdenticalOutputPassesAndComparesEveryJudgedCounter) {
  const auto r = bsp::gate::compare_benchmarks(bench_output(8, 1.8, 1e5), bench_output(8, 1.8, 1e5), {});
  EXPECT_FALSE(r.failed());
  EXPECT_EQ(r.runs_compared, 2u);
  // build_vs_embree, choose_vs_embree, machinery_vs_embree, speedup, build_peak_vs_tree, fragments,
  // bytes; traverse_vs_embree_rays, traverse_vs_sort, fragments
  EXPECT_EQ(r.values_compared, 10u);
}

// The build's bill is gated part by part: the core's own work slower by half fails by name even
// where the whole build moved less than the tolerance.
TEST(BenchGate, SlowerMachineryFailsByNameWhateverTheHeuristicsShare) {
  // 8 = 3.2 choosing + 4.8 machinery, then 3.2 + 7.5 = 10.7 (x1.34 in all, x1.56 in the machinery)
  const auto r = bsp::gate::compare_benchmarks(bench_output(8, 1.8, 1e5), bench_output(10.7, 1.8, 1e5, 1.9, 3.6, 0.3, 7.5), {});
  EXPECT_TRUE(r.failed());
  EXPECT_TRUE(any_change(r, "worse", "machinery_vs_embree"));
  EXPECT_FALSE(any_change(r, "worse", "build_vs_embree"));
}

// The traversal is gated against its paired Embree rays; a move against std::sort alone (which
// does not slow with the machine as a traversal does) is listed, not failed.
TEST(BenchGate, TraversalFailsAgainstItsPairedRaysAndIsNotedAgainstTheSort) {
  const auto base = bench_output(8, 1.8, 1e5);
  const auto slower = bsp::gate::compare_benchmarks(base, bench_output(8, 1.8, 1e5, 1.9, 5.5, 0.45), {});
  EXPECT_TRUE(slower.failed());
  EXPECT_TRUE(any_change(slower, "worse", "traverse_vs_embree_rays"));
  const auto drift = bsp::gate::compare_benchmarks(base, bench_output(8, 1.8, 1e5, 1.9, 3.7, 0.55), {});
  EXPECT_FALSE(drift.failed());
  EXPECT_TRUE(any_change(drift, "worse", "traverse_vs_sort"));
}

TEST(BenchGate, RatioWorseByTheToleranceFailsAndASmallerDriftPasses) {
  EXPECT_TRUE(any_change(bsp::gate::compare_benchmarks(bench_output(8, 1.8, 1e5), bench_output(12, 1.8, 1e5), {}),
                         "worse", "build_vs_embree"));
  EXPECT_FALSE(bsp::gate::compare_benchmarks(bench_output(8, 1.8, 1e5), bench_output(11.5, 1.8, 1e5), {}).failed());
  // A speed-up is better when higher; losing it is noted, not failed (the second core is shared).
  const auto lost_core = bsp::gate::compare_benchmarks(bench_output(8, 1.8, 1e5), bench_output(8, 1.0, 1e5), {});
  EXPECT_TRUE(any_change(lost_core, "worse", "speedup"));
  EXPECT_FALSE(lost_core.failed());
}

TEST(BenchGate, ABuildThatHoldsMoreMemoryFails) {
  const auto r = bsp::gate::compare_benchmarks(bench_output(8, 1.8, 1e5, 1.9), bench_output(8, 1.8, 1e5, 3.8), {});
  EXPECT_TRUE(r.failed());
  EXPECT_TRUE(any_change(r, "worse", "build_peak_vs_tree"));
}

TEST(BenchGate, BetterRatioIsANoteNotAFailure) {
  const auto r = bsp::gate::compare_benchmarks(bench_output(8, 1.8, 1e5), bench_output(4, 1.8, 1e5), {});
  EXPECT_FALSE(r.failed());
  EXPECT_TRUE(any_change(r, "better", "build_vs_embree"));
}

TEST(BenchGate, ChangedTreeOrMissingBenchmarkFails) {
  EXPECT_TRUE(any_change(bsp::gate::compare_benchmarks(bench_output(8, 1.8, 1e5), bench_output(8, 1.8, 1e5 + 1), {}),
                         "changed", "fragments"));
  auto fewer = bench_output(8, 1.8, 1e5);
  fewer["benchmarks"].erase(1);
  const auto r = bsp::gate::compare_benchmarks(bench_output(8, 1.8, 1e5), fewer, {});
  EXPECT_TRUE(r.failed());
  EXPECT_TRUE(any_change(r, "missing benchmark", ""));
  // The other way round the extra benchmark is new, not a regression.
  EXPECT_FALSE(bsp::gate::compare_benchmarks(fewer, bench_output(8, 1.8, 1e5), {}).failed());
}

TEST(BenchGate, ReportsAreNotBenchmarkOutputs) {
  EXPECT_TRUE(bsp::gate::is_benchmark_output(bench_output(8, 1.8, 1e5)));
  EXPECT_FALSE(bsp::gate::is_benchmark_output(nlohmann::json{{"schema", "bspbench-report"}, {"runs", nlohmann::json::array()}}));
}

// The complete example of analysis/SUITE_SCHEMA.md (its one ```json block), read as if it lay in
// examples/suites/: every key reaches the jobs it should.
TEST(SweepSuiteFile, SchemaExampleExpandsToWhatItsKeysAsk) {
  if (!freedoom_installed()) GTEST_SKIP() << kNoFreedoom;  // its Doom block reads freedoom2.wad
  std::ifstream in(std::string(BSPBENCH_SOURCE_DIR) + "/analysis/SUITE_SCHEMA.md");
  const std::string doc{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const auto begin = doc.find("```json\n");
  ASSERT_NE(begin, std::string::npos);
  const auto end = doc.find("```", begin + 8);
  const std::string text = doc.substr(begin + 8, end - begin - 8);
  const Suite suite = parse_suite_file(text, std::string(BSPBENCH_SOURCE_DIR) + "/examples/suites/full-example.json");
  EXPECT_EQ(suite.name, "full-example");
  EXPECT_EQ(suite.source.text, text);
  std::map<std::string, std::size_t> kinds;
  std::set<std::string> drawn_heuristics;
  std::size_t incremental = 0, mesh = 0, city = 0;
  for (const auto& job : expand(suite)) {
    const JobFacts j = facts(*job);
    ++kinds[j.kind];
    if (j.kind != "draw") continue;
    if (j.incremental) {
      ++incremental;
      continue;
    }
    drawn_heuristics.insert(j.heuristic);
    if (j.file) {
      ++mesh;
      EXPECT_EQ(j.scene, "file:meshes/courtyard.obj");
      EXPECT_EQ(j.validation_views, 2u);  // a mesh has no size to reduce the views at
      continue;
    }
    if (j.scene == "saddle-grid") {
      EXPECT_TRUE(j.n == 30 || j.n == 60) << j.n;  // scene_sizes
    }
    if (j.scene == "city") {
      ++city;
      EXPECT_NE(std::find(j.scene_params.begin(), j.scene_params.end(), std::pair<std::string, std::string>{"max_height", "12"}),
                j.scene_params.end());
    }
    EXPECT_EQ(j.validation_views, j.n > 500 ? 1u : 2u) << j.scene << " " << j.n;
  }
  EXPECT_EQ(drawn_heuristics, (std::set<std::string>{"crystal", "weighted:split_weight=4,coplanar_weight=1",
                                                     "naylor:candidates=8,model=area"}));
  EXPECT_EQ(mesh, 3u * 2 * 3);             // heuristics x shapes x seeds
  EXPECT_EQ(city, 2u * 3 * 2 * 3);         // sizes x heuristics x shapes x seeds
  EXPECT_EQ(incremental, (1u + 1) * 2 * 2);  // (random-disjoint at 1000 + the mesh) x shapes x seeds
  EXPECT_EQ(kinds["merge"], 2u);           // one pair, heuristic, size and seed; two operations
  EXPECT_EQ(kinds["animate"], 2u);         // one scene, size, heuristic, count, speed and seed; two strategies
  EXPECT_EQ(kinds["occlude"], 1u);
  EXPECT_EQ(kinds["optimal"], 2u * 2 * 2 * 2 * 2);  // scenes x heuristics x seeds x objectives x shapes, one size
  EXPECT_EQ(kinds["doom"], 2u + 1 + 1);    // one map: crystal and doom-splits, ZDBSP, the shipped nodes
}

// The report's tables take each drawing run's timings, like its metrics, from
// analysis/metric_docs.json; a timing added to a drawing run without its line there would show up
// unexplained (tests/test_metrics.cpp checks the metrics).
TEST(SweepRecord, EveryTimingOfADrawingRunIsDocumentedForTheReport) {
  std::ifstream in(std::string(BSPBENCH_SOURCE_DIR) + "/analysis/metric_docs.json");
  const nlohmann::json docs = nlohmann::json::parse(in)["metrics"];
  const auto jobs = expand(find_suite("smoke"));
  const auto draw = std::find_if(jobs.begin(), jobs.end(), [](const JobPtr& j) { return j->kind() == "draw"; });
  ASSERT_NE(draw, jobs.end());
  const nlohmann::json run = (*draw)->run({});
  std::size_t checked = 0;
  for (const auto& [key, value] : run["timings"].items()) {
    if (!value.is_number()) continue;  // the samples behind a median are not shown as a metric
    EXPECT_TRUE(docs.contains(key)) << key << " is not in metric_docs.json";
    ++checked;
  }
  EXPECT_GE(checked, 4u);
}

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The section of a Markdown document under the heading "## TITLE", up to the next "## ".
std::string markdown_section(const std::string& doc, std::string_view title) {
  const std::string heading = "\n## " + std::string(title) + "\n";
  const auto begin = doc.find(heading);
  if (begin == std::string::npos) return {};
  const auto end = doc.find("\n## ", begin + heading.size());
  return doc.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

// What a kind's documentation lacks: its record's section of analysis/SCHEMA.md (naming each of its
// timing fields) and its suite key in analysis/SUITE_SCHEMA.md.
std::vector<std::string> undocumented(const Kind& kind, const std::string& schema, const std::string& suite_schema) {
  std::vector<std::string> missing;
  const std::string section = markdown_section(schema, kind.schema_section);
  if (section.empty()) missing.push_back("SCHEMA.md section " + std::string(kind.schema_section));
  const auto quoted = [](std::string_view open, std::string_view name, std::string_view close) {
    return std::string(open).append(name).append(close);
  };
  for (const auto& f : kind.timings)
    if (section.find(quoted("\"", f.name, "\"")) == std::string::npos) missing.emplace_back(f.name);
  if (suite_schema.find(quoted("| `", kind.suite_key, "` |")) == std::string::npos)
    missing.push_back(quoted("SUITE_SCHEMA.md key ", kind.suite_key, ""));
  return missing;
}

}  // namespace

// Every kind's record is documented where readers look (analysis/SCHEMA.md, one section per kind
// naming every timing field the kind declares) and its blocks in analysis/SUITE_SCHEMA.md; and the
// check notices a timing left out of the docs.
TEST(SweepRecord, RecordsDocumentEveryKind) {
  const std::string schema = read_text(std::string(BSPBENCH_SOURCE_DIR) + "/analysis/SCHEMA.md");
  const std::string suite_schema = read_text(std::string(BSPBENCH_SOURCE_DIR) + "/analysis/SUITE_SCHEMA.md");
  ASSERT_FALSE(schema.empty());
  for (const Kind* kind : kinds()) EXPECT_EQ(undocumented(*kind, schema, suite_schema), std::vector<std::string>{}) << kind->name;
  std::string planted = schema;
  const auto at = planted.find("\"merge_cpu_merges\"", planted.find("\n## MERGE RUN\n"));
  ASSERT_NE(at, std::string::npos);
  planted.replace(at, 18, "\"merges_timed\"");
  EXPECT_EQ(undocumented(merge_kind(), planted, suite_schema), std::vector<std::string>{"merge_cpu_merges"});
}

// The kinds' registry: each kind once, found by its name, with a parser, a suite key of its own and
// exactly one gated timing; a record of an unknown kind is nobody's.
TEST(SweepRecord, EveryKindIsRegisteredOnceWithOneGatedTiming) {
  std::set<std::string_view> names, keys;
  for (const Kind* kind : kinds()) {
    EXPECT_TRUE(names.insert(kind->name).second) << kind->name;
    EXPECT_TRUE(keys.insert(kind->suite_key).second) << kind->suite_key;
    EXPECT_EQ(find_kind(kind->name), kind);
    EXPECT_NE(kind->parse, nullptr);
    EXPECT_EQ(std::count_if(kind->timings.begin(), kind->timings.end(),
                            [](const TimingField& f) { return f.role == TimingRole::GatedSamples; }),
              1)
        << kind->name;
  }
  EXPECT_EQ(find_kind("sculpt"), nullptr);
  EXPECT_EQ(kind_of({{"kind", "sculpt"}}), nullptr);
  EXPECT_EQ(kind_of({{"kind", 3}}), nullptr);
}
