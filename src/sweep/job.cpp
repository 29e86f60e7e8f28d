#include "sweep/job.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <map>
#include <set>

#include "catalog.h"
#include "common/errors.h"
#include "common/hash.h"
#include "dynamic/updater.h"
#include "io/mesh_reader.h"
#include "mesh_scenes.h"
#include "solid_pairs.h"
#include "split/registry.h"
#include "sweep/doom_job.h"
#include "tree/build.h"

namespace bsp::sweep {

namespace {

const ParamSpec* find_spec(const GeneratorInfo& g, std::string_view name) {
  for (const auto& p : g.params)
    if (p.name == name) return &p;
  return nullptr;
}

// The sizes a block asks of generator g: its sizes within g's `n` range, or one run at the
// defaults (size 0) when g has no `n`.
std::vector<std::uint64_t> sizes_for(const GeneratorInfo& g, const SuiteBlock& block) {
  const ParamSpec* n = find_spec(g, "n");
  if (!n) return {0};
  const std::vector<std::uint64_t>* sizes = &block.sizes;
  for (const auto& o : block.scene_sizes)
    if (o.scene == g.name) sizes = &o.sizes;
  std::vector<std::uint64_t> out;
  for (auto s : *sizes)
    if (static_cast<double>(s) >= n->min && static_cast<double>(s) <= n->max) out.push_back(s);
  return out;
}

std::vector<SceneSpec> scene_specs(const SuiteBlock& block) {
  if (!block.scenes.empty()) return block.scenes;
  std::vector<SceneSpec> all;
  for (const auto& g : generators())
    if (!g.closed_solid && !g.segments) all.push_back(g.name);
  return all;
}

std::vector<std::string> heuristic_names(const SuiteBlock& block) {
  if (block.incremental) return {std::string(kIncrementalLabel)};
  if (!block.heuristics.empty()) return block.heuristics;
  std::vector<std::string> all;
  for (const auto& h : heuristics()) all.push_back(h.name);
  return all;
}

Job make_job(const GeneratorInfo& g, const ParamAssignments& params, const std::string& heuristic, bool incremental,
             Shape shape, std::uint64_t seed, std::uint64_t n, std::uint32_t views) {
  Job job{g.name, params, heuristic, incremental, shape, seed, n, views, std::nullopt, 0, {}, std::nullopt, false,
          std::nullopt, std::nullopt};
  if (n > 0) job.scene_params.emplace_back("n", std::to_string(n));
  if (find_spec(g, "seed")) job.scene_params.emplace_back("seed", std::to_string(seed));
  assign_key(job);
  return job;
}

std::vector<std::string> pair_names(const MergeBlock& block) {
  if (!block.pairs.empty()) return block.pairs;
  std::vector<std::string> all;
  for (const auto& p : solid_pairs()) all.push_back(p.name);
  return all;
}

std::vector<SetOp> set_ops(const MergeBlock& block) {
  if (!block.ops.empty()) return block.ops;
  return {SetOp::Union, SetOp::Intersection, SetOp::Difference, SetOp::SymmetricDifference};
}

std::vector<std::uint64_t> pair_sizes(const SolidPairInfo& pair, const MergeBlock& block) {
  if (!pair.sized) return {0};
  std::vector<std::uint64_t> out;
  for (auto s : block.sizes)
    if (static_cast<double>(s) >= pair.min_n && static_cast<double>(s) <= pair.max_n) out.push_back(s);
  return out;
}

void expand_merge_block(const MergeBlock& block, std::vector<Job>& out) {
  SuiteBlock heuristics_only;
  heuristics_only.heuristics = block.heuristics;
  for (const auto& name : pair_names(block)) {
    const SolidPairInfo& pair = find_solid_pair(name);
    for (auto n : pair_sizes(pair, block))
      for (const auto& h : heuristic_names(heuristics_only))
        for (auto op : set_ops(block))
          for (auto seed : block.seeds) {
            Job job{pair.name, {}, h, false, Shape::Strict, seed, n, 0, op, block.points, {}, std::nullopt, false,
                    std::nullopt, std::nullopt};
            if (n > 0) job.scene_params.emplace_back("n", std::to_string(n));
            job.scene_params.emplace_back("seed", std::to_string(seed));
            assign_key(job);
            out.push_back(std::move(job));
          }
  }
}

std::vector<std::uint64_t> block_sizes(const GeneratorInfo& g, const std::vector<std::uint64_t>& sizes) {
  SuiteBlock b;
  b.sizes = sizes;
  return sizes_for(g, b);
}

void expand_animate_block(const AnimateBlock& block, std::vector<Job>& out) {
  SuiteBlock heuristics_only;
  heuristics_only.heuristics = block.heuristics;
  const std::vector<std::string> strategies = block.strategies.empty() ? updater_names() : block.strategies;
  for (const auto& scene : block.scenes) {
    const GeneratorInfo& g = find_generator(scene);
    for (auto n : block_sizes(g, block.sizes))
      for (const auto& h : heuristic_names(heuristics_only))
        for (const auto& strategy : strategies)
          for (auto moving : block.moving)
            for (auto speed : block.speeds)
              for (auto seed : block.seeds) {
                Job job = make_job(g, {}, h, false, Shape::Strict, seed, n, block.views);
                job.animate = AnimateParams{strategy,  moving, block.frames, block.object,     block.object_n,
                                            block.size, speed, block.spin,  block.check_every, block.drift_every};
                assign_key(job);
                out.push_back(std::move(job));
              }
  }
}

void expand_occlude_block(const OccludeBlock& block, std::vector<Job>& out) {
  SuiteBlock heuristics_only;
  heuristics_only.heuristics = block.heuristics;
  for (const auto& scene : block.scenes) {
    const GeneratorInfo& g = find_generator(scene);
    for (auto n : block_sizes(g, block.sizes))
      for (const auto& h : heuristic_names(heuristics_only))
        for (auto seed : block.seeds) {
          Job job = make_job(g, {}, h, false, Shape::Strict, seed, n, block.views);
          job.occlude = true;
          assign_key(job);
          out.push_back(std::move(job));
        }
  }
}

bool is_mesh(const SceneSpec& spec) { return is_file_scene(spec.name) || is_mesh_scene(spec.name); }

SceneFile scene_file(const SceneSpec& spec) {
  std::string path = spec.path;
  if (path.empty())
    path = is_file_scene(spec.name) ? spec.name.substr(kFileScenePrefix.size()) : mesh_scene_path(spec.name);
  std::string hash = file_hash(path);
  return {std::move(path), std::move(hash)};
}

// A mesh has no size and no seed of its own: one job per heuristic, shape and seed, at the block's
// views for small scenes (its polygon count is not known before it is read).
void expand_mesh(const SuiteBlock& block, const SceneSpec& spec, std::vector<Job>& out) {
  const SceneFile file = scene_file(spec);
  for (const auto& h : heuristic_names(block))
    for (auto shape : block.shapes)
      for (auto seed : block.seeds) {
        Job job;
        job.scene = spec.name;
        job.heuristic = h;
        job.incremental = block.incremental;
        job.shape = shape;
        job.seed = seed;
        job.validation_views = block.validation.views;
        job.file = file;
        assign_key(job);
        out.push_back(std::move(job));
      }
}

void expand_block(const SuiteBlock& block, std::vector<Job>& out) {
  for (const auto& spec : scene_specs(block)) {
    if (is_mesh(spec)) {
      expand_mesh(block, spec, out);
      continue;
    }
    const GeneratorInfo& g = find_generator(spec.name);
    for (auto n : sizes_for(g, block))
      for (const auto& h : heuristic_names(block))
        for (auto shape : block.shapes)
          for (auto seed : block.seeds)
            out.push_back(
                make_job(g, spec.params, h, block.incremental, shape, seed, n, block.validation.views_for(n)));
  }
}


ParamSet operand_params(const SolidOperand& o) {
  return ParamSet::resolve(find_generator(o.scene).params, o.params, "scene " + o.scene);
}

// A merge job's pair parameters as given (n when the pair is sized, and the seed).
nlohmann::json pair_params_json(const Job& job) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [k, v] : job.scene_params) out[k] = std::stoull(v);
  return out;
}

