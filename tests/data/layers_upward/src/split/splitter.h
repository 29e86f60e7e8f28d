#pragma once
// A header of the split layer, which the tree layer uses.
