// flaplag documents — where results go (stdout, an atomically replaced file, a device or FIFO) and
// how numbers and tables are written.
#pragma once

#include <string>
#include <vector>

namespace flaplag::documents {

// Where `-o FILE` (and `--plot FILE`) writes.  Constructed before the analysis, so that a long
// run does not end in a lost result: it checks that the path can be written and decides how, and
// leaves nothing behind (no file is created, opened or changed until write()).
//   - a missing path or a regular file is replaced atomically: a temporary file in the same
//     directory is written, flushed to disk and renamed over the path (a new file gets mode
//     0666 & ~umask, a replaced one keeps its mode and, where permitted, its owner);
//   - a character device (/dev/null, a terminal) or a FIFO is written straight through: it is
//     never replaced;
//   - /dev/stdout, /dev/stderr, /dev/fd/N and /proc/self/fd/N (directly or through links) are
//     written straight to that open descriptor, whatever it is (a pipe, a socket, a file the
//     shell opened), as the shell's own redirection would;
//   - a symbolic link is followed (chains too, relative to the link's directory) and the rules
//     above apply to its target: a regular target is replaced atomically in the target's
//     directory and the link is kept; a dangling link creates its target.  As the kernel's
//     protected_symlinks rule, whether or not the system enables it: a link in a sticky
//     world-writable directory (/tmp), the last component or a directory on the way, is
//     followed only when it belongs to the caller (effective uid) or to the directory's owner;
//   - a directory, block device or socket is refused.
// Errors throw InvalidInput(name, path, reason): name "output" (the command line names it -o as
// typed) or "plot" (--plot).
class OutputTarget {
 public:
  // "" means standard output: nothing to check.
  explicit OutputTarget(std::string path, std::string name = "output");
  void write(const std::string& content) const;

 private:
  std::string path_, name_;
};

// Writes all of `content` to the open descriptor fd; "" on success, else the reason ("write
// failed: No space left on device").  ignore_sigpipe: a pipe whose reader went away is such a
// failure (EPIPE) rather than the end of the process by SIGPIPE (which is what standard output
// does, as every filter in a pipeline: `flaplag models | head -1`).
std::string write_descriptor(int fd, const std::string& content, bool ignore_sigpipe = true);

// Numbers in text output (tables, key-value lines, plot titles), for people: about six
// significant digits (%.6g, exponent without leading zeros: "1e-5").  CSV uses exact_num() and
// JSON the double itself, which keep full round-trip precision.  A non-finite value is a bug
// of the caller, which must have checked its results (commands.cc): num() and exact_num()
// throw std::logic_error rather than print "nan" or "inf" as a result.
std::string num(double v);
// Numbers in CSV: the shortest decimal that reads back as exactly the same double (never more
// than the 17 significant digits of %.17g).
std::string exact_num(double v);
// A damping exponent: num() (text) or exact_num() (CSV), or "-inf" for the zeta of a zero
// multiplier (the only documented non-finite result).
std::string zeta_text(double zeta);
std::string exact_zeta_text(double zeta);

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

// write(2) of all of `content` to fd, retried on EINTR; false with errno set on failure.
bool write_all(int fd, const std::string& content);

}  // namespace flaplag::documents
