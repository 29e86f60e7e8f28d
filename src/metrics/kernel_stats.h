#pragma once
// What an exact-kernel build did (tree/exact_build.h), as the JSON object every command and
// record reports under "exact": how snapping moved the input and how each side test was decided.
#include <nlohmann/json_fwd.hpp>

#include "tree/exact_build.h"

namespace bsp {

nlohmann::json to_json(const ExactBuildStats& s);

}  // namespace bsp
