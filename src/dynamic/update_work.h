#pragma once
// What one update of a dynamic scene's tree did, counted where it happens, so strategies that do
// less than a full build show where their time goes.
#include <cstdint>

namespace bsp {

struct UpdateWork {
  double seconds = 0;                     // thread CPU seconds of the update
  std::uint64_t polygons_built = 0;       // fragments given to the splitter (all of them for rebuild)
  std::uint64_t nodes_built = 0;          // nodes made: by those builds, hung object parts, separators
  std::uint64_t fragments_removed = 0;    // moving fragments taken out of nodes
  std::uint64_t nodes_removed = 0;        // nodes freed because no fragment or object defined them
  // Chrysanthou and Slater's hard case: a removed node with two non-empty subtrees. The smaller
  // subtree is dismantled and its fragments reinserted into the larger, which takes the node's place.
  std::uint64_t repairs = 0;
  std::uint64_t reinserted_fragments = 0;
  std::uint64_t dismantled_nodes = 0;
  std::uint64_t fragments_inserted = 0;   // fragments filtered down from a node (inserts and repairs)
  std::uint64_t partitioned_nodes = 0;    // object-tree nodes visited partitioning by a host plane
  std::uint64_t moved_nodes = 0;          // nodes moved rigidly in place, nothing rebuilt
  std::uint64_t objects_placed = 0;       // objects (re)placed into the tree this update
  std::uint64_t objects_whole = 0;        // of those, placed whole in one cell (torres can move them in place)
};

}  // namespace bsp
