// Must NOT compile with only flaplag_analysis' include directories: the documents (result files,
// pictures, reports) are above the analysis, which knows nothing of files or JSON.
#include "flaplag/documents/read_file.h"
