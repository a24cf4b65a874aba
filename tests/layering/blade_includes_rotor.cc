// Must NOT compile with only flaplag_blade's include directories (rotor is above blade).
#include "flaplag/rotor/system_builder.h"
