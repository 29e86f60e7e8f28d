#pragma once
// The leaf test and the partition rule of leafy trees (tree.h, Shape::Leafy): when a set of
// fragments bounds one convex cell, and which plane parts a set that does not.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "geometry/plane.h"
#include "split/fragment_store.h"

namespace bsp {

// The directions of the lines through segment endpoints that group_separators tries: the axes,
// the diagonals and the slopes ±1/2 and ±2, small integer vectors, both orientations.
inline constexpr std::pair<double, double> kSeparatorDirections[] = {{1, 0}, {0, 1},  {1, 1},  {1, -1},
                                                                     {2, 1}, {1, 2},  {2, -1}, {1, -2},
                                                                     {-1, 0}, {0, -1}, {-1, -1}, {-1, 1}};

// Whether fragment b is in front of a's plane (or on it facing the same way) as a leaf requires.
// Opposite-facing fragments in one plane bound two cells, never one.
bool faces_into_cell(const FragmentStore& frags, const PlanePool& planes, std::uint32_t a, std::uint32_t b, double eps);

// A fragment of `ids` whose plane has another fragment behind it or in it facing the other way:
// its plane parts the set (each side gets a fragment or a piece of one). nullopt when every pair
// faces into one cell. O(m²) plane tests in the worst case, with an early exit.
std::optional<std::uint32_t> convexity_witness(std::span<const std::uint32_t> ids, const FragmentStore& frags,
                                               const PlanePool& planes, double eps);

// Whether all fragments come from sources of one group (`groups` by source; empty means one group).
bool one_group(std::span<const std::uint32_t> ids, const FragmentStore& frags, std::span<const std::uint32_t> groups);

// Planes that may part two fragments of different groups, best first, for the first such pair (in
// ids order) whose vertex averages lie more than eps apart: the perpendicular bisector of the
// averages; then, for segments, the lines through each of their endpoints in the directions of
// kSeparatorDirections, which part two pieces meeting at a corner and, through integer endpoints,
// are lines a format with integer partitions stores exactly (where the bisector, snapped to the
// grid, can miss pieces shorter than a grid unit). Empty when every such pair is in one place
// (coincident fragments of two groups, which no plane parts).
std::vector<Plane> group_separators(std::span<const std::uint32_t> ids, const FragmentStore& frags,
                                    std::span<const std::uint32_t> groups, double eps);

// Whether splitting `ids` by `plane` by the leafy rule (coplanar fragments to the side they face)
// leaves fragments on both sides.
bool parts_leafy(std::span<const std::uint32_t> ids, const FragmentStore& frags, const PlanePool& planes,
                 const Plane& plane, double eps);

}  // namespace bsp
