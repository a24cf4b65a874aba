#include "output.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <utility>

#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag::cli {

namespace {

// The library-style name of -o: the command line shows it as the user typed it.
const char* const kOutputName = "output";

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
  throw InvalidInput(kOutputName, path.empty() ? "\"\"" : path, reason);
}

std::string errno_text() { return std::strerror(errno); }

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

std::string directory_of(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

enum class Kind { Missing, Regular, Through };

struct Resolved {
  std::string path;  // symlinks followed: what is replaced or written
  Kind kind = Kind::Missing;
  struct stat st {};
};

// Follows symbolic links in the last component (the kernel resolves those in the directories)
// and classifies what is found.  Fails for anything that is neither missing, a regular file, a
// character device nor a FIFO.
Resolved resolve(const std::string& given) {
  if (given.empty()) fail(given, "empty file name");
  if (given.back() == '/') fail(given, "names a directory (ends in /)");
  Resolved r;
  r.path = given;
  // Linux gives up after 40 links too (ELOOP).
  for (int hop = 0; hop <= 40; ++hop) {
    if (::lstat(r.path.c_str(), &r.st) != 0) {
      if (errno == ENOENT) {
        r.kind = Kind::Missing;
        return r;
      }
      fail(given, (r.path == given ? "" : "target " + r.path + ": ") + errno_text());
    }
    if (S_ISLNK(r.st.st_mode)) {
      std::vector<char> buf(static_cast<std::size_t>(r.st.st_size > 0 ? r.st.st_size : 255) + 2);
      const ssize_t n = ::readlink(r.path.c_str(), buf.data(), buf.size() - 1);
      if (n < 0) fail(given, "cannot read the symbolic link: " + errno_text());
      const std::string to(buf.data(), static_cast<std::size_t>(n));
      if (to.empty()) fail(given, "empty symbolic link");
      r.path = to[0] == '/' ? to : directory_of(r.path) + "/" + to;
      if (r.path.back() == '/') fail(given, "symbolic link to a directory: " + r.path);
      continue;
    }
    const std::string what = r.path == given ? "" : "symbolic link to " + r.path + ", which ";
    if (S_ISREG(r.st.st_mode)) {
      r.kind = Kind::Regular;
    } else if (S_ISCHR(r.st.st_mode) || S_ISFIFO(r.st.st_mode)) {
      r.kind = Kind::Through;
    } else if (S_ISDIR(r.st.st_mode)) {
      fail(given, what + "is a directory");
    } else {
      fail(given, what + "is neither a regular file, a character device nor a FIFO");
    }
    // Replacing a file the user may not write would bypass its permissions.
    if (::access(r.path.c_str(), W_OK) != 0) {
      fail(given,
           (what.empty() ? "" : "target " + r.path + ": ") + "not writable: " + errno_text());
    }
    return r;
  }
  fail(given, "too many levels of symbolic links");
}

// Creates a temporary file next to `path` (in its directory, so that rename() is atomic);
// returns the descriptor and fills `tmp`.
int make_temporary(const std::string& given, const std::string& path, std::string& tmp) {
  const std::string pattern = directory_of(path) + "/.flaplag-tmp.XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) {
    fail(given, "cannot create a file in " + directory_of(path) + ": " + errno_text());
  }
  tmp.assign(name.data());
  return fd;
}

// write(2) until done; false with errno set on failure.
bool write_all(int fd, const std::string& content) {
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

void replace_atomically(const std::string& given, const Resolved& r, const std::string& content) {
  std::string tmp;
  const int fd = make_temporary(given, r.path, tmp);
  auto abandon = [&](const std::string& what) {
    const std::string reason = what + ": " + errno_text();
    ::close(fd);
    ::unlink(tmp.c_str());
    fail(given, reason);
  };
  // mkstemp creates mode 0600; give the file the mode it would have had if written directly.
  mode_t mode = 0;
  if (r.kind == Kind::Regular) {
    mode = r.st.st_mode & 07777;
    // Keep the owner where we may (root replacing a user's file); failure is harmless.
    if (::fchown(fd, r.st.st_uid, r.st.st_gid) != 0) errno = 0;
  } else {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    mode = 0666 & ~mask;
  }
  if (::fchmod(fd, mode) != 0) abandon("cannot set the file mode");
  if (!write_all(fd, content)) abandon("write failed");
  // Without fsync a crash after rename can leave an empty file where the old one was.
  if (::fsync(fd) != 0) abandon("write failed");
  if (::close(fd) != 0) {
    const std::string reason = "write failed: " + errno_text();
    ::unlink(tmp.c_str());
    fail(given, reason);
  }
  if (::rename(tmp.c_str(), r.path.c_str()) != 0) {
    const std::string reason = "cannot replace " + r.path + ": " + errno_text();
    ::unlink(tmp.c_str());
    fail(given, reason);
  }
}

void write_through(const std::string& given, const Resolved& r, const std::string& content) {
  // A FIFO whose reader went away must give an error, not kill us with SIGPIPE.
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGPIPE, &ignore, &previous);
  // No O_CREAT: a device or FIFO that vanished since resolve() is not recreated as a file.
  const int fd = ::open(r.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  std::string reason;
  if (fd < 0) {
    reason = "cannot open: " + errno_text();
  } else {
    if (!write_all(fd, content)) reason = "write failed: " + errno_text();
    if (::close(fd) != 0 && reason.empty()) reason = "write failed: " + errno_text();
  }
  ::sigaction(SIGPIPE, &previous, nullptr);
  if (!reason.empty()) fail(given, reason);
}

}  // namespace

OutputTarget::OutputTarget(std::string path) : path_(std::move(path)) {
  if (path_.empty()) return;
  const Resolved r = resolve(path_);
  if (r.kind == Kind::Through) return;  // opening a FIFO would wait for a reader
  // The rename needs a writable directory: find out now, leaving nothing behind.
  std::string tmp;
  const int fd = make_temporary(path_, r.path, tmp);
  ::close(fd);
  ::unlink(tmp.c_str());
}

void OutputTarget::write(const std::string& content) const {
  if (path_.empty()) return;
  // Resolved again: the path may have changed during the analysis.
  const Resolved r = resolve(path_);
  if (r.kind == Kind::Through) {
    write_through(path_, r, content);
  } else {
    replace_atomically(path_, r, content);
  }
}

namespace {
void check_finite(double v) {
  if (!std::isfinite(v)) {
    throw std::logic_error("non-finite number " + round_trip_text(v) + " reached the output");
  }
}
}  // namespace

std::string num(double v) {
  check_finite(v);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  // "1e-05" -> "1e-5", "1e+20" -> "1e+20" stays, "1e+05" -> "1e+5".
  std::string s = buf;
  const std::size_t e = s.find('e');
  if (e != std::string::npos && e + 2 < s.size()) {
    std::size_t first = e + 2;
    while (first + 1 < s.size() && s[first] == '0') s.erase(first, 1);
  }
  return s;
}

std::string exact_num(double v) {
  check_finite(v);
  return round_trip_text(v);
}

std::string zeta_text(double zeta) {
  return zeta == -std::numeric_limits<double>::infinity() ? "-inf" : num(zeta);
}

std::string exact_zeta_text(double zeta) {
  return zeta == -std::numeric_limits<double>::infinity() ? "-inf" : exact_num(zeta);
}

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
