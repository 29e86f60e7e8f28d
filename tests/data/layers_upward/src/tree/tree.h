#pragma once
// The tree layer's header that split/upward.cpp reaches up to.
#include "split/splitter.h"
