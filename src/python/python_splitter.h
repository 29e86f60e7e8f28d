#pragma once
// A splitter written in Python, for prototyping at small n: a callable given a Node (the node's
// fragments, their planes and points, side counts) that returns a fragment id of the node, a free
// plane (nx, ny, nz, d) or None (the build loop's fallback). It is called with the GIL held, from
// the one thread the build runs on (module.cpp, build_with). An exception it raises, or an answer
// that is none of these, ends the build and is raised from build_with.
#include <optional>

#include <pybind11/pybind11.h>

#include "split/splitter.h"

namespace bsp::python {

class PythonSplitter final : public Splitter {
 public:
  explicit PythonSplitter(pybind11::function choose) : choose_(std::move(choose)) {}
  ~PythonSplitter() override;
  SplitChoice choose(const SplitContext& ctx) override;
  // The build runs on one thread and never hands a subtree off, but clone() must still work.
  std::unique_ptr<Splitter> clone() const override;
  void check() const override;

 private:
  pybind11::function choose_;
  std::optional<pybind11::error_already_set> error_;
};

// Registers the Node class the callable receives.
void register_node(pybind11::module_& m);

}  // namespace bsp::python
