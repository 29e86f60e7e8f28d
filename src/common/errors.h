#pragma once
// The two kinds of failure a user can cause. Both end the CLI with exit code 2 and a one-line
// message; anything else escaping to main is a bug.
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

}  // namespace bsp
