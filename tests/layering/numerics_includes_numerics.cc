// Control: a numerics header compiles with flaplag_numerics' include directories, so the
// failures of the other two files are about the layering, not about the compile command.
#include "flaplag/numerics/continuation.h"
