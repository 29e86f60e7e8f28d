#pragma once
// Loads plugins (split/plugin.h) and registers their heuristics, at the edges: the CLI's --plugin
// and a suite file's "plugins", before any job is made. A loaded heuristic is then a name like any
// built-in's; its jobs' keys and repeat commands carry the plugin (heuristic_choice.h).
#include <string>
#include <vector>

#include "split/registry.h"

namespace bsp::experiments {

// Loads the plugin at `path` (made absolute) and registers its heuristics; loading the same file
// again does nothing. Throws InputError, naming the file, for a file that cannot be opened as a
// shared library, has no entry points, was built for another bspbench version or compiler (split/
// plugin.h), describes no heuristic or a nameless one, or names one already registered (a
// built-in's, a search's, another plugin's); PluginError when the plugin's code throws.
const PluginIdentity& load_plugin(const std::string& path);
// The plugins loaded so far, in order: what a report's environment lists.
std::vector<PluginIdentity> loaded_plugins();

}  // namespace bsp::experiments
