#pragma once
// The code a binary was built from, taken when it was built (not when CMake was configured): the
// generated revision.cpp is rewritten by every build whose git state differs (CMakeLists.txt,
// cmake/revision.cmake), so reports and benchmark contexts name the commit that produced them.
namespace bsp {

// The commit's 12-digit abbreviated hash, with "-dirty" when tracked files differed from it;
// "unknown" outside a git checkout.
const char* git_revision();
// The project's version (CMakeLists.txt `project(... VERSION ...)`).
const char* project_version();

}  // namespace bsp
