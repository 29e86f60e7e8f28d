#include "tree/tree.h"

namespace bsp {

const char* shape_name(Shape s) {
  switch (s) {
    case Shape::Strict: return "strict";
    case Shape::Coarse: return "coarse";
    case Shape::Leafy: return "leafy";
  }
  return "strict";
}

std::optional<Shape> shape_named(std::string_view name) {
  for (Shape s : {Shape::Strict, Shape::Coarse, Shape::Leafy})
    if (name == shape_name(s)) return s;
  return std::nullopt;
}

TreeBytes Tree::bytes_by_part() const {
  TreeBytes b;
  b.positions = fragments.position_bytes();
  b.attributes = fragments.attribute_bytes();
  b.fragments = fragments.record_bytes() + fragment_plane.size() * sizeof(std::uint32_t);
  b.nodes = nodes.size() * sizeof(Node);
  b.planes = planes.bytes();
  return b;
}

}  // namespace bsp
