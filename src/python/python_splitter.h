#pragma once
// A splitter written in Python, for prototyping at small n: a callable given a Node (the node's
// fragments, their planes and points, side counts) that returns a fragment id of the node, a free
// plane (nx, ny, nz, d) or None (the build loop's fallback). It is called with the GIL held, from
// the one thread the build runs on (module.cpp, build_with). An exception it raises, or an answer
// that is none of these, is recorded: the build finishes without calling it again, and build_with
// raises it.
#include <memory>
#include <optional>

#include <pybind11/pybind11.h>

#include "split/splitter.h"

namespace bsp::python {

class PythonSplitter final : public Splitter {
 public:
  explicit PythonSplitter(pybind11::function choose);
  ~PythonSplitter() override;
  SplitChoice choose(const SplitContext& ctx) override;
  // build_with hands no subtree off, but a clone shares the callable and the recorded error.
  std::unique_ptr<Splitter> clone() const override;
  void check() const override;

 private:
  using Error = std::optional<pybind11::error_already_set>;
  PythonSplitter(pybind11::function choose, std::shared_ptr<Error> error)
      : choose_(std::move(choose)), error_(std::move(error)) {}

  pybind11::function choose_;
  std::shared_ptr<Error> error_;  // the first error, shared with the clones
};

// Registers the Node class the callable receives.
void register_node(pybind11::module_& m);

}  // namespace bsp::python
