// bspbench optimal: the optimal autopartition of a small scene for one objective and tree shape
// (search/optimal.h), its tree checked like any other, and every heuristic's gap to it
// (experiments/optimal/optimal.h). Exit code 1 when the certificate fails a check or its measured
// value differs from the solver's. The search's passes show as progress on stderr, the time left
// being at most the --seconds budget's rest.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/run_args.h"
#include "common/errors.h"
#include "common/progress.h"
#include "experiments/block_reader.h"
#include "experiments/optimal/optimal.h"
#include "search/optimal.h"

namespace bsp::cli {

namespace {

void print_text(const nlohmann::json& out) {
  const auto& o = out["optimum"];
  std::printf("%s, %s, %s tree: ", out["scene"]["name"].get<std::string>().c_str(), o["objective"].get<std::string>().c_str(),
              o["shape"].get<std::string>().c_str());
  if (o["optimal"].get<bool>())
    std::printf("optimum %.10g (proved)\n", o["upper"].get<double>());
  else
    std::printf("optimum in [%.10g, %.10g] (budget ran out)\n", o["lower"].get<double>(), o["upper"].get<double>());
  const auto& s = o["solver"];
  std::printf("solver: %.3f s, %llu states, %llu expansions, greedy start %.10g\n", s["seconds"].get<double>(),
              s["states"].get<unsigned long long>(), s["expansions"].get<unsigned long long>(), o["greedy"].get<double>());
  std::printf("certificate: value %.10g, %llu invariant violations, %llu order violations over %llu rays\n",
              o["certificate_value"].get<double>(), o["invariant_violations"].get<unsigned long long>(),
              o["order_violations"].get<unsigned long long>(), o["order_rays"].get<unsigned long long>());
  std::printf("%-24s %14s %10s %10s\n", "heuristic", "value", "gap", "gap (lb)");
  for (const auto& g : o["heuristics"])
    std::printf("%-24s %14.6g %10.4f %10.4f%s\n", g["heuristic"].get<std::string>().c_str(), g["value"].get<double>(),
                g["gap_lower"].get<double>(), g["gap_upper"].get<double>(),
                g["autopartition"].get<bool>() ? "" : "  (free planes: may beat the autopartition optimum)");
}

int run(Args& args) {
  std::uint64_t seed = 1;
  const bool json = args.flag("--json");
  experiments::GapSettings settings;
  if (auto name = args.option("--objective")) {
    const auto o = objective_named(*name);
    if (!o) throw UsageError("--objective wants fragments, e_point or e_line");
    settings.solver.objective = *o;
  }
  settings.solver.shape = shape_from(args);
  settings.solver.seconds = args.real("--seconds").value_or(settings.solver.seconds);
  if (!(settings.solver.seconds > 0)) throw UsageError("--seconds wants a positive number");
  settings.solver.max_states = static_cast<std::uint64_t>(
      args.integer("--max-states", 1, 1'000'000'000).value_or(static_cast<long long>(settings.solver.max_states)));
  settings.solver.cell_margin = args.real("--margin").value_or(settings.solver.cell_margin);
  if (!(settings.solver.cell_margin >= 0)) throw UsageError("--margin wants a number >= 0");
  settings.views = static_cast<std::uint32_t>(args.integer("--views", 1, experiments::kMaxViews).value_or(settings.views));
  const std::vector<std::string> labels = args.options("--heuristic");
  Scene scene = scene_from_args(args, seed);
  args.finish();
  settings.seed = seed;
  settings.heuristics = experiments::choices_or_all(labels);
  // Progress on stderr: the search's passes against its time budget, with its bounds.
  Progress progress(std::clog, ::isatty(STDERR_FILENO) != 0, "optimal", "passes", Progress::kUnknownTotal,
                    settings.solver.seconds);
  double last_seconds = 0;
  settings.solver.on_pass = [&](const OptimalProgress& p) {
    char detail[128];
    std::snprintf(detail, sizeof detail, "bounds [%.6g, %.6g], %llu states", p.lower, p.upper,
                  static_cast<unsigned long long>(p.states));
    progress.job_done(p.seconds - std::exchange(last_seconds, p.seconds), detail);
  };
  const experiments::GapComparison c = experiments::compare_with_optimum(scene.polygons, settings);
  progress.finish();
  nlohmann::json out;
  out["scene"] = scene_json(scene);
  out["seed"] = seed;
  out["optimum"] = experiments::to_json(c);
  const bool ok = experiments::certificate_agrees(c.certificate_value, c.optimum.upper) && c.invariant_violations == 0 && c.order_violations == 0;
  out["certificate_ok"] = ok;
  if (json) std::cout << out.dump() << "\n";
  else print_text(out);
  return ok ? 0 : 1;
}

}  // namespace

Command optimal_command() {
  static const std::string usage = std::string(kSceneUsage) +
                                   " [--objective fragments|e_point|e_line] [--shape strict|coarse|leafy] [--seconds S]"
                                   " [--max-states N] [--margin M] [--heuristic LABEL]... [--views K] [--json]";
  return {"optimal", usage, "solve a small scene's optimal autopartition and every heuristic's gap to it", run,
          concat({kSceneOptions,
                  {{"--objective NAME", "fragments stored (default), or Naylor's expected cost e_point or e_line"},
                   kBuildModeOptions[0],
                   {"--seconds S", "the solver's time budget (default 60); past it the optimum is an interval"},
                   {"--max-states N", "the solver's memory budget in memoised subproblems (default 4,000,000)"},
                   {"--margin M", "the expected costs' root cell margin, of the diagonal (default 0.01)"},
                   {"--heuristic LABEL", "a heuristic to compare, NAME or NAME:k=v,k=v; repeatable (default every one)"},
                   {"--views K", "eyes the optimal tree's order is checked from (default 8)"}},
                  kJsonOption})};
}

}  // namespace bsp::cli
