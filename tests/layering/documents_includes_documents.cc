// Control: a documents header compiles with flaplag_documents' include directories (the layers
// below it and nlohmann-json), so the failure of analysis_includes_documents.cc is about the
// layering, not about the compile command.
#include "flaplag/documents/read_file.h"
