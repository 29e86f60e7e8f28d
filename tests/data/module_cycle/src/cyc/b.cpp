#include "cyc/b.h"
#include "cyc/c.h"
