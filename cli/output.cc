#include "output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/rotor/parameter_table.h"

namespace flaplag::cli {

namespace {

const char* const kOutputOption = "-o";

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
  throw InvalidInput(kOutputOption, path.empty() ? "\"\"" : path, reason);
}

// Counts display columns, not bytes, so that tables with Greek letters stay aligned.
std::size_t display_width(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char c : s) {
    if ((c & 0xC0) != 0x80) ++n;
  }
  return n;
}

std::string pad_left(const std::string& s, std::size_t width) {
  const std::size_t w = display_width(s);
  return w >= width ? s : std::string(width - w, ' ') + s;
}

std::string pad_right(const std::string& s, std::size_t width) {
  const std::size_t w = display_width(s);
  return w >= width ? s : s + std::string(width - w, ' ');
}

void check_target(const std::string& path) {
  if (path.empty()) fail(path, "empty file name");
  if (path.back() == '/') fail(path, "is a directory");
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) fail(path, "is a directory");
}

// Creates <path>.tmp.XXXXXX; returns the descriptor and fills `tmp`.
int make_temporary(const std::string& path, std::string& tmp) {
  std::vector<char> name(path.begin(), path.end());
  const char suffix[] = ".tmp.XXXXXX";
  name.insert(name.end(), suffix, suffix + sizeof suffix);  // includes the terminating NUL
  const int fd = ::mkstemp(name.data());
  if (fd < 0) fail(path, std::string("cannot create a file there: ") + std::strerror(errno));
  tmp.assign(name.data());
  return fd;
}

}  // namespace

void probe_output_path(const std::string& path) {
  check_target(path);
  std::string tmp;
  const int fd = make_temporary(path, tmp);
  ::close(fd);
  ::unlink(tmp.c_str());
}

void write_file_atomically(const std::string& path, const std::string& content) {
  check_target(path);
  std::string tmp;
  const int fd = make_temporary(path, tmp);
  auto abandon = [&](const std::string& what) {
    const std::string reason = what + ": " + std::strerror(errno);
    ::close(fd);
    ::unlink(tmp.c_str());
    fail(path, reason);
  };
  // mkstemp creates mode 0600; give the file the mode it would have had if written directly.
  struct stat st {};
  mode_t mode = 0;
  if (::stat(path.c_str(), &st) == 0) {
    mode = st.st_mode & 07777;
  } else {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    mode = 0666 & ~mask;
  }
  if (::fchmod(fd, mode) != 0) abandon("cannot set the file mode");
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      abandon("write failed");
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  // Without fsync a crash after rename can leave an empty file where the old one was.
  if (::fsync(fd) != 0) abandon("write failed");
  if (::close(fd) != 0) {
    const std::string reason = std::string("write failed: ") + std::strerror(errno);
    ::unlink(tmp.c_str());
    fail(path, reason);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = std::string("cannot replace the file: ") + std::strerror(errno);
    ::unlink(tmp.c_str());
    fail(path, reason);
  }
}

std::string num(double v) { return round_trip_text(v); }

TextTable::TextTable(std::vector<std::string> header) { rows_.push_back(std::move(header)); }

void TextTable::add_row(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }

void TextTable::left_align(std::size_t column) { left_.push_back(column); }

std::string TextTable::render(const std::string& indent) const {
  std::size_t ncol = 0;
  for (const auto& r : rows_) ncol = std::max(ncol, r.size());
  std::vector<std::size_t> width(ncol, 0);
  for (const auto& r : rows_) {
    for (std::size_t c = 0; c < r.size(); ++c) width[c] = std::max(width[c], display_width(r[c]));
  }
  std::string out;
  for (const auto& r : rows_) {
    std::string line = indent;
    for (std::size_t c = 0; c < ncol; ++c) {
      const std::string cell = c < r.size() ? r[c] : "";
      if (c > 0) line += "  ";
      const bool left = std::find(left_.begin(), left_.end(), c) != left_.end();
      line += left ? pad_right(cell, width[c]) : pad_left(cell, width[c]);
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

void KeyValues::add(std::string key, std::string value) {
  items_.emplace_back(std::move(key), std::move(value));
}

std::string KeyValues::render(const std::string& indent) const {
  std::size_t w = 0;
  for (const auto& kv : items_) w = std::max(w, display_width(kv.first));
  std::string out;
  const std::string hanging = indent + std::string(w + 2, ' ');
  for (const auto& kv : items_) {
    // Continuation lines of a multi-line value line up under its first line.
    std::string value;
    for (char c : kv.second) value += c == '\n' ? "\n" + hanging : std::string(1, c);
    out += indent + pad_right(kv.first, w) + "  " + value + "\n";
  }
  return out;
}

}  // namespace flaplag::cli
