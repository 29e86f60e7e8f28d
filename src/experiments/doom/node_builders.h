#pragma once
// External Doom node builders, the reference our trees are compared with on real maps: each run
// builds the nodes of one single-map PWAD in a process of its own, timed by the child's CPU time
// (user + system, from wait4), which the machine's other load barely changes, and by wall time.
//  - "zdbsp": ZDBSP with its defaults (`zdbsp -o OUT IN`). ZDBSP 1.19 writes vanilla
//    NODES/SEGS/SSECTORS for all 68 Freedoom maps; by its documentation it switches to ZDoom's
//    extended nodes only for a map the vanilla format cannot hold, and no option forces vanilla
//    (-X, -z and -Z only force extended or compressed nodes).
//  - "glbsp": glBSP `-n` (`glbsp -n IN -o OUT`). Without -n glBSP keeps the normal nodes a map
//    already has and only adds GL nodes; -n rebuilds the normal (vanilla) nodes too. glBSP has no
//    option to skip the GL nodes: both come from one tree, so its time includes writing them.
// Both also rebuild the BLOCKMAP, and glBSP replaces REJECT with an empty table; which changes the
// game (tests/doom/play_demos.py), not the tree.
#include <string>
#include <vector>

namespace bsp::experiments {

struct BuilderRun {
  std::string builder, output_path;
  double cpu_seconds = 0;    // the child's user + system time
  double wall_seconds = 0;
  int exit_code = -1;        // -1 when it did not exit by itself: not started, killed by a signal or the timeout
  bool timed_out = false;
  std::string log;           // stdout and stderr as the builder wrote them, kept for error messages
  bool ok() const { return exit_code == 0 && !timed_out; }
  // "" when ok(), else one line: how it failed and the log's last line.
  std::string failure() const;
};

struct BuilderInstall {
  std::string path;     // empty when the builder is not on PATH
  std::string version;  // its banner, e.g. "ZDBSP 1.19 (GCC-amd64 : Aug  8 2019)"; empty when not installed
};

std::vector<std::string> known_builders();
// Throws UsageError naming the known builders when `name` is none of them. Known, not necessarily
// installed: a builder missing at run time is a run with an error.
void check_builder_name(const std::string& name);

// UsageError listing the known builders for any other name.
BuilderInstall find_builder(const std::string& builder);

// Builds the nodes of `in_pwad` into `out_pwad`, killing the builder after `timeout_s` seconds.
// A builder that fails, crashes, times out or is not installed gives a BuilderRun that says so;
// an unknown builder is a UsageError and an unreadable `in_pwad` an InputError.
BuilderRun run_node_builder(const std::string& builder, const std::string& in_pwad, const std::string& out_pwad,
                            double timeout_s);

}  // namespace bsp::experiments
