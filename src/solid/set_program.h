#pragma once
// A program of set operations on closed solids in postfix order: what a CSG program (OpenSCAD's
// CSG format, csg/lower.h) becomes once its transforms and 2D parts are applied, and what every
// engine evaluates alike, bspbench's merges (csg/evaluate.h) and CGAL's corefinement step by step
// (validate/exact_measure.h: exact_corefine_program), so they take the same polyhedra in the same order.
#include <cstdint>

namespace bsp {

enum class StepKind : std::uint8_t { Leaf, Empty, Union, Intersection, Difference, Hull };

// Leaf pushes leaf number `count`; Empty pushes the empty solid; the others pop `count` operands
// (the first pushed is the first operand) and push their result: union and intersection of them
// all, the first minus the others, or the convex hull of them all. An operation on no operands
// gives the empty solid. The operands are combined two at a time, left to right.
struct Step {
  StepKind kind = StepKind::Empty;
  std::uint32_t count = 0;
  std::uint32_t node = 0;  // where the step comes from (a node of the CSG program), for records
};

}  // namespace bsp
