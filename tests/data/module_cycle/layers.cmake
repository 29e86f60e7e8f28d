# The layer description of this planted tree: one library whose modules a, b and c use each other
# in a ring (a.h includes b.h, b.cpp includes c.h, c.h includes a.h), which
# cmake/check_module_cycles.cmake must report as one cycle; d only uses a and is on no cycle.
set(layer_include_roots "src")
set(layer_libraries "cyc")
set(layer_cyc_files "src/cyc/b.cpp;src/cyc/d.cpp")
set(layer_cyc_dirs "src/cyc")
set(layer_cyc_links "")