ParamSet scene_params(const Job& job) {
  if (job.file) return {};
  const GeneratorInfo& g = find_generator(job.scene);
  return ParamSet::resolve(g.params, job.scene_params, "scene " + g.name);
}

ParamSet heuristic_params(const Job& job) {
  if (job.incremental) return ParamSet::resolve({}, {}, job.heuristic);
  const HeuristicVariant v = parse_heuristic_variant(job.heuristic);
  const HeuristicInfo& h = find_heuristic(v.name);
  return ParamSet::resolve(h.params, v.params, "heuristic " + h.name);
}

std::string heuristic_arguments(const HeuristicVariant& v) {
  std::string out = " --heuristic " + v.name;
  for (const auto& [k, value] : v.params) out += " --param " + k + "=" + value;
  return out;
}

std::string merge_command(const Job& job) {
  std::string command = "bspbench merge";
  const auto operands = merge_operands(job);
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string which = i == 0 ? "--a" : "--b";
    command += " " + which + " " + operands[i].scene;
    for (const auto& [k, v] : operands[i].params) command += " " + which + "-param " + k + "=" + v;
  }
  return command + " --op " + std::string(set_op_name(*job.op)) + heuristic_arguments(parse_heuristic_variant(job.heuristic)) +
         " --seed " + std::to_string(job.seed) + " --points " + std::to_string(job.points);
}

