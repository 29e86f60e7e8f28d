#pragma once
// The experiment kinds, registered once (kinds.cpp): the suite parser reads their blocks, the gate
// finds their gated timings, and the results find their timing fields through this list and
// nothing else. Adding a kind is its folder under src/experiments/ and one line in kinds.cpp.
#include <span>
#include <string_view>

#include "experiments/kind.h"

namespace bsp {

// In the order suite files list their blocks and reports their sections.
std::span<const experiments::Kind* const> kinds();
// The kind of that name (a record's id.kind); nullptr when there is none.
const experiments::Kind* find_kind(std::string_view name);

}  // namespace bsp
