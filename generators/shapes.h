#pragma once
// Building blocks shared by the generators: polygons from corners with texture coordinates, and the
// parallel item loop that keeps every generator deterministic on any thread count.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "common/params.h"
#include "geometry/polygon.h"

namespace bsp {

// Texture coordinates span the unit square (quads) or its lower-left half (triangles). The front
// is the side from which the corners run counter-clockwise.
Polygon triangle(const Vec3& a, const Vec3& b, const Vec3& c);
Polygon quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
// The parallelogram origin, origin + u, origin + u + v, origin + v; its front faces cross(u, v).
Polygon parallelogram(const Vec3& origin, const Vec3& u, const Vec3& v);
// The same polygon facing the other way (vertex order reversed, the plane unchanged).
Polygon flipped(Polygon poly);

// Runs make(i, out) for every item i < items (in parallel; each call appends item i's polygons to
// its own `out`) and concatenates the results in item order, numbering `source` 0, 1, 2, ... So the
// output depends only on what each item makes, never on the thread that made it; each item must
// draw its randomness from its own stream (rng.h stream_seed).
std::vector<Polygon> generate_items(std::size_t items,
                                    const std::function<void(std::size_t, std::vector<Polygon>&)>& make);

std::uint64_t seed_of(const ParamSet& p);
std::size_t count_of(const ParamSet& p);  // the "n" parameter

}  // namespace bsp
