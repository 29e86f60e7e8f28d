#include "experiments/csg/peers.h"

#include <sys/wait.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "experiments/csg/programs.h"
#include "io/mesh_reader.h"
#include "validate/exact_measure.h"

namespace bsp::experiments {

namespace {

using nlohmann::json;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `command` under coreutils' timeout; returns its exit status (124: timed out) and wall time.
// `command` is shell text whose paths went through shell_quoted.
std::pair<int, double> run_timed(const std::string& command, double timeout_seconds) {
  const auto start = std::chrono::steady_clock::now();
  const std::string cmd = "timeout -k 5 " + std::to_string(timeout_seconds) + " " + command;  // fractions allowed
  const int status = std::system(cmd.c_str());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return {code == 137 ? 124 : code, seconds};  // 137: killed by -k after ignoring the first signal
}

std::string first_line(const std::string& text) {
  const auto end = text.find('\n');
  return text.substr(0, end == std::string::npos ? text.size() : end);
}

bool have(const char* program) {
  return std::system((std::string("command -v ") + program + " > /dev/null 2>&1").c_str()) == 0;
}

PeerResult cgal_child(const std::filesystem::path& program, const std::filesystem::path& scratch, const PeerSettings& settings) {
  PeerResult r;
  r.engine = "cgal";
  const auto out = scratch / "cgal.json", log = scratch / "cgal.log";
  const auto [code, seconds] = run_timed(shell_quoted(settings.self) + " csg " + shell_quoted(program) + " --engine cgal --json > " + shell_quoted(out) +
                                             " 2> " + shell_quoted(log),
                                         settings.timeout);
  if (code == 124) return r.seconds = seconds, r.status = "timeout", r.note = "killed after " + std::to_string(settings.timeout) + " s", r;
  if (code != 0) return r.seconds = seconds, r.status = "error", r.note = first_line(slurp(log)), r;
  const json reply = json::parse(slurp(out), nullptr, false);
  if (reply.is_discarded()) return r.seconds = seconds, r.status = "error", r.note = "no JSON from the CGAL child", r;
  return peer_result_from_json(reply);
}

}  // namespace

PeerResult run_cgal(const csg::Postfix& postfix) {
  PeerResult r;
  r.engine = "cgal";
  const ExactProgramVolume v = exact_corefine_program(postfix.leaf_meshes(), postfix.steps);
  r.version = "CGAL corefinement, Epeck, step by step";
  r.seconds = v.seconds;
  r.volume = v.volume_double;
  r.triangles = v.triangles;
  if (!v.error.empty()) r.status = "error", r.note = v.error;
  return r;
}

namespace {

// Surface area times the largest rounding of one coordinate written with 6 significant digits.
double rounding_bound(const std::vector<Polygon>& polys) {
  double area_sum = 0, max_abs = 0;
  for (const Polygon& p : polys) {
    area_sum += area(p);
    for (const Vertex& v : p.verts) max_abs = std::max({max_abs, std::abs(v.p.x), std::abs(v.p.y), std::abs(v.p.z)});
  }
  return area_sum * std::sqrt(3.0) * 5e-6 * max_abs;
}


PeerResult openscad(const std::filesystem::path& program, const std::filesystem::path& scratch, double timeout) {
  PeerResult r;
  r.engine = "openscad";
  if (!have("openscad")) return r.status = "missing", r.note = "openscad is not installed (.ci/setup installs Debian's openscad)", r;
  const auto out = scratch / "openscad.off", log = scratch / "openscad.log";
  std::system(("openscad --version > " + shell_quoted(log) + " 2>&1").c_str());
  r.version = first_line(slurp(log));
  const auto [code, seconds] = run_timed("openscad -o " + shell_quoted(out) + " " + shell_quoted(program) + " > " + shell_quoted(log) + " 2>&1", timeout);
  r.seconds = seconds;
  if (code == 124) return r.status = "timeout", r.note = "killed after " + std::to_string(timeout) + " s", r;
  // An empty top-level object is a result (volume 0), though OpenSCAD exits 1 and writes no file.
  if (slurp(log).find("Current top level object is empty") != std::string::npos) return r.note = "empty", r;
  if (code != 0 || !std::filesystem::exists(out)) return r.status = "error", r.note = first_line(slurp(log)), r;
  try {
    const Scene result = read_mesh(out.string());
    r.volume = enclosed_volume(result.polygons);
    r.triangles = result.polygons.size();
    r.volume_rounding_bound = rounding_bound(result.polygons);
  } catch (const InputError& e) {
    r.status = "error", r.note = e.what();  // an OFF file bspbench cannot read
  }
  return r;
}

std::filesystem::path manifold_script() { return std::filesystem::path(BSPBENCH_SOURCE_DIR) / "bench/peers/manifold/run.mjs"; }

PeerResult manifold(const csg::Postfix& postfix, const std::filesystem::path& scratch, double timeout) {
  PeerResult r;
  r.engine = "manifold";
  const auto script = manifold_script();
  if (!have("node")) return r.status = "missing", r.note = "node is not installed (.ci/setup installs nodejs)", r;
  if (!std::filesystem::exists(script.parent_path() / "node_modules/manifold-3d"))
    return r.status = "missing", r.note = "manifold-3d is not installed (.ci/setup runs npm ci in bench/peers/manifold)", r;
  json program;
  try {
    program = manifold_program(postfix);
  } catch (const InputError& e) {
    return r.status = "error", r.note = e.what(), r;
  }
  const auto in = scratch / "manifold.json", out = scratch / "manifold.out", log = scratch / "manifold.log";
  std::ofstream(in) << program.dump();
  // Three repeats, their median: the first includes compiling the WebAssembly (its README).
  const auto [code, seconds] = run_timed("node " + shell_quoted(script) + " " + shell_quoted(in) + " --repeat 3 > " + shell_quoted(out) + " 2> " + shell_quoted(log), timeout);
  if (code == 124) return r.seconds = seconds, r.status = "timeout", r.note = "killed after " + std::to_string(timeout) + " s", r;
  if (code != 0) return r.seconds = seconds, r.status = "error", r.note = first_line(slurp(log)), r;
  const json line = json::parse(slurp(out), nullptr, false);
  if (line.is_discarded() || !line.is_object()) return r.seconds = seconds, r.status = "error", r.note = "no JSON line from run.mjs", r;
  r.version = "manifold-3d " + line.value("version", "") + ", node " + line.value("node", "");
  r.threads = line.value("threads", 1);
  r.status = line.value("status", "error");
  r.note = line.value("error", "");
  r.seconds = line.value("seconds", 0.0);
  r.volume = line.value("volume", 0.0);
  r.triangles = line.value("triangles", 0);
  return r;
}

}  // namespace

bool is_peer(std::string_view engine) { return engine == "cgal" || engine == "openscad" || engine == "manifold"; }

PeerResult run_peer(std::string_view engine, const std::filesystem::path& program_file, const csg::Postfix& postfix,
                    const std::filesystem::path& scratch, const PeerSettings& settings) {
  if (engine == "cgal") return settings.self.empty() ? run_cgal(postfix) : cgal_child(program_file, scratch, settings);
  if (engine == "openscad") return openscad(program_file, scratch, settings.timeout);
  return manifold(postfix, scratch, settings.timeout);
}

std::filesystem::path self_executable() { return std::filesystem::read_symlink("/proc/self/exe"); }

// How deep the program's operations nest: run.mjs refuses more than kMaxManifoldDepth, and JSON that
// deep is written and read recursively.
std::size_t nesting(const csg::Postfix& postfix) {
  std::vector<std::size_t> depth;
  std::size_t most = 0;
  for (const Step& s : postfix.steps) {
    std::size_t d = 1;
    for (std::uint32_t i = 0; s.kind != StepKind::Leaf && i < s.count; ++i) {
      d = std::max(d, depth.back() + 1);
      depth.pop_back();
    }
    depth.push_back(d);
    most = std::max(most, d);
  }
  return most;
}

json manifold_program(const csg::Postfix& postfix) {
  if (nesting(postfix) > kMaxManifoldDepth)
    throw InputError("operations nested deeper than " + std::to_string(kMaxManifoldDepth) + ", more than the Manifold peer reads");
  json meshes = json::array();
  for (const csg::Leaf& leaf : postfix.leaves) {
    std::vector<double> vertices;
    std::vector<std::uint32_t> triangles;
    std::map<std::array<double, 3>, std::uint32_t> index;
    const auto id = [&](const Vec3& p) {
      const auto [it, fresh] = index.try_emplace({p.x, p.y, p.z}, static_cast<std::uint32_t>(index.size()));
      if (fresh) vertices.insert(vertices.end(), {p.x, p.y, p.z});
      return it->second;
    };
    for (const Polygon& p : leaf.polygons)
      for (std::size_t i = 1; i + 1 < p.verts.size(); ++i)
        triangles.insert(triangles.end(), {id(p.verts[0].p), id(p.verts[i].p), id(p.verts[i + 1].p)});
    meshes.push_back({{"vertices", vertices}, {"triangles", triangles}});
  }
  std::vector<json> stack;
  for (const Step& s : postfix.steps) {
    if (s.kind == StepKind::Leaf) {
      stack.push_back({{"mesh", s.count}});
      continue;
    }
    if (s.kind == StepKind::Hull) throw InputError("a hull of set operations: the Manifold peer's program format has no hull");
    const char* op = s.kind == StepKind::Intersection ? "intersection" : s.kind == StepKind::Difference ? "difference" : "union";
    json children = json::array();
    for (auto it = stack.end() - s.count; it != stack.end(); ++it) children.push_back(std::move(*it));
    stack.resize(stack.size() - s.count);
    stack.push_back({{"op", op}, {"children", std::move(children)}});
  }
  return {{"meshes", meshes}, {"program", stack.empty() ? json{{"op", "union"}, {"children", json::array()}} : stack.back()}};
}

PeerResult peer_result_from_json(const json& j) {
  PeerResult r;
  r.engine = j.value("engine", "");
  r.status = j.value("status", "error");
  r.note = j.value("note", "");
  r.version = j.value("version", "");
  r.threads = j.value("threads", 1);
  r.seconds = j.value("seconds", 0.0);
  r.volume = j.value("volume", 0.0);
  r.triangles = j.value("triangles", std::uint64_t{0});
  r.volume_rounding_bound = j.value("volume_rounding_bound", 0.0);
  return r;
}

json to_json(const PeerResult& r) {
  return {{"engine", r.engine},   {"status", r.status},   {"note", r.note},
          {"version", r.version}, {"threads", r.threads}, {"seconds", r.seconds},
          {"volume", r.volume},   {"triangles", r.triangles}, {"volume_rounding_bound", r.volume_rounding_bound}};
}

}  // namespace bsp::experiments
