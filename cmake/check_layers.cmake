cmake_minimum_required(VERSION 3.25)
# The layering is the link lines (cmake/layers.cmake writes them down at configure time as
# build/layers.cmake): a file may include only files of its own library and of the libraries it
# links, directly or through others; and a library links only libraries it includes something of.
#   cmake -DROOT=<source tree> -DLAYERS=<layer description> -P check_layers.cmake
# prints every offence and fails when there is one;
#   ... -DMODE=graph -P check_layers.cmake
# prints the layer graph (each library and the libraries it links directly), and
#   ... -DMODE=documented -DDOC=<file> -P check_layers.cmake
# fails unless DOC holds that printed block verbatim (docs/architecture.md does).

if(MODE STREQUAL "graph" OR MODE STREQUAL "documented")
  include(${LAYERS})
  # Sorted, one edge a line, so that the block changes only where the link lines do.
  set(edges "")
  set(libs ${layer_libraries})
  list(SORT libs)
  foreach(lib IN LISTS libs)
    set(links ${layer_${lib}_links})
    list(SORT links)
    if(NOT links)
      list(APPEND edges "  ${lib}")
    endif()
    foreach(link IN LISTS links)
      list(APPEND edges "  ${lib} --> ${link}")
    endforeach()
  endforeach()
  list(JOIN edges "\n" edges)
  set(block "<!-- layer-graph:begin -->\n```mermaid\ngraph TD\n${edges}\n```\n<!-- layer-graph:end -->")
  if(MODE STREQUAL "graph")
    message(NOTICE "${block}")
  else()
    file(READ ${DOC} doc)
    string(FIND "${doc}" "${block}" at)
    if(at EQUAL -1)
      message(NOTICE "${block}")
      message(FATAL_ERROR "${DOC} does not hold the layer graph of the link lines printed above: "
                          "put it in place of the block between the markers")
    endif()
  endif()
  return()
endif()

include(${CMAKE_CURRENT_LIST_DIR}/project_includes.cmake)
set(problems 0)
macro(problem text)
  message(NOTICE "${text}")
  math(EXPR problems "${problems} + 1")
endmacro()

# What each library may include from: the libraries it links, and theirs, down to the bottom.
foreach(lib IN LISTS layer_libraries)
  set(reach_${lib} "")
  set(pending ${layer_${lib}_links})
  while(pending)
    list(POP_FRONT pending next)
    if(NOT next IN_LIST reach_${lib})
      list(APPEND reach_${lib} ${next})
      list(APPEND pending ${layer_${next}_links})
    endif()
  endwhile()
endforeach()

foreach(file IN LISTS project_files)
  layer_owners(${file} lib)
  list(LENGTH lib owners)
  if(owners GREATER 1)
    list(JOIN lib ", " lib)
    problem("${file}: owned by several libraries (${lib}): name it among the sources of one")
    continue()
  endif()
  project_includes(${file} included)
  foreach(inc IN LISTS included)
    layer_owners(${inc} used)
    if(NOT used)
      problem("${file}: ${lib} includes ${inc}, which no library owns")
    elseif(used IN_LIST reach_${lib})
      set(uses_${lib}_${used} TRUE)
    # (a file of several owners is reported once, as such, not at each include of it)
    elseif(NOT used STREQUAL lib AND NOT used MATCHES ";")
      problem("${file}: ${lib} includes ${inc} of ${used}, which it does not link")
    endif()
  endforeach()
endforeach()

# A link nothing needs hides the real layering and makes a lower layer look used.
foreach(lib IN LISTS layer_libraries)
  foreach(link IN LISTS layer_${lib}_links)
    if(NOT uses_${lib}_${link})
      problem("${lib} links ${link} but includes nothing of it")
    endif()
  endforeach()
endforeach()

list(LENGTH layer_libraries count)
if(problems GREATER 0)
  message(FATAL_ERROR "check_layers: ${problems} problem(s) in ${count} libraries")
endif()
message(STATUS "check_layers: the includes of ${count} libraries follow their link lines exactly")