// The object trees' heuristic of an animate job: halving for torres (its method), else the run's.
std::string object_heuristic(const Job& job) { return job.animate->strategy == "torres" ? "halving" : job.heuristic; }

std::string animate_command(const Job& job) {
  const AnimateParams& a = *job.animate;
  std::string command = "bspbench animate --scene " + job.scene;
  if (job.n > 0) command += " --n " + std::to_string(job.n);
  const auto real = [](double x) { return nlohmann::json(x).dump(); };
  command += " --seed " + std::to_string(job.seed) + " --moving " + std::to_string(a.moving) + " --frames " +
             std::to_string(a.frames) + " --object " + a.object + " --object-n " + std::to_string(a.object_n) +
             " --size " + real(a.size) + " --speed " + real(a.speed) + " --spin " + real(a.spin) + " --strategy " +
             a.strategy + heuristic_arguments(parse_heuristic_variant(job.heuristic));
  if (object_heuristic(job) != job.heuristic) command += " --object-heuristic " + object_heuristic(job);
  return command + " --views " + std::to_string(job.validation_views) + " --check-every " +
         std::to_string(a.check_every) + " --drift-every " + std::to_string(a.drift_every);
}

std::string occlude_command(const Job& job) {
  std::string command = "bspbench occlude --scene " + job.scene;
  if (job.n > 0) command += " --n " + std::to_string(job.n);
  return command + " --seed " + std::to_string(job.seed) + heuristic_arguments(parse_heuristic_variant(job.heuristic)) +
         " --views " + std::to_string(job.validation_views);
}

std::string build_arguments(const Job& job) {
  if (job.incremental) return " --incremental --order shuffled";
  return heuristic_arguments(parse_heuristic_variant(job.heuristic));
}

}  // namespace

HeuristicVariant parse_heuristic_variant(const std::string& label) {
  const auto colon = label.find(':');
  HeuristicVariant v{label.substr(0, colon), {}};
  if (colon == std::string::npos) return v;
  std::string_view rest(label);
  rest.remove_prefix(colon + 1);
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    v.params.push_back(parse_assignment(rest.substr(0, comma)));
    rest.remove_prefix(comma == std::string_view::npos ? rest.size() : comma + 1);
  }
  return v;
}

namespace {

// Everything that decides a run's results, with the scene given as `scene` (its resolved
// parameters for the key, its content for run_identity).
std::string run_hash(const Job& job, const std::string& scene) {
  Hasher h;
  h.add_string(job.scene);
  h.add_string(scene);
  h.add_string(job.heuristic);
  h.add_string(heuristic_params(job).canonical());
  h.add_string(shape_name(job.shape));
  h.add_u64(job.seed);
  h.add_u64(job.validation_views);
  if (job.incremental) h.add_string("incremental shuffled");
  return h.hex();
}

// A merge job's key: the pair, both operands as resolved, the operation and the points checked.
std::string merge_hash(const Job& job) {
  Hasher h;
  h.add_string("merge");
  h.add_string(job.scene);
  for (const auto& o : merge_operands(job)) {
    h.add_string(o.scene);
    h.add_string(operand_params(o).canonical());
  }
  h.add_string(job.heuristic);
  h.add_string(heuristic_params(job).canonical());
  h.add_string(set_op_name(*job.op));
  h.add_u64(job.seed);
  h.add_u64(job.points);
  return h.hex();
}

}  // namespace

