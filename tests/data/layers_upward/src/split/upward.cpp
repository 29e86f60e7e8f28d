// A split-layer file that reaches up into the tree layer: check_layers.cmake must reject it.
#include "tree/tree.h"
