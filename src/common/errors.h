#pragma once
// The two kinds of failure a user can cause, UsageError and InputError: both end the CLI with exit
// code 2 and a one-line message. PluginError ends it with exit code 3; anything else escaping to
// main is a bug.
#include <stdexcept>
#include <string>

namespace bsp {

// A bad command line or parameter: unknown name, value out of range, missing option.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Bad input data: a missing, unreadable or malformed file, non-finite coordinates, an empty scene.
// The message names the file (or scene) and the problem.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An exception thrown by a plugin's code (split/plugin.h), caught where it left the plugin and
// rethrown naming the plugin. It stops a sweep instead of failing one job: the plugin is at fault,
// not the job, and its other jobs would fail alike.
struct PluginError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace bsp
