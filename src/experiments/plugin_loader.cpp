#include "experiments/plugin_loader.h"

#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <filesystem>
#include <mutex>

#include "common/errors.h"
#include "experiments/scene_run.h"
#include "search/tree_search.h"
#include "split/plugin.h"

namespace bsp::experiments {

namespace {

using AbiFunction = const char* (*)();
using DescribeFunction = void (*)(PluginInfo&);

// The first error a plugin's splitter met in one build, shared by the splitter and its clones
// (which other threads use). Once set, the clones stop calling the plugin.
class Fault {
 public:
  explicit Fault(std::string who) : who_(std::move(who)) {}
  bool failed() const { return failed_.load(std::memory_order_acquire); }
  void record(const std::string& what) {
    std::lock_guard lock(mutex_);
    if (failed()) return;
    message_ = who_ + ": " + what;
    failed_.store(true, std::memory_order_release);
  }
  void check() const {
    if (failed()) throw PluginError(message_);
  }

 private:
  std::string who_;
  std::mutex mutex_;
  std::atomic<bool> failed_{false};
  std::string message_;
};

// What an exception in flight says, for messages.
std::string what_of(std::exception_ptr e) {
  try {
    std::rethrow_exception(e);
  } catch (const std::exception& x) {
    return x.what();
  } catch (...) {
    return "an exception of unknown type";
  }
}

// A plugin's splitter as the build loops see it: exceptions and invalid choices become a recorded
// fault (Splitter::check) instead of leaving a parallel region, and a fault stops further calls.
class PluginSplitter final : public Splitter {
 public:
  // `autopartition`: as the heuristic declared it (HeuristicInfo), which a free plane then breaks.
  PluginSplitter(std::unique_ptr<Splitter> inner, std::shared_ptr<Fault> fault, bool autopartition)
      : inner_(std::move(inner)), fault_(std::move(fault)), needs_cell_(inner_ && inner_->needs_cell()),
        autopartition_(autopartition) {}

  SplitChoice choose(const SplitContext& ctx) override {
    if (!inner_ || fault_->failed()) return SplitChoice::none();
    try {
      const SplitChoice c = inner_->choose(ctx);
      if (const std::string bad = invalid(c, ctx); !bad.empty()) fault_->record(bad);
      else return c;
    } catch (...) {
      fault_->record("choose() threw: " + what_of(std::current_exception()));
    }
    return SplitChoice::none();
  }

  std::unique_ptr<Splitter> clone() const override {
    std::unique_ptr<Splitter> copy;
    if (inner_ && !fault_->failed()) try {
        copy = inner_->clone();
        if (!copy) fault_->record("clone() returned no splitter");
      } catch (...) {
        fault_->record("clone() threw: " + what_of(std::current_exception()));
      }
    return std::make_unique<PluginSplitter>(std::move(copy), fault_, autopartition_);
  }

  bool needs_cell() const override { return needs_cell_; }
  void check() const override { fault_->check(); }

 private:
  // Why the build loop cannot take `c`, or empty: a fragment not in the node, a plane that is none,
  // a free plane from a heuristic declared an autopartition.
  std::string invalid(const SplitChoice& c, const SplitContext& ctx) const {
    if (c.kind == SplitChoice::Kind::Fragment &&
        std::find(ctx.ids.begin(), ctx.ids.end(), c.fragment) == ctx.ids.end())
      return "choose() picked fragment " + std::to_string(c.fragment) + ", which is not in the node";
    if (c.kind == SplitChoice::Kind::Free && autopartition_)
      return "choose() returned a free plane, but the heuristic is declared an autopartition";
    if (c.kind == SplitChoice::Kind::Free) {
      const Plane& p = c.plane;
      const bool finite = std::isfinite(p.n.x) && std::isfinite(p.n.y) && std::isfinite(p.n.z) && std::isfinite(p.d);
      if (!finite || length(p.n) == 0) return "choose() returned a free plane with a zero or non-finite normal";
    }
    return {};
  }

