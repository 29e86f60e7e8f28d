#pragma once
// Meshes from files: OBJ, OFF, PLY and STL through CGAL's polygon-soup reader.
#include <string>

#include "scene/scene.h"

namespace bsp {

// The scene is named "file:PATH". Convex planar faces are kept as polygons; others are
// triangulated; faces with a repeated vertex or zero area are dropped; all counted in scene.load.
// Throws InputError "PATH: problem" for a missing, unreadable or malformed file, one claiming more
// than it holds (mesh_claims.h), an unsupported extension, non-finite coordinates or an empty result.
Scene read_mesh(const std::string& path);

}  // namespace bsp
