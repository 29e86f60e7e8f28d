#include "sweep/suite.h"

#include "common/errors.h"

namespace bsp::sweep {

namespace {

// Scenes built to need Omega(n^2) (saddle-grid) and Theta(n^1.5) (orthogonal-stacks) fragments get
// smaller sizes, so they do not take over a suite's time budget. Every other generator runs at the
// block's common sizes. Run times below were measured on the 2-core reference machine.
std::vector<SceneSizes> superlinear(std::vector<std::uint64_t> saddle, std::vector<std::uint64_t> stacks) {
  return {{"saddle-grid", std::move(saddle)}, {"orthogonal-stacks", std::move(stacks)}};
}

// near-degenerate's validation grows as n^2: its features are a few plane_eps wide, far below what
// Embree's float rays resolve at the scene's size, so every ray through the motif region takes
// every motif fragment as a candidate for the double-precision test (about 30 s a job at n = 3000).
std::vector<SceneSizes> with_near_degenerate(std::vector<SceneSizes> sizes, std::vector<std::uint64_t> near) {
  sizes.push_back({"near-degenerate", std::move(near)});
  return sizes;
}

// The scorers as their sources run them, scoring every plane of every node (O(m²) per node), beside
// their sampled defaults; only at the sizes where they finish in seconds.
const std::vector<std::string> kExhaustive = {"balanced:candidates=0", "min-relation:candidates=0",
                                              "weighted:candidates=0", "quake:candidates=0"};

// Set operations on two solid pairs (spheres, hollow boxes), every heuristic and operation.
MergeBlock few_merges(std::vector<std::uint64_t> sizes, std::vector<std::uint64_t> seeds, std::uint64_t points) {
  return {{"spheres", "hollow-boxes"}, {}, {}, std::move(sizes), std::move(seeds), points};
}

// Dynamic scenes for a gate: city and architecture at 300, every strategy, two object counts and
// two speeds, a dozen frames each checked every third, one fresh build half way.
AnimateBlock few_animations(std::vector<std::string> heuristics) {
  AnimateBlock b;
  b.scenes = {"city", "architecture"};
  b.sizes = {300};
  b.heuristics = std::move(heuristics);
  b.moving = {2, 6};
  b.speeds = {0.004, 0.02};
  b.seeds = {1};
  b.frames = 12;
  b.object_n = 48;
  b.check_every = 3;
  b.drift_every = 6;
  b.views = 1;
  return b;
}

// Occlusion culling of the scenes it is for: interiors, a city, a terrain.
OccludeBlock occlusions(std::vector<std::uint64_t> sizes, std::vector<std::string> heuristics,
                        std::vector<std::uint64_t> seeds, std::uint32_t views) {
  return {{"architecture", "city", "terrain"}, std::move(sizes), std::move(heuristics), std::move(seeds), views};
}

// Doom maps of one IWAD: every registered heuristic and Doom preset, one seed, beside `builders`.
DoomBlock doom_maps(std::vector<std::string> iwads, std::vector<std::string> maps, std::vector<std::string> builders,
                    std::uint32_t views) {
  return {std::move(iwads), std::move(maps), {}, std::move(builders), {1}, views};
}

Suite smoke() {
  return {"smoke",
          "9 s on 2 shared cores (458 runs): every scene and heuristic at two tiny sizes, one view; merges of "
          "two solid pairs at one; every update strategy and occlusion culling at 100; for tests and trying things out",
          {{{}, {}, {40, 100}, superlinear({16, 32}, {30, 60}), {1, 2}, {Shape::Strict}, {1, 0, 1}}},
          {few_merges({50}, {1}, 2000)},
          {[] {
            AnimateBlock b = few_animations({"crystal"});
            b.scenes = {"city"};
            b.sizes = {100};
            b.moving = {2};
            b.speeds = {0.01};
            b.frames = 4;
            b.object_n = 24;
            b.check_every = 1;
            b.drift_every = 2;
            return b;
          }()},
          {occlusions({100}, {"crystal"}, {1}, 2)}};
}

// CI's gate, so everything that can break is in it: strict trees at three sizes; coarse leaves and
// the incremental build (both shapes) at smaller sizes, which keeps them cheap; 2D segments, strict
// and leafy; two Doom maps, so our nodes are proved and their build times gated beside ZDBSP's.
Suite quick() {
  return {"quick",
          "49 s on 2 cores beside a one-thread sweep (1,466 runs): every scene and heuristic, strict at 3 sizes to 10^3 and coarse "
          "at 300, the exhaustive scorers at 300, incremental at 100 and 300, 2 seeds, 2 views; random-segments (2D) "
          "at 300 and 10^3, strict and leafy; merges of spheres and "
          "hollow boxes at 100 and 300; every update strategy and occlusion culling at 300 (occlusion also 10^3); "
          "freedoom2's MAP01 and MAP02 by every heuristic and Doom preset beside ZDBSP and the shipped nodes; CI "
          "gates on it",
          {{{}, {}, {100, 300, 1000}, superlinear({30, 60, 120}, {100, 200, 400}), {1, 2}, {Shape::Strict}, {2, 0, 2}},
           {{}, {}, {300}, superlinear({60}, {200}), {1, 2}, {Shape::Coarse}, {2, 0, 2}},
           {{}, kExhaustive, {300}, superlinear({60}, {200}), {1, 2}, {Shape::Strict}, {2, 0, 2}},
           {{}, {}, {100, 300}, superlinear({30, 60}, {100, 200}), {1, 2}, {Shape::Strict, Shape::Coarse}, {2, 0, 2},
            true},
           {{"random-segments"}, {}, {300, 1000}, {}, {1, 2}, {Shape::Strict, Shape::Leafy}, {2, 0, 2}}},
          {few_merges({100, 300}, {1, 2}, 5000)},
          {few_animations({"crystal", "naylor"})},
          {occlusions({300, 1000}, {}, {1}, 2)},
          {doom_maps({"freedoom2.wad"}, {"MAP01", "MAP02"}, {"zdbsp"}, 2)}};
}

// The research question of dynamic scenes: each strategy against rebuild as the moving share of the
// polygons and the speed grow. Every strategy, crystal's trees, checked every 10th frame, a fresh
// build every 30th.
AnimateBlock dynamic_block(std::vector<std::string> scenes, std::vector<std::uint64_t> sizes,
                           std::vector<std::uint32_t> moving, std::vector<double> speeds,
                           std::vector<std::uint64_t> seeds, std::uint32_t frames) {
  AnimateBlock b;
  b.scenes = std::move(scenes);
  b.sizes = std::move(sizes);
  b.heuristics = {"crystal"};
  b.moving = std::move(moving);
  b.speeds = std::move(speeds);
  b.seeds = std::move(seeds);
  b.frames = frames;
  b.check_every = 10;
  b.drift_every = 30;
  b.views = 1;
  return b;
}

std::vector<SceneSizes> default_sizes() {
  return with_near_degenerate(superlinear({30, 60, 120, 180}, {100, 200, 400, 800}), {100, 300, 1000});
}

// Five seeds in every block, so a verdict's paired test over seeds and an interval mean something.
Suite default_suite() {
  const std::vector<std::uint64_t> seeds = {1, 2, 3, 4, 5};
  DoomBlock doom = doom_maps({"freedoom2.wad"}, {"MAP01", "MAP02", "MAP03", "MAP04"}, {"zdbsp", "glbsp"}, 2);
  doom.seeds = seeds;
  return {"default",
          "21 min on 2 shared cores (6,562 runs): every scene and heuristic and the exhaustive scorers, 4 sizes to "
          "3*10^3 (near-degenerate to 10^3), 5 seeds, 2 views (1 past 10^3); merges of every solid pair to 10^3; every "
          "update strategy and occlusion culling at 10^3 (occlusion also 3*10^3); freedoom2's MAP01 to MAP04 by every "
          "heuristic and Doom preset beside ZDBSP, glBSP and the shipped nodes",
          {{{}, {}, {100, 300, 1000, 3000}, default_sizes(), seeds, {Shape::Strict}, {2, 1000, 1}},
           {{}, kExhaustive, {100, 300, 1000, 3000}, default_sizes(), seeds, {Shape::Strict}, {2, 1000, 1}}},
          {{{}, {}, {}, {100, 300, 1000}, seeds, 10000}},
          {dynamic_block({"city", "architecture"}, {1000}, {1, 4, 16}, {0.002, 0.008, 0.032}, seeds, 60)},
          {occlusions({1000, 3000}, {}, seeds, 4)},
          {std::move(doom)}};
}

// Set operations only: every solid pair, heuristic and operation at 300 and 10^3 polygons per
// operand, 5 seeds, 10^4 points proved per run. Larger operands are bspbench_bench_merge's: at
// 3*10^3 the proof dominates (CGAL's corefinement of two crossing cylinders alone takes 3-21 s a run,
// the boundary check of first's 231,000-node union 25 s), and the suite would run for hours.
Suite merge_suite() {
  return {"merge",
          "13 min 28 s on 2 shared cores (1,980 runs): every solid pair, heuristic and set operation at 300 and "
          "10^3 per operand, 5 seeds",
          {},
          {{{}, {}, {}, {300, 1000}, {1, 2, 3, 4, 5}, 10000}}};
}

// Dynamic scenes only: the crossover of every strategy with rebuild over 6 object counts and 4
// speeds, on city and architecture at 10^3 and 10^4.
Suite dynamic_suite() {
  return {"dynamic",
          "38 min 31 s on 2 shared cores (960 runs): every update strategy on city and architecture at 10^3 and 10^4, "
          "1 to 32 moving spheres, 4 speeds, 2 seeds, 60 frames",
          {},
          {},
          {dynamic_block({"city", "architecture"}, {1000, 10000}, {1, 2, 4, 8, 16, 32}, {0.001, 0.004, 0.016, 0.064},
                         {1, 2}, 60)}};
}

// Occlusion culling only: architecture, city and terrain at 3 sizes to 10^4, every heuristic, 3 seeds,
// 8 views. Past 10^4 the proof dominates (five rays per fragment and a pixel grid, per view) and
// culling a city from outside takes seconds a view: bspbench_bench_occlusion measures those sizes.
Suite occlusion_suite() {
  return {"occlusion",
          "13 min 17 s on 2 shared cores (243 runs): occlusion culling on architecture, city and terrain at 10^3 to "
          "10^4, every heuristic, "
          "3 seeds, 8 views",
          {},
          {},
          {},
          {occlusions({1000, 3000, 10000}, {}, {1, 2, 3}, 8)}};
}

// Doom maps only: all 68 maps of both Freedoom IWADs, every heuristic and Doom preset against ZDBSP,
// glBSP and the shipped nodes (README, "Doom maps").
Suite doom_suite() {
  return {"doom",
          "27 min on 2 shared cores (952 runs): all 68 maps of freedoom1 and freedoom2, every heuristic and both "
          "Doom presets (seed 1, 4 views) beside ZDBSP, glBSP and the shipped nodes",
          {},
          {},
          {},
          {},
          {doom_maps({"freedoom1.wad", "freedoom2.wad"}, {}, {"zdbsp", "glbsp"}, 4)}};
}

// The large sizes run every heuristic at its defaults (sampled candidates keep each build near
// n log n) on the scenes whose fragments stay near linear as n grows, except halving: its free
// planes cut sphere-field's spheres into 13 fragments per polygon at 10^5 (1.3 M fragments,
// 0.5 GB), and at 10^6 one job's validation outgrew 24 GB. halving stops at 10^5.
const std::vector<std::string> kNearLinear = {"first",  "random", "balanced", "min-relation",
                                              "weighted", "quake", "crystal", "naylor"};

Suite full() {
  return {"full",
          "11.5 h on 2 shared cores (6,034 runs): 5 sizes to 10^4 and both shapes on every scene and heuristic, 5 "
          "seeds; 3*10^4 to 10^6 on "
          "random-disjoint and sphere-field with every heuristic at its defaults but halving (to 10^5), 3 seeds",
          {{{}, {}, {100, 300, 1000, 3000, 10000}, superlinear({30, 60, 120, 240}, {100, 200, 400, 800, 1600}),
            {1, 2, 3, 4, 5}, {Shape::Strict, Shape::Coarse}, {4, 1000, 1}},
           {{}, kExhaustive, {100, 300, 1000, 3000, 10000}, superlinear({30, 60, 120, 240}, {100, 200, 400, 800, 1600}),
            {1, 2, 3, 4, 5}, {Shape::Strict}, {4, 1000, 1}},
           {{"random-disjoint", "sphere-field"}, kNearLinear, {30000, 100000, 300000, 1000000}, {},
            {1, 2, 3}, {Shape::Strict}, {1, 0, 1}},
           {{"random-disjoint", "sphere-field"}, {"halving"}, {30000, 100000}, {}, {1, 2, 3}, {Shape::Strict}, {1, 0, 1}}}};
}

// 2D segments only. The random autopartition of n disjoint segments against Paterson and Yao's
// bound n + 2n ln n, from 10^2 to 10^6 over 5 seeds; and every heuristic in every shape at 10^3
// and 10^4.
Suite segments_suite() {
  return {"segments",
          "10 min 36 s on 2 cores (181 runs), 2D: the random autopartition of random-segments from 10^2 to 10^6, 5 "
          "seeds; every heuristic and shape at 10^3 and 10^4, 3 seeds",
          {{{"random-segments"}, {"random"}, {100, 1000, 10000, 100000, 1000000}, {}, {1, 2, 3, 4, 5},
            {Shape::Strict}, {2, 10000, 0}},
           {{"random-segments"}, {}, {1000, 10000}, {}, {1, 2, 3}, {Shape::Strict, Shape::Coarse, Shape::Leafy},
            {2, 10000, 0}}}};
}

}  // namespace

bool is_file_scene(std::string_view scene_name) { return scene_name.starts_with(kFileScenePrefix); }

const std::vector<Suite>& suites() {
  static const std::vector<Suite> all = {smoke(), quick(), default_suite(), merge_suite(), dynamic_suite(),
                                         occlusion_suite(), segments_suite(), doom_suite(), full()};
  return all;
}

const Suite& find_suite(std::string_view name) {
  for (const auto& s : suites())
    if (s.name == name) return s;
  std::string known;
  for (const auto& s : suites()) known += (known.empty() ? "" : ", ") + s.name;
  throw UsageError("unknown suite '" + std::string(name) + "' (known: " + known + "; or a suite file, FILE.json)");
}

}  // namespace bsp::sweep
