#include "cyc/a.h"
#include <vector>
