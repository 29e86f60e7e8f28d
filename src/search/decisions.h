#pragma once
// Decisions: the planes chosen for some nodes of a tree, keyed by the nodes' paths
// (SplitContext::node_key), and a splitter that builds with them. A node with a decision takes its
// plane; any other asks the base heuristic, or, with none, is an error (a replay that must be
// complete). This is how the searching builders (tree_search.h) and the optimal solver (optimal.h)
// turn a choice made for a node into an ordinary tree: build_tree with a DecisionSplitter.
//
// A build can also record, for the nodes down to a depth, what the base chose and a few
// alternatives: the searches' branching. The record is keyed by path, so it comes out the same on
// any thread.
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "geometry/plane.h"
#include "split/splitter.h"

namespace bsp {

// A node's plane: a fragment's own plane (the node takes a fragment lying on it) or a free plane.
struct Decision {
  Plane plane;
  bool free = false;
  bool operator==(const Decision&) const = default;
};

using Decisions = std::unordered_map<std::uint64_t, Decision>;

// What one recorded node offers a search: the base's choice first, then the alternatives.
struct RecordedNode {
  std::uint32_t depth = 0;
  std::vector<Decision> options;
};

struct RecordSettings {
  std::uint32_t depth = 0;  // nodes of this depth or less are recorded (the root has depth 1)
  std::uint32_t width = 1;  // options per node, the base's choice included
  std::uint32_t pool = 64;  // fragments' planes, drawn per node, that alternatives are ranked from
};

// Filled by a build (from any thread): nodes by path key. std::map so that walking it is ordered.
class Recorder {
 public:
  explicit Recorder(RecordSettings s) : settings_(s) {}
  const RecordSettings& settings() const { return settings_; }
  void add(std::uint64_t key, RecordedNode node);
  // Read after the build: no more writers.
  const std::map<std::uint64_t, RecordedNode>& nodes() const { return nodes_; }

 private:
  RecordSettings settings_;
  std::mutex mutex_;
  std::map<std::uint64_t, RecordedNode> nodes_;
};

class DecisionSplitter final : public Splitter {
 public:
  // `base` null: every node must have a decision. `recorder` may be null.
  DecisionSplitter(std::shared_ptr<const Decisions> decisions, std::unique_ptr<Splitter> base,
                   std::shared_ptr<Recorder> recorder = nullptr);
  SplitChoice choose(const SplitContext& ctx) override;
  std::unique_ptr<Splitter> clone() const override;
  bool needs_cell() const override { return base_ && base_->needs_cell(); }
  void check() const override {
    if (base_) base_->check();
  }

 private:
  void record(const SplitContext& ctx, const SplitChoice& chosen);

  std::shared_ptr<const Decisions> decisions_;
  std::unique_ptr<Splitter> base_;
  std::shared_ptr<Recorder> recorder_;
};

}  // namespace bsp
