# What the checks of cmake/check_layers.cmake and cmake/check_module_cycles.cmake read (script mode,
# -DROOT=<source tree> -DLAYERS=<layer description>): the description cmake/layers.cmake writes at
# configure time (or a test's own), the project's files (every .h and .cpp in a library's
# directories), the file each quoted include names, and the library owning each file.
if(NOT ROOT OR NOT LAYERS)
  message(FATAL_ERROR "give -DROOT=<source tree> -DLAYERS=<layer description>")
endif()
include(${LAYERS})

set(project_files "")
foreach(lib IN LISTS layer_libraries)
  foreach(dir IN LISTS layer_${lib}_dirs)
    file(GLOB_RECURSE found RELATIVE ${ROOT} ${ROOT}/${dir}/*.h ${ROOT}/${dir}/*.cpp)
    list(APPEND project_files ${found})
  endforeach()
endforeach()
list(REMOVE_DUPLICATES project_files)
list(SORT project_files)

# The libraries owning `file` (relative to ROOT): the ones naming it among their sources or naming
# the .cpp beside a header, else the ones with the longest directory holding it. More than one
# owner is an ambiguity the layer check reports; none, a file outside every library.
function(layer_owners file out)
  set(owners "")
  string(REGEX REPLACE "\\.h$" ".cpp" twin "${file}")
  foreach(lib IN LISTS layer_libraries)
    if(file IN_LIST layer_${lib}_files OR twin IN_LIST layer_${lib}_files)
      list(APPEND owners ${lib})
    endif()
  endforeach()
  if(NOT owners)
    set(longest -1)
    foreach(lib IN LISTS layer_libraries)
      foreach(dir IN LISTS layer_${lib}_dirs)
        string(FIND "${file}" "${dir}/" at)
        string(LENGTH "${dir}" length)
        if(at EQUAL 0 AND length GREATER longest)
          set(owners ${lib})
          set(longest ${length})
        elseif(at EQUAL 0 AND length EQUAL longest)
          list(APPEND owners ${lib})
        endif()
      endforeach()
    endforeach()
  endif()
  list(REMOVE_DUPLICATES owners)
  set(${out} ${owners} PARENT_SCOPE)
endfunction()

# The project files `file` includes by quoted name ("x/y.h", "catalog.h"), relative to ROOT: each
# name is looked for in the including file's directory, then in the include roots, as the compiler
# does; a name found nowhere (a system header) is left out.
function(project_includes file out)
  file(STRINGS ${ROOT}/${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  cmake_path(GET file PARENT_PATH own_dir)
  set(included "")
  foreach(line IN LISTS lines)
    string(REGEX MATCH "\"([^\"]+)\"" unused "${line}")
    foreach(dir IN ITEMS ${own_dir} ${layer_include_roots})
      set(candidate ${dir}/${CMAKE_MATCH_1})
      cmake_path(NORMAL_PATH candidate)
      if(EXISTS ${ROOT}/${candidate} AND NOT IS_DIRECTORY ${ROOT}/${candidate})
        list(APPEND included ${candidate})
        break()
      endif()
    endforeach()
  endforeach()
  set(${out} ${included} PARENT_SCOPE)
endfunction()
