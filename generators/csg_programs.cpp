#include "csg_programs.h"

#include <cmath>
#include <cstdio>

#include "common/errors.h"
#include "common/rng.h"

namespace bsp {

namespace {

// A number as OpenSCAD's CSG export writes it: up to 6 significant digits. Placements are rounded
// to the same digits here so the program is what a reader of the file sees.
std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

std::string translate(double x, double y, double z, const std::string& body) {
  return "multmatrix([[1, 0, 0, " + num(x) + "], [0, 1, 0, " + num(y) + "], [0, 0, 1, " + num(z) +
         "], [0, 0, 0, 1]]) {\n\t\t" + body + "\n\t}\n";
}

std::string drilled_plate(std::uint64_t k, std::uint64_t seed) {
  constexpr double kSide = 100, kThickness = 4, kRadius = 1.2;
  Rng rng(stream_seed(seed, 0xd1711));
  const auto per_row = static_cast<std::uint64_t>(std::ceil(std::sqrt(static_cast<double>(k))));
  const double pitch = kSide / static_cast<double>(per_row + 1);
  const double jitter = std::max(0.0, pitch / 2 - kRadius * 1.5);  // holes never touch
  std::string out = "difference() {\n\tcube(size = [" + num(kSide) + ", " + num(kSide) + ", " + num(kThickness) +
                    "], center = false);\n";
  const std::string hole = "cylinder($fn = 16, $fa = 12, $fs = 2, h = " + num(kThickness + 2) + ", r1 = " + num(kRadius) +
                           ", r2 = " + num(kRadius) + ", center = false);";
  for (std::uint64_t i = 0; i < k; ++i) {
    const double x = pitch * static_cast<double>(i % per_row + 1) + rng.uniform(-jitter, jitter);
    const double y = pitch * static_cast<double>(i / per_row + 1) + rng.uniform(-jitter, jitter);
    out += "\t" + translate(x, y, -1, hole);
  }
  return out + "}\n";
}

std::string sphere_union(std::uint64_t k, std::uint64_t seed) {
  Rng rng(stream_seed(seed, 0x5feae));
  std::string out = "union() {\n";
  double x = 0, y = 0, z = 0;
  for (std::uint64_t i = 0; i < k; ++i) {
    out += "\t" + translate(x, y, z, "sphere($fn = 24, $fa = 12, $fs = 2, r = 10);");
    // A step of 6 to 10 in a random direction: the next sphere overlaps this one.
    const double u = rng.uniform(-1, 1), phi = rng.uniform(0, 2 * M_PI), step = rng.uniform(6, 10);
    const double s = std::sqrt(1 - u * u);
    x += step * s * std::cos(phi);
    y += step * s * std::sin(phi);
    z += step * u;
  }
  return out + "}\n";
}

}  // namespace

const std::vector<CsgProgramInfo>& csg_programs() {
  static const std::vector<CsgProgramInfo> all = {
      {"drilled-plate", "a plate minus k cylinders, one difference step per hole", 100000, drilled_plate},
      {"sphere-union", "the union of k overlapping spheres along a random walk", 100000, sphere_union},
  };
  return all;
}

const CsgProgramInfo& find_csg_program(std::string_view name) {
  std::string known;
  for (const auto& p : csg_programs()) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + std::string(p.name);
  }
  throw UsageError("unknown csg program '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace bsp
