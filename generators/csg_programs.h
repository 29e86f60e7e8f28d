#pragma once
// Generated CSG programs in OpenSCAD's CSG format (src/csg/program.h): the iterated workloads of
// the csg runs, where each step merges one more part into the result, as people's programs do
// (a plate drilled hole by hole; a union of many overlapping parts). Each is a function of its
// size k and seed, and is written as OpenSCAD itself would export it, so `openscad -o x.off` renders
// the very same program.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace bsp {

struct CsgProgramInfo {
  std::string_view name;
  std::string_view summary;
  std::uint64_t max_k;
  std::string (*text)(std::uint64_t k, std::uint64_t seed);
};

// drilled-plate: a 100 x 100 x 4 plate minus k cylinders (r 1.2, $fn 16) through it on a jittered
//   grid, each hole a step of one difference.
// sphere-union: the union of k spheres (r 10, $fn 24) along a random walk of steps 6 to 10, so each
//   overlaps the one before it.
const std::vector<CsgProgramInfo>& csg_programs();
// Throws UsageError naming the known programs.
const CsgProgramInfo& find_csg_program(std::string_view name);

}  // namespace bsp
