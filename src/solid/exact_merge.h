#pragma once
// Set operations on exact solid trees (exact_solid_tree.h) by merging [Naylor1990; Chrysanthou §4],
// merge.h's algorithm with every classification decided exactly and every cut a new bound of a
// plane polygon, so the parts of a sub-hyperplane share their new vertices exactly.
//
// Notation as merge.h. Exactly, the two classifications partitionTree makes agree, so merge.h's
// `inconsistent` resolution and its trimming of shp(T) have no counterpart: with r(T) inside
// r(t1), h(t1) ∩ r(T) is shp(t1) ∩ r(T). If shp(t1) ∩ r(T) lies on one side of h(T), shp(T)
// cannot cross h(t1): a crossing point X would lie on h(t1) inside r(T), hence in the relative
// interior of shp(t1) ∩ r(T) and on h(T), and a convex polygon touching a plane at a relative
// interior point while on one side of it lies in it: coplanar, the case decided first by pooled
// index. If shp(t1) ∩ r(T) spans h(T), the line h(t1) ∩ h(T) passes through the interior of r(T),
// so shp(T) spans h(t1). (Interior: h(t1) is no face plane of r(T), since a node's plane is no
// ancestor's and a B node on h(t1) was removed where it met t1.) A disagreement is therefore a
// broken invariant, and throws std::logic_error; MergeStats::inconsistent stays 0.
#include "solid/exact_solid_tree.h"
#include "solid/merge.h"

namespace bsp {

// A op B, both of `space`. The result is reduced (every subtree of one label collapsed) and of the
// same space; the sub-hyperplanes it does not use that the merge made are released.
// Pruning by bounds as merge.h's, with the fragments' certified boxes (exact_predicates.h): a
// subtree is passed whole only when the filter proves its box strictly on one side.
ExactSolidTree merge(const ExactSolidTree& a, const ExactSolidTree& b, ExactSolidSpace& space, SetOp op,
                     MergeStats* stats = nullptr, MergeOptions options = {});
ExactSolidTree merge_with_table(const ExactSolidTree& a, const ExactSolidTree& b, ExactSolidSpace& space,
                                const CellTable& table, MergeStats* stats = nullptr, MergeOptions options = {});

// Releases the sub-hyperplanes of a merge's result that neither operand holds: for a result that is
// no longer needed (timing repeats a merge in one space). The result must not be used afterwards.
void discard(const ExactSolidTree& result, const ExactSolidTree& a, const ExactSolidTree& b, ExactSolidSpace& space);

// Collapses every subtree whose leaves all carry one label into that leaf and stores the nodes that
// remain in pre-order (a subtree two parents share is stored once per parent). Exactly, no node's
// plane misses its region, so that step of reduce() in merge.h has nothing to do.
ExactSolidTree reduce(const ExactSolidTree& solid);

}  // namespace bsp
