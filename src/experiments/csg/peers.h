#pragma once
// The peer boolean engines of the csg runs, each given the same program mesh in, mesh out:
//   cgal      CGAL's corefinement step by step with exact constructions (Epeck) on the same
//             polyhedra as ours (validate/exact_measure.h), one thread, in a child process
//             (`bspbench csg FILE --engine cgal`) so the timeout can stop it; timed inside;
//   openscad  Debian's openscad rendering the same .csg file (`openscad -o out.off`, its CGAL Nef
//             backend in 2021.01), a child process: its time includes starting it and writing the OFF;
//   manifold  the manifold-3d npm package (WebAssembly, one thread) under node on the same polyhedra,
//             step by step (bench/peers/manifold/run.mjs), timed inside node (mesh in to mesh out).
// A peer that is not installed is "missing" with a note saying what to install; one that fails is
// "error" with its message; one that runs past the timeout is killed and "timeout".
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "csg/lower.h"

namespace bsp::experiments {

struct PeerResult {
  std::string engine;
  std::string status = "ok";  // ok | error | timeout | missing
  std::string note;           // the error, or what is missing
  std::string version;
  int threads = 1;
  double seconds = 0;
  double volume = 0;
  std::uint64_t triangles = 0;
  // OpenSCAD writes coordinates with 6 significant digits: its volume is known to within this
  // (the surface area times the largest rounding of a coordinate, sqrt(3) * 5e-6 * max |x|).
  double volume_rounding_bound = 0;
};

inline constexpr double kDefaultPeerTimeout = 600;  // seconds

struct PeerSettings {
  double timeout = kDefaultPeerTimeout;  // seconds
  // The bspbench executable that runs the cgal peer in a child process; empty: in this process,
  // where no timeout can stop it.
  std::filesystem::path self;
};

bool is_peer(std::string_view engine);  // cgal, openscad or manifold
PeerResult run_peer(std::string_view engine, const std::filesystem::path& program_file, const csg::Postfix& postfix,
                    const std::filesystem::path& scratch, const PeerSettings& settings);
// The cgal peer in this process: what `bspbench csg FILE --engine cgal` runs.
PeerResult run_cgal(const csg::Postfix& postfix);
// This process's executable (/proc/self/exe).
std::filesystem::path self_executable();

nlohmann::json to_json(const PeerResult& r);
PeerResult peer_result_from_json(const nlohmann::json& j);

inline constexpr std::size_t kMaxManifoldDepth = 1000;

// The program as bench/peers/manifold/run.mjs reads it: indexed triangle meshes of the leaves (convex
// faces fanned, equal coordinates one vertex) and the operations as a tree. Throws InputError for a
// hull step, which that format lacks, and for operations nested deeper than kMaxManifoldDepth.
nlohmann::json manifold_program(const csg::Postfix& postfix);

}  // namespace bsp::experiments
