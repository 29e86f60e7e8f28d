// The wrapper main runs every command in (cli/guard.h): whatever a command throws ends as one line
// "bspbench COMMAND: ..." and an exit code, never std::terminate.
#include <gtest/gtest.h>

#include <new>
#include <sstream>
#include <stdexcept>

#include "cli/guard.h"
#include "common/errors.h"

using namespace bsp;
using namespace bsp::cli;

namespace {

struct Outcome {
  int code;
  std::string err;
};

template <class Body>
Outcome guarded(Body body) {
  std::ostringstream err;
  const int code = run_guarded("build", "--scene NAME", body, err);
  return {code, err.str()};
}

}  // namespace

TEST(Guard, ReturnsTheCommandsExitCodeAndPrintsNothing) {
  const Outcome o = guarded([] { return 1; });
  EXPECT_EQ(o.code, 1);
  EXPECT_TRUE(o.err.empty());
}

TEST(Guard, UsageAndInputErrorsExitTwo) {
  const Outcome usage = guarded([]() -> int { throw UsageError("missing option --scene"); });
  EXPECT_EQ(usage.code, kExitUsage);
  EXPECT_EQ(usage.err, "bspbench build: missing option --scene\nusage: bspbench build --scene NAME\n");
  const Outcome input = guarded([]() -> int { throw InputError("a.obj: malformed"); });
  EXPECT_EQ(input.code, kExitUsage);
  EXPECT_EQ(input.err, "bspbench build: a.obj: malformed\n");
}

TEST(Guard, EveryOtherExceptionIsOneLineAndExitThree) {
  const Outcome runtime = guarded([]() -> int { throw std::runtime_error("Embree: out of range"); });
  EXPECT_EQ(runtime.code, kExitInternal);
  EXPECT_EQ(runtime.err, "bspbench build: internal error: Embree: out of range\n");
  const Outcome memory = guarded([]() -> int { throw std::bad_alloc(); });
  EXPECT_EQ(memory.code, kExitInternal);
  EXPECT_EQ(memory.err, "bspbench build: internal error: out of memory\n");
  const Outcome unknown = guarded([]() -> int { throw 42; });
  EXPECT_EQ(unknown.code, kExitInternal);
  EXPECT_EQ(unknown.err, "bspbench build: internal error: an exception of unknown type\n");
}
