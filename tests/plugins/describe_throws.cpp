// A plugin whose describe function throws: exit code 3, one line naming the plugin.
#include <stdexcept>

#include "split/plugin.h"

namespace {
bsp::PluginInfo describe() { throw std::runtime_error("describe failed on purpose"); }
}  // namespace

BSPBENCH_PLUGIN(describe)
