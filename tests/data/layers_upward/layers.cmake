# The layer description of this planted tree, as cmake/layers.cmake writes the project's: split
# links nothing, tree links split, so split/upward.cpp's include of tree/tree.h must be rejected.
set(layer_include_roots "src")
set(layer_libraries "split;tree")
set(layer_split_files "src/split/upward.cpp")
set(layer_split_dirs "src/split")
set(layer_split_links "")
set(layer_tree_files "")
set(layer_tree_dirs "src/tree")
set(layer_tree_links "split")
