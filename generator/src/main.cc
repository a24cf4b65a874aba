// flaplag-derive: derive one ordering model and write <out-dir>/<model>.cc and <model>.md.
//
//   flaplag-derive --spec generator/orderings/paper.toml --out-dir build/gen
//
// Exit codes: 0 ok, 2 bad spec or arguments (one line on stderr), 1 internal failure.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "flaplag_derive/derive.h"
#include "flaplag_derive/emit.h"
#include "flaplag_derive/generic.h"
#include "flaplag_derive/spec.h"

namespace {

// Writes atomically: a failed run never leaves a half-written file behind.
void write_file(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::filesystem::rename(tmp, path);
}

int usage() {
  std::cerr << "flaplag-derive: error: usage: flaplag-derive --spec FILE.toml --out-dir DIR\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string spec_path, out_dir;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--spec" && i + 1 < argc) {
      spec_path = argv[++i];
    } else if (a == "--out-dir" && i + 1 < argc) {
      out_dir = argv[++i];
    } else {
      std::cerr << "flaplag-derive: error: unknown argument " << a << "\n";
      return 2;
    }
  }
  if (spec_path.empty() || out_dir.empty()) return usage();
  try {
    const auto spec = flaplag::derive::load_spec(spec_path);
    // The family (any M x N) is the code; the report audits the spec's own mode counts in the
    // paper's layout, then every term with its mode indices.
    const auto family = flaplag::derive::extract_generic(spec);
    auto concrete_spec = spec;
    concrete_spec.cyclic_pitch = true;
    concrete_spec.nonlinear = true;
    const auto model = flaplag::derive::derive_model(concrete_spec);
    std::filesystem::create_directories(out_dir);
    write_file(std::filesystem::path(out_dir) / (spec.name + ".cc"),
               flaplag::derive::emit_family_cpp(family));
    write_file(std::filesystem::path(out_dir) / (spec.name + ".md"),
               flaplag::derive::emit_report(model) +
                   flaplag::derive::emit_family_report(family));
  } catch (const flaplag::derive::SpecError& e) {
    std::cerr << "flaplag-derive: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "flaplag-derive: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