std::array<SolidOperand, 2> merge_operands(const Job& job) { return find_solid_pair(job.scene).operands(job.n, job.seed); }

// An animate job's key adds its animation and strategy to the drawing run's; an occlude job's, its kind.
std::string dynamic_hash(const Job& job) {
  Hasher h;
  h.add_string(std::string(job_kind_name(job.kind())));
  h.add_string(run_hash(job, scene_params(job).canonical()));
  if (job.animate) {
    const AnimateParams& a = *job.animate;
    h.add_string(a.strategy);
    h.add_string(object_heuristic(job));
    h.add_string(a.object);
    for (const std::uint64_t v : {std::uint64_t{a.moving}, std::uint64_t{a.frames}, a.object_n,
                                  std::uint64_t{a.check_every}, std::uint64_t{a.drift_every}})
      h.add_u64(v);
    for (const double v : {a.size, a.speed, a.spin}) h.add_string(nlohmann::json(v).dump());
  }
  return h.hex();
}

// What stands for a drawing job's scene in its key: a generator's resolved parameters, a mesh's bytes.
std::string scene_key(const Job& job) {
  return job.file ? "file " + job.file->hash : scene_params(job).canonical();
}

void assign_key(Job& job) {
  switch (job.kind()) {
    case JobKind::Merge: job.key = merge_hash(job); break;
    case JobKind::Animate:
    case JobKind::Occlude: job.key = dynamic_hash(job); break;
    case JobKind::Doom: job.key = doom_key(job); break;
    case JobKind::Draw: job.key = run_hash(job, scene_key(job)); break;
  }
}

std::string_view job_kind_name(JobKind kind) {
  switch (kind) {
    case JobKind::Merge: return "merge";
    case JobKind::Animate: return "animate";
    case JobKind::Occlude: return "occlude";
    case JobKind::Doom: return "doom";
    case JobKind::Draw: break;
  }
  return "draw";
}

namespace {

// The content hash of a job's scene, generated once per process: sizes are nominal, and a generator
// may build the same scene at several (architecture's 136-polygon building at n = 30, 100 and 300).
const std::string& scene_hash(const Job& job) {
  static std::map<std::string, std::string> hashes;
  const std::string key = job.scene + " " + scene_params(job).canonical();
  auto it = hashes.find(key);
  if (it == hashes.end()) it = hashes.emplace(key, content_hash(make_scene(job.scene, job.scene_params))).first;
  return it->second;
}

// What a run measures, apart from the nominal size: two jobs alike in all of it are one run. A mesh
// has no nominal size, so its key says it all.
std::string run_identity(const Job& job) {
  return job.kind() == JobKind::Draw && !job.file ? run_hash(job, scene_hash(job)) : job.key;
}

}  // namespace

std::vector<Job> expand(const Suite& suite) {
  std::vector<Job> all;
  for (const auto& block : suite.blocks) expand_block(block, all);
  for (const auto& block : suite.merges) expand_merge_block(block, all);
  for (const auto& block : suite.animations) expand_animate_block(block, all);
  for (const auto& block : suite.occlusions) expand_occlude_block(block, all);
  for (const auto& block : suite.doom) expand_doom_block(block, all);
  // Smallest nominal size first, so a scene built at several sizes runs once, at the smallest.
  std::stable_sort(all.begin(), all.end(), [](const Job& a, const Job& b) { return a.n < b.n; });
  std::vector<Job> jobs;
  std::set<std::string> seen;
  for (auto& j : all)
    if (seen.insert(run_identity(j)).second) jobs.push_back(std::move(j));
  std::sort(jobs.begin(), jobs.end(), [](const Job& a, const Job& b) {
    return a.n != b.n ? a.n > b.n : a.key < b.key;
  });
  return jobs;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  Shard s;
  const auto parse = [&](std::string_view part, std::uint32_t& v) {
    auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
    return ec == std::errc() && ptr == part.data() + part.size() && !part.empty();
  };
  const std::string_view all(text);
  if (slash == std::string::npos || !parse(all.substr(0, slash), s.index) || !parse(all.substr(slash + 1), s.count) ||
      s.count == 0 || s.index >= s.count)
    throw UsageError("--shard wants i/N with 0 <= i < N, not '" + text + "'");
  return s;
}

std::vector<Job> shard_jobs(const std::vector<Job>& jobs, Shard s) {
  std::vector<Job> out;
  for (std::size_t i = s.index; i < jobs.size(); i += s.count) out.push_back(jobs[i]);
  return out;
}

