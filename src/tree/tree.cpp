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

std::size_t Tree::bytes() const {
  return nodes.size() * sizeof(Node) + planes.bytes() + fragments.bytes() +
         fragment_plane.size() * sizeof(std::uint32_t);
}

}  // namespace bsp
