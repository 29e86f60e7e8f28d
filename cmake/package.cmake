# The installed library: `cmake --install build --prefix P` puts the public headers in
# P/include/bspbench, one shared library, libbspbench.so, in P/lib, and a CMake package in
# P/lib/cmake/bspbench, so another project writes
#   find_package(bspbench 0.1 CONFIG REQUIRED)
#   target_link_libraries(x PRIVATE bspbench::bsp)
# and includes <bspbench/tree/build.h> (or "tree/build.h"). docs/plugins.md has the rules.
#
# The shared library holds the objects of the layers below experiments (common to validate, and the
# scene generators): the layers themselves stay static, so bspbench's own programs link as before.
# Every library is position-independent (CMakeLists.txt) for this. CGAL and Embree are linked
# privately: no public header names their types (the package test checks), so a consumer needs
# neither, only nlohmann_json, which the headers' json_fwd.hpp comes from.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(_bspbench_installed_layers bspbench_common bspbench_geometry bspbench_scene bspbench_split bspbench_tree
    bspbench_solid bspbench_cull bspbench_dynamic bspbench_search bspbench_io bspbench_metrics bspbench_validate
    bspbench_validate_solid bspbench_generators)
# The layers' header folders under src/, and generators/.
set(_bspbench_installed_dirs common geometry scene split tree solid cull dynamic search io metrics validate)

set(_bspbench_objects "")
foreach(layer IN LISTS _bspbench_installed_layers)
  list(APPEND _bspbench_objects $<TARGET_OBJECTS:${layer}>)
endforeach()
add_library(bspbench_shared SHARED ${_bspbench_objects})
# The layers' own links (CGAL's helper libraries, Embree, OpenMP, GMP, dl) come with them; their
# objects are already in, so the archives add nothing twice.
target_link_libraries(bspbench_shared PRIVATE ${_bspbench_installed_layers}
                      PUBLIC nlohmann_json::nlohmann_json)
target_include_directories(bspbench_shared INTERFACE
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src> $<BUILD_INTERFACE:${CMAKE_BINARY_DIR}/generated>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/bspbench> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_compile_features(bspbench_shared INTERFACE cxx_std_20)
set_target_properties(bspbench_shared PROPERTIES
  OUTPUT_NAME bspbench EXPORT_NAME bsp
  VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
  LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/lib)

install(TARGETS bspbench_shared EXPORT bspbenchTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/bspbench)
foreach(dir IN LISTS _bspbench_installed_dirs)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/${dir} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/bspbench
          FILES_MATCHING PATTERN "*.h"
          # CGAL's types, for the CGAL-compiled files of the library only
          PATTERN "cgal_mesh.h" EXCLUDE)
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/generators/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/bspbench/generators
        FILES_MATCHING PATTERN "*.h")
install(FILES ${CMAKE_BINARY_DIR}/generated/common/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/bspbench/common)

install(EXPORT bspbenchTargets NAMESPACE bspbench:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/bspbench)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/bspbenchConfig.cmake.in
  ${CMAKE_BINARY_DIR}/package/bspbenchConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/bspbench)
# While the major version is 0, a minor release may break the interface (common/version.h).
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/bspbenchConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/package/bspbenchConfig.cmake ${CMAKE_BINARY_DIR}/package/bspbenchConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/bspbench)