std::string definition_hash(const std::string& suite_name, const std::vector<Job>& jobs, std::string_view source_text) {
  Hasher h;
  h.add_string(suite_name);
  h.add_u64(jobs.size());
  for (const auto& j : jobs) h.add_string(j.key);
  if (!source_text.empty()) h.add_string(source_text);
  return h.hex();
}

std::string file_hash(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) throw InputError(path + ": cannot open the file");
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  Hasher h;
  h.add_string(bytes);
  return h.hex();
}

Scene job_scene(const Job& job) {
  if (!job.file) {
    Scene scene = make_scene(job.scene, job.scene_params);
    check_scene(scene, "scene " + scene.name);
    return scene;
  }
  Scene scene = read_mesh(job.file->path);
  scene.name = job.scene;
  check_scene(scene, job.file->path);
  return scene;
}

namespace {

nlohmann::json merge_identity(const Job& job) {
  nlohmann::json operands = nlohmann::json::array();
  for (const auto& o : merge_operands(job)) operands.push_back({{"scene", o.scene}, {"params", operand_params(o).to_json()}});
  return {{"kind", "merge"},
          {"scene", job.scene},
          {"scene_params", pair_params_json(job)},
          {"operands", std::move(operands)},
          {"heuristic", job.heuristic},
          {"heuristic_params", heuristic_params(job).to_json()},
          {"operation", set_op_name(*job.op)},
          {"build", "recursive"},
          {"shape", shape_name(job.shape)},
          {"seed", job.seed},
          {"n", job.n},
          {"points", job.points},
          {"command", merge_command(job)}};
}

}  // namespace

namespace {
nlohmann::json drawing_identity(const Job& job);
}  // namespace

nlohmann::json job_identity(const Job& job) {
  if (job.op) return merge_identity(job);
  if (job.doom) return doom_identity(job);
  if (job.animate) {
    const AnimateParams& a = *job.animate;
    nlohmann::json id = drawing_identity(job);
    id["kind"] = "animate";
    id["strategy"] = a.strategy;
    id["object_heuristic"] = object_heuristic(job);
    id["moving"] = a.moving;
    id["frames"] = a.frames;
    id["object"] = a.object;
    id["object_n"] = a.object_n;
    id["size"] = a.size;
    id["speed"] = a.speed;
    id["spin"] = a.spin;
    id["check_every"] = a.check_every;
    id["drift_every"] = a.drift_every;
    id["command"] = animate_command(job);
    return id;
  }
  if (job.occlude) {
    nlohmann::json id = drawing_identity(job);
    id["kind"] = "occlude";
    id["command"] = occlude_command(job);
    return id;
  }
  return drawing_identity(job);
}

namespace {

// `text` as one word of a POSIX shell command.
std::string shell_word(const std::string& text) {
  const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '/' || c == '.' || c == '_' || c == '-' || c == ':' || c == '+' || c == ',' || c == '=';
  });
  if (plain) return text;
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string scene_arguments(const Job& job) {
  if (job.file && is_file_scene(job.scene)) return " --input " + shell_word(job.file->path);
  std::string out = " --scene " + shell_word(job.scene);
  if (job.n > 0) out += " --n " + std::to_string(job.n);
  for (const auto& [k, v] : job.scene_params)
    if (k != "n" && k != "seed") out += " --scene-param " + shell_word(k + "=" + v);
  return out;
}

nlohmann::json drawing_identity(const Job& job) {
  const std::string command = "bspbench build" + scene_arguments(job) + " --seed " + std::to_string(job.seed) +
                              build_arguments(job) + " --shape " + shape_name(job.shape);
  nlohmann::json id{{"kind", "draw"},
          {"scene", job.scene},
          {"scene_params", scene_params(job).to_json()},
          {"constant_density", !job.file && find_generator(job.scene).constant_density},
          {"heuristic", job.heuristic},
          {"heuristic_params", heuristic_params(job).to_json()},
          {"build", job.incremental ? "incremental" : "recursive"},
          {"shape", shape_name(job.shape)},
          {"seed", job.seed},
          {"n", job.n},
          {"validation_views", job.validation_views},
          {"command", command}};
  if (job.file) id["scene_file_hash"] = job.file->hash;
  return id;
}

}  // namespace

}  // namespace bsp::sweep
