// flaplag-json-docs: writes docs/json.md (json_docs.h) to the file given, or to standard output.
// A build tool (the refresh-docs target), not a user command.
#include <fstream>
#include <iostream>

#include "json_docs.h"

int main(int argc, char** argv) {
  const std::string text = flaplag::cli::json_reference();
  if (argc < 2) {
    std::cout << text;
    return std::cout ? 0 : 1;
  }
  std::ofstream out(argv[1], std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    std::cerr << "flaplag-json-docs: cannot write " << argv[1] << "\n";
    return 1;
  }
  return 0;
}
