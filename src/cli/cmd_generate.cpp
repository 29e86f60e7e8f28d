// bspbench generate: write a scene as OBJ, with how long making and writing it took.
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/run_args.h"
#include "common/errors.h"
#include "io/atomic_file.h"
#include "io/obj_writer.h"

namespace bsp::cli {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int run(Args& args) {
  const bool json = args.flag("--json");
  const std::string out_path = args.required("--out");
  if (!out_path.ends_with(".obj")) throw UsageError("--out must name a .obj file, not '" + out_path + "'");
  std::uint64_t seed = 1;
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = scene_from_args(args, seed);
  args.finish();
  const double generate_seconds = seconds_since(start);
  nlohmann::json report = scene_json(scene);
  const auto write_start = std::chrono::steady_clock::now();
  write_file_atomically(out_path, to_obj(scene.polygons, "bspbench scene " + report.dump()));
  report["out"] = out_path;
  report["generate_seconds"] = generate_seconds;
  report["write_seconds"] = seconds_since(write_start);
  if (json) {
    std::cout << report.dump() << "\n";
  } else {
    std::cout << "wrote " << scene.polygons.size() << " polygons of " << scene.name << " (hash "
              << report["hash"].get<std::string>() << ") to " << out_path << "; generated in " << generate_seconds
              << " s, written in " << report["write_seconds"].get<double>() << " s\n";
  }
  return 0;
}

}  // namespace

Command generate_command() {
  return {"generate", "(--scene NAME [--n N] [--seed S] [--scene-param k=v]... | --input FILE) --out FILE.obj [--json]",
          "write a scene (generated or mesh:NAME) as an OBJ file", run,
          concat({kSceneOptions, {{"--out FILE.obj", "where to write the OBJ (atomically)"}}, kJsonOption})};
}

}  // namespace bsp::cli
