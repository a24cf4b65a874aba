// Must NOT compile with only flaplag_numerics' include directories: the numerics know nothing
// about rotors, so the analysis facade is out of their reach (tests/layering/CMakeLists.txt).
#include "flaplag/analysis.h"
