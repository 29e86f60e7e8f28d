#include "search/decisions.h"

#include <algorithm>
#include <stdexcept>
#include <tuple>

#include "common/rng.h"
#include "split/candidates.h"

namespace bsp {

namespace {

constexpr std::uint64_t kRecordStream = 0x5ea7c4;

Decision decision_of(const SplitContext& ctx, const SplitChoice& c) {
  if (c.kind == SplitChoice::Kind::Free) return {c.plane, true};
  return {ctx.planes[ctx.frags.plane(c.fragment)], false};
}

// Alternatives to the base's choice, best first: fewest splits, then the smallest imbalance; a
// plane with nothing on one side and nothing split divides nothing and comes last.
std::vector<Decision> ranked_alternatives(const SplitContext& ctx, const RecordSettings& s) {
  CandidateScratch scratch;
  Rng rng(stream_seed(kRecordStream, ctx.node_key));
  const auto candidates = candidate_fragments(ctx, s.pool, rng, scratch);
  const std::vector<std::uint32_t> ids(candidates.begin(), candidates.end());
  const SideCounter count(ctx, 0, rng, scratch);
  const auto counts = count(ids);
  std::vector<std::tuple<bool, std::uint32_t, std::uint32_t, std::size_t>> order;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const SideCounts& c = counts[i];
    const bool divides_nothing = c.spanning == 0 && (c.front == 0 || c.back == 0);
    const std::uint32_t imbalance = c.front > c.back ? c.front - c.back : c.back - c.front;
    order.emplace_back(divides_nothing, c.spanning, imbalance, i);
  }
  std::sort(order.begin(), order.end());
  std::vector<Decision> out;
  for (const auto& o : order) out.push_back({ctx.planes[ctx.frags.plane(ids[std::get<3>(o)])], false});
  return out;
}

}  // namespace

void Recorder::add(std::uint64_t key, RecordedNode node) {
  const std::lock_guard lock(mutex_);
  nodes_[key] = std::move(node);
}

DecisionSplitter::DecisionSplitter(std::shared_ptr<const Decisions> decisions, std::unique_ptr<Splitter> base,
                                   std::shared_ptr<Recorder> recorder)
    : decisions_(std::move(decisions)), base_(std::move(base)), recorder_(std::move(recorder)) {}

SplitChoice DecisionSplitter::choose(const SplitContext& ctx) {
  if (const auto it = decisions_->find(ctx.node_key); it != decisions_->end()) {
    const Decision& d = it->second;
    if (d.free) return SplitChoice::free_plane(d.plane);
    for (auto id : ctx.ids)
      if (ctx.planes[ctx.frags.plane(id)] == d.plane) return SplitChoice::of_fragment(id);
    throw std::logic_error("decisions: a node's decided plane is no fragment's of the node");
  }
  if (!base_) throw std::logic_error("decisions: the replay reached a node with no decision");
  const SplitChoice chosen = base_->choose(ctx);
  if (recorder_ && ctx.depth <= recorder_->settings().depth && chosen.kind != SplitChoice::Kind::None)
    record(ctx, chosen);
  return chosen;
}

void DecisionSplitter::record(const SplitContext& ctx, const SplitChoice& chosen) {
  const RecordSettings& s = recorder_->settings();
  RecordedNode node{ctx.depth, {decision_of(ctx, chosen)}};
  if (s.width > 1)
    for (const Decision& d : ranked_alternatives(ctx, s)) {
      if (node.options.size() >= s.width) break;
      if (std::find(node.options.begin(), node.options.end(), d) == node.options.end()) node.options.push_back(d);
    }
  recorder_->add(ctx.node_key, std::move(node));
}

std::unique_ptr<Splitter> DecisionSplitter::clone() const {
  return std::make_unique<DecisionSplitter>(decisions_, base_ ? base_->clone() : nullptr, recorder_);
}

}  // namespace bsp
