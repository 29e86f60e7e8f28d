#pragma once
#include "cyc/b.h"
