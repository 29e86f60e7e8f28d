#pragma once
// What a mesh file may claim, checked against what it holds before CGAL sees it. CGAL's readers
// size their arrays from the file's own numbers (an OFF header's vertex and face counts, an OFF
// face's vertex count, a PLY list's length) before reading the data, so a 100-byte file claiming a
// billion faces would make them allocate gigabytes. Every such number is checked here against the
// records or bytes that are really there.
#include <string>
#include <string_view>

namespace bsp {

// Before CGAL reads the file. `content` is the whole file, `ext` its lower-case extension; OFF, PLY
// and STL are checked (CGAL's OBJ reader grows its arrays as it reads). Throws InputError
// "PATH: problem" naming the first claim the file cannot back: a count larger than the records or
// bytes that follow, a face or list longer than its line or the bytes left. Binary OFF is rejected
// (its per-face counts are not checked here).
void check_mesh_claims(const std::string& path, std::string_view content, const std::string& ext);

// After CGAL read an OBJ file, or to say why it rejected one: CGAL reads a face index into an int, stops the face silently at
// one that does not fit, and resolves a negative (relative) one without checking it, so the
// indices are checked on the text. Throws InputError "PATH: line L: face index I ..." for an index
// that is zero, too large for an int, past the last vertex, or reaching back past the first.
void check_obj_face_indices(const std::string& path, std::string_view content);

}  // namespace bsp
