#pragma once
// A heuristic written outside this repository, as a shared library ("plugin") that bspbench loads
// at run time (`--plugin PATH.so` on any command, "plugins" in a suite file) and registers beside
// the built-ins: examples/my_heuristic/ is one to copy. A plugin defines one function returning a
// PluginInfo and names it with BSPBENCH_PLUGIN; it is built against the installed package
// (find_package(bspbench CONFIG), target bspbench::bsp).
//
// Compatibility (checked by the loader, experiments/plugin_loader.h, before it reads anything
// else): the heuristics cross into bspbench as C++ objects (std::string, std::function, the
// Splitter vtable), so a plugin loads only into a bspbench of the major.minor version it was built
// against (common/version.h), built by the same compiler (family and major version) with the same
// standard-library ABI. kPluginAbi is that rule as text, compiled into both sides.
//
// Errors: an exception thrown by the plugin's code ends the command with exit code 3 and one line
// naming the plugin, writing nothing. A crash in the plugin (a bad pointer) takes the process down
// with it: plugins run in bspbench's process, unisolated.
#include <string>
#include <vector>

#include "common/version.h"
#include "split/registry.h"

namespace bsp {

struct PluginInfo {
  std::string name;     // the plugin's, in messages and job identities
  std::string version;  // the plugin's own (semantic) version: it joins the keys of jobs using it
  std::vector<HeuristicInfo> heuristics;  // registered under their names, which must be new
};

#define BSPBENCH_PLUGIN_TEXT_(x) #x
#define BSPBENCH_PLUGIN_TEXT(x) BSPBENCH_PLUGIN_TEXT_(x)
#if defined(__clang__)
#define BSPBENCH_PLUGIN_COMPILER "clang " BSPBENCH_PLUGIN_TEXT(__clang_major__)
#elif defined(__GNUC__)
#define BSPBENCH_PLUGIN_COMPILER "gcc " BSPBENCH_PLUGIN_TEXT(__GNUC__)
#else
#define BSPBENCH_PLUGIN_COMPILER "unknown compiler"
#endif

// Interface revision 1 of the entry points below.
inline constexpr char kPluginAbi[] = "bspbench plugin 1, bspbench " BSPBENCH_VERSION_COMPATIBLE
                                     ", " BSPBENCH_PLUGIN_COMPILER
                                     ", libstdc++ cxx11 abi " BSPBENCH_PLUGIN_TEXT(_GLIBCXX_USE_CXX11_ABI);

}  // namespace bsp

// Defines the plugin's two entry points, C symbols the loader finds by name: the ABI tag, read
// first, and `describe` (a function returning bsp::PluginInfo), called once when compatible.
#define BSPBENCH_PLUGIN(describe)                                                                  \
  extern "C" __attribute__((visibility("default"))) const char* bspbench_plugin_abi() {            \
    return ::bsp::kPluginAbi;                                                                      \
  }                                                                                                \
  extern "C" __attribute__((visibility("default"))) void bspbench_plugin_describe(::bsp::PluginInfo& out) { \
    out = describe();                                                                              \
  }
