#include "experiments/scene_run.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>

#include <nlohmann/json.hpp>

#include "catalog.h"
#include "common/errors.h"
#include "common/hash.h"
#include "io/mesh_reader.h"
#include "tree/build.h"

namespace bsp::experiments {

namespace {

const ParamSpec* find_spec(const GeneratorInfo& g, std::string_view name) {
  for (const auto& p : g.params)
    if (p.name == name) return &p;
  return nullptr;
}

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

}  // namespace

bool is_file_scene(std::string_view scene_name) { return scene_name.starts_with(kFileScenePrefix); }

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

SceneRun SceneRun::generated(const GeneratorInfo& g, ParamAssignments params, std::optional<HeuristicChoice> heuristic,
                             Shape shape, std::uint64_t seed, std::uint64_t n, std::uint32_t views) {
  SceneRun run{g.name, std::move(params), std::nullopt, std::move(heuristic), shape, seed, n, views};
  if (n > 0) run.scene_params.emplace_back("n", std::to_string(n));
  if (find_spec(g, "seed")) run.scene_params.emplace_back("seed", std::to_string(seed));
  return run;
}

std::string SceneRun::heuristic_label() const { return heuristic ? heuristic->label : std::string(kIncrementalLabel); }

ParamSet SceneRun::heuristic_params() const {
  return heuristic ? heuristic->resolved : ParamSet::resolve({}, {}, kIncrementalLabel);
}

ParamSet SceneRun::resolved_scene_params() const {
  if (file) return {};
  const GeneratorInfo& g = find_generator(scene);
  return ParamSet::resolve(g.params, scene_params, "scene " + g.name);
}

std::string SceneRun::hash(const std::string& scene_text) const {
  Hasher h;
  h.add_string(scene);
  h.add_string(scene_text);
  h.add_string(heuristic_label());
  h.add_string(heuristic_params().canonical());
  if (heuristic) add_plugin_identity(h, heuristic->name);
  h.add_string(shape_name(shape));
  h.add_u64(seed);
  h.add_u64(views);
  if (incremental()) h.add_string("incremental shuffled");
  return h.hex();
}

std::string SceneRun::key_scene_text() const {
  return file ? "file " + file->hash : resolved_scene_params().canonical();
}

const std::string& SceneRun::content_hash() const {
  static std::mutex mutex;
  static std::map<std::string, std::string> hashes;
  const std::string key = scene + " " + resolved_scene_params().canonical();
  const std::lock_guard lock(mutex);
  auto it = hashes.find(key);
  if (it == hashes.end()) it = hashes.emplace(key, bsp::content_hash(bsp::make_scene(scene, scene_params))).first;
  return it->second;
}

Scene SceneRun::make_scene() const {
  if (!file) {
    Scene s = bsp::make_scene(scene, scene_params);
    check_scene(s, "scene " + s.name);
    return s;
  }
  Scene s = read_mesh(file->path);
  s.name = scene;
  check_scene(s, file->path);
  return s;
}

std::string SceneRun::scene_arguments() const {
  if (file && is_file_scene(scene)) return " --input " + shell_word(file->path);
  std::string out = " --scene " + shell_word(scene);
  if (n > 0) out += " --n " + std::to_string(n);
  for (const auto& [k, v] : scene_params)
    if (k != "n" && k != "seed") out += " --scene-param " + shell_word(k + "=" + v);
  return out;
}

nlohmann::json SceneRun::identity(std::string_view kind) const {
  const std::string build =
      incremental() ? std::string(" --incremental --order shuffled") : heuristic->arguments();
  const std::string command = "bspbench build" + scene_arguments() + " --seed " + std::to_string(seed) + build +
                              " --shape " + shape_name(shape);
  nlohmann::json id{{"kind", std::string(kind)},
                    {"scene", scene},
                    {"scene_params", resolved_scene_params().to_json()},
                    {"constant_density", !file && find_generator(scene).constant_density},
                    {"heuristic", heuristic_label()},
                    {"heuristic_params", heuristic_params().to_json()},
                    {"build", incremental() ? "incremental" : "recursive"},
                    {"shape", shape_name(shape)},
                    {"seed", seed},
                    {"n", n},
                    {"validation_views", views},
                    {"command", command}};
  if (file) id["scene_file_hash"] = file->hash;
  return id;
}

}  // namespace bsp::experiments
