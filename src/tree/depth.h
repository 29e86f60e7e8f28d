#pragma once
// A tree's depth, for the searches' objective and the animation's frame records.
#include <cstdint>

#include "tree/tree.h"

namespace bsp {

// The depth of the deepest node (the root has depth 1; 0 for an empty tree), by an explicit stack:
// a tree can be a chain as deep as its input.
std::uint32_t max_depth(const Tree& tree);

}  // namespace bsp