  std::unique_ptr<Splitter> inner_;
  std::shared_ptr<Fault> fault_;
  bool needs_cell_;
  bool autopartition_;
};

// `info` with its `make` guarded: a throw names the plugin, and the splitter is a PluginSplitter.
HeuristicInfo guarded(HeuristicInfo info, const std::string& plugin) {
  const std::string who = "plugin " + plugin + ", heuristic " + info.name;
  info.make = [make = std::move(info.make), who, autopartition = info.autopartition](const ParamSet& params,
                                                                                   std::uint64_t seed) {
    std::unique_ptr<Splitter> inner;
    try {
      inner = make(params, seed);
    } catch (...) {
      throw PluginError(who + ": make threw: " + what_of(std::current_exception()));
    }
    if (!inner) throw PluginError(who + ": make returned no splitter");
    return std::unique_ptr<Splitter>(
        std::make_unique<PluginSplitter>(std::move(inner), std::make_shared<Fault>(who), autopartition));
  };
  return info;
}

// A symbol of the library, or InputError naming what is missing.
void* entry(void* library, const char* symbol, const std::string& path) {
  void* f = dlsym(library, symbol);
  if (!f)
    throw InputError("plugin " + path + ": not a bspbench plugin (no symbol " + symbol +
                     "; a plugin defines its entry points with BSPBENCH_PLUGIN, split/plugin.h)");
  return f;
}

// Why `name` cannot name a heuristic in a suite label ("NAME:k=v,k=v"), or empty.
std::string bad_name(const std::string& name) {
  if (name.empty()) return "a heuristic without a name";
  if (name.find_first_of(":,= \t\n") != std::string::npos) return "heuristic name '" + name + "' has ':', ',', '=' or a space";
  if (find_search(name)) return "heuristic '" + name + "' has the name of a searching builder";
  return {};
}

std::deque<PluginIdentity>& loaded() {  // a deque: load_plugin returns references into it
  static std::deque<PluginIdentity> plugins;
  return plugins;
}

}  // namespace

const PluginIdentity& load_plugin(const std::string& given) {
  std::error_code ec;
  const std::string path = std::filesystem::absolute(given, ec).lexically_normal().string();
  for (const auto& p : loaded())
    if (p.path == path) return p;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError("plugin " + given + ": no such file");
  const std::string hash = file_hash(path);
  // RTLD_LOCAL: the plugin's symbols (and the copy of bspbench it links) stay its own. The library
  // is never closed: its heuristics' code lives in it for the rest of the process.
  void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!library) throw InputError("plugin " + path + ": cannot load: " + dlerror());
  const auto abi = reinterpret_cast<AbiFunction>(entry(library, "bspbench_plugin_abi", path));
  const auto describe = reinterpret_cast<DescribeFunction>(entry(library, "bspbench_plugin_describe", path));
  if (const std::string theirs = abi(); theirs != kPluginAbi)
    throw InputError("plugin " + path + ": built for \"" + theirs + "\", but this bspbench is \"" + kPluginAbi +
                     "\"; rebuild the plugin against this version");
  PluginInfo info;
  try {
    describe(info);
  } catch (...) {
    throw PluginError("plugin " + path + ": its describe function threw: " + what_of(std::current_exception()));
  }
  const std::string label = (info.name.empty() ? path : info.name) + " (" + path + ")";
  if (info.name.empty() || info.version.empty()) throw InputError("plugin " + path + ": no name or no version");
  if (info.heuristics.empty()) throw InputError("plugin " + label + ": describes no heuristic");
  for (std::size_t i = 0; i < info.heuristics.size(); ++i) {
    const HeuristicInfo& h = info.heuristics[i];
    for (std::size_t j = 0; j < i; ++j)
      if (info.heuristics[j].name == h.name) throw InputError("plugin " + label + ": heuristic '" + h.name + "' described twice");
    if (const std::string bad = bad_name(h.name); !bad.empty()) throw InputError("plugin " + label + ": " + bad);
    if (!h.make) throw InputError("plugin " + label + ": heuristic " + h.name + " has no make function");
    for (const auto& other : heuristics())
      if (other.name == h.name) {
        const PluginIdentity* from = heuristic_plugin(h.name);
        throw InputError("plugin " + label + ": heuristic '" + h.name + "' is already registered by " +
                         (from ? "plugin " + from->name + " (" + from->path + ")" : std::string("bspbench (a built-in)")));
      }
  }
  PluginIdentity identity{info.name, info.version, hash, path};
  for (HeuristicInfo& h : info.heuristics) register_heuristic(guarded(std::move(h), label), identity);
  return loaded().emplace_back(std::move(identity));
}

std::vector<PluginIdentity> loaded_plugins() { return {loaded().begin(), loaded().end()}; }

}  // namespace bsp::experiments
