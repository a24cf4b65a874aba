// flaplag CLI — where results go (stdout or an atomically replaced file) and how numbers and
// tables are written.
#pragma once

#include <string>
#include <vector>

namespace flaplag::cli {

// Checks now that `path` can be written, so that a long analysis does not end in a lost result,
// and leaves nothing behind: the probe file is removed at once.  Throws InvalidInput("-o", ...).
void probe_output_path(const std::string& path);

// Writes `content` to `path` atomically: a temporary file in the same directory
// (<path>.tmp.XXXXXX) is written, flushed to disk and renamed over `path`.  On any failure the
// temporary is removed, an existing `path` is left untouched and InvalidInput("-o", ...) is thrown.
// A new file gets mode 0666 & ~umask; a replaced file keeps its mode.
void write_file_atomically(const std::string& path, const std::string& content);

// Numbers in text output: shortest decimal that reads back as exactly the same double
// (never more than the 17 significant digits of %.17g).
std::string num(double v);

// A text table: left-aligned first column, right-aligned further columns (numbers) unless
// marked as text, two blanks between.
class TextTable {
 public:
  explicit TextTable(std::vector<std::string> header);
  void add_row(std::vector<std::string> cells);
  void left_align(std::size_t column);
  // Each line starts with `indent`.
  std::string render(const std::string& indent = "  ") const;

 private:
  std::vector<std::vector<std::string>> rows_;  // rows_[0] is the header
  std::vector<std::size_t> left_{0};
};

// "key   value" lines with the values aligned; a value may span several lines.
class KeyValues {
 public:
  void add(std::string key, std::string value);
  std::string render(const std::string& indent = "  ") const;

 private:
  std::vector<std::pair<std::string, std::string>> items_;
};

}  // namespace flaplag::cli
