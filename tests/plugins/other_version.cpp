// A plugin as built against another bspbench version: its ABI tag names 0.0, which no bspbench of
// this version accepts. It defines the entry points by hand, as BSPBENCH_PLUGIN would with 0.0.
#include "split/plugin.h"

extern "C" __attribute__((visibility("default"))) const char* bspbench_plugin_abi() {
  return "bspbench plugin 1, bspbench 0.0, " BSPBENCH_PLUGIN_COMPILER ", libstdc++ cxx11 abi 1";
}
extern "C" __attribute__((visibility("default"))) void bspbench_plugin_describe(bsp::PluginInfo& out) {
  out = {"other_version", "0.0.1", {}};
}
