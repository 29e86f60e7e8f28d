#pragma once
// Csg runs: CSG programs (programs.h) evaluated by merging solid trees and by the peer engines. A
// suite block of this kind is a "csg" entry: program x engine x (heuristic x kernel, for bspbench)
// x seed. A bspbench job evaluates the program with one heuristic in one kernel (evaluate.h, the
// pipeline `bspbench csg` runs), times repeated evaluations mesh in to mesh out against an in-run
// reference, and proves the result against CGAL step by step; a peer job (peers.h) runs one other
// engine on the same program. The record is analysis/SCHEMA.md's CSG RUN.
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/csg/programs.h"
#include "experiments/heuristic_choice.h"
#include "experiments/kind.h"
#include "tree/exact_build.h"

namespace bsp::experiments {

struct CsgBlock final : Block {
  std::vector<ProgramSource> programs;
  std::vector<std::string> engines = {"bspbench"};  // bspbench, cgal, openscad, manifold
  std::vector<std::string> heuristics;              // bspbench's; empty: octree
  std::vector<Kernel> kernels = {Kernel::Exact};
  std::vector<std::uint64_t> seeds = {1};
  std::uint64_t points = 0;
  double peer_timeout = 0;

  Jobs expand() const override;
};

struct CsgSpec {
  ProgramSource program;
  std::string engine = "bspbench";
  HeuristicChoice heuristic;  // bspbench only
  Kernel kernel = Kernel::Exact;  // bspbench only
  std::uint64_t seed = 1;         // a generated program's and the heuristic's
  std::uint64_t points = 0;
  double peer_timeout = 0;        // peers only
};

class CsgJob final : public Job {
 public:
  explicit CsgJob(CsgSpec spec);
  std::string_view kind() const override { return "csg"; }
  nlohmann::json identity() const override;
  nlohmann::json run(const RunContext& context) const override;

 private:
  nlohmann::json run_peer_job(const LoadedProgram& loaded, const std::filesystem::path& scratch, double start) const;
  CsgSpec spec_;
};

const Kind& csg_kind();

}  // namespace bsp::experiments
