#pragma once
// Polygons as Wavefront OBJ text (and an indexed mesh as OFF), for looking at scenes in any viewer and for reading them back.
#include <span>
#include <string>
#include <string_view>

#include "geometry/mesh_weld.h"
#include "geometry/polygon.h"

namespace bsp {

// Each polygon writes its own "v" and "vt" lines, then its "f" line; coordinates are in shortest
// round-trip form, so reading the file back gives the same doubles. `comment` (may be multi-line)
// opens the file as "# " lines. Built in parallel chunks; the text is the same on any thread count.
std::string to_obj(std::span<const Polygon> polys, std::string_view comment);

// An indexed mesh: shared "v" lines, then one "f" line per face (no texture coordinates).
std::string to_obj(const IndexedMesh& mesh, std::string_view comment);

// An indexed mesh as OFF (0-based indices), the format OpenSCAD and CGAL read; `comment` follows
// the header line as "# " lines. Numbers as in to_obj.
std::string to_off(const IndexedMesh& mesh, std::string_view comment);

}  // namespace bsp
