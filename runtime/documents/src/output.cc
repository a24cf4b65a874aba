#include "flaplag/documents/output.h"

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

namespace flaplag::documents {

namespace {

// `name` is the library-style name of the option ("output": -o, "plot": --plot); the command
// line shows it as the user typed it.
[[noreturn]] void fail(const std::string& name, const std::string& path,
                       const std::string& reason) {
  throw InvalidInput(name, path.empty() ? "\"\"" : path, reason);
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

enum class Kind { Missing, Regular, Through, Descriptor };

struct Resolved {
  std::string path;  // symlinks followed: what is replaced or written
  Kind kind = Kind::Missing;
  int fd = -1;  // Descriptor: the open descriptor written to
  struct stat st {};
};

// The descriptor a path names by itself: /dev/stdout (1), /dev/stderr (2), /dev/fd/N and
// /proc/self/fd/N; -1 for any other path.  Following these as links would end in the kernel's
// "pipe:[N]" or "socket:[N]", which name nothing on disk.
int descriptor_of(const std::string& path) {
  if (path == "/dev/stdout") return 1;
  if (path == "/dev/stderr") return 2;
  for (const char* prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    const std::string p(prefix);
    if (path.size() <= p.size() || path.size() > p.size() + 6 || path.compare(0, p.size(), p) != 0)
      continue;
    int fd = 0;
    for (std::size_t i = p.size(); i < path.size(); ++i) {
      if (path[i] < '0' || path[i] > '9') return -1;
      fd = fd * 10 + (path[i] - '0');
    }
    return fd;
  }
  return -1;
}

// The kernel's protected_symlinks rule, applied whether or not the system enables it: in a
// sticky world-writable directory (/tmp) a link is followed only when it belongs to the caller
// or to the directory's owner, so that another user's planted link cannot redirect the output.
void check_link_owner(const std::string& name, const std::string& given, const std::string& link,
                      const struct stat& link_st) {
  const std::string dir = directory_of(link);
  struct stat d {};
  if (::stat(dir.c_str(), &d) != 0) fail(name, given, "directory " + dir + ": " + errno_text());
  const bool sticky_public = (d.st_mode & S_ISVTX) != 0 && (d.st_mode & S_IWOTH) != 0;
  if (!sticky_public || link_st.st_uid == d.st_uid || link_st.st_uid == ::geteuid()) return;
  fail(name, given,
       (link == given ? std::string("a symbolic link") : "symbolic link " + link) +
           " owned by uid " + std::to_string(link_st.st_uid) +
           " in the sticky world-writable directory " + dir +
           ", neither yours nor the directory owner's: not followed");
}

// The same rule for the links among the directories of `dir` (e.g. -o /tmp/planted/out.json with
// /tmp/planted another user's link to /root), which the kernel follows without asking: walks
// `dir` component by component, links resolved as the kernel does (relative to the directory
// holding them), and applies check_link_owner to each link met.  A missing component ends the
// walk (creating the file there fails later with the reason).
void check_directory_links(const std::string& name, const std::string& given,
                           const std::string& dir) {
  std::vector<std::string> todo;  // components still to walk, the next one last
  const auto push_path = [&todo](const std::string& p) {
    std::vector<std::string> parts;
    std::string::size_type from = 0;
    while (from <= p.size()) {
      const auto slash = p.find('/', from);
      const std::string part = p.substr(from, slash == std::string::npos ? slash : slash - from);
      if (!part.empty() && part != ".") parts.push_back(part);
      if (slash == std::string::npos) break;
      from = slash + 1;
    }
    todo.insert(todo.end(), parts.rbegin(), parts.rend());
  };
  std::string at = "/";  // resolved so far: no links in it
  if (dir.empty() || dir[0] != '/') {
    std::vector<char> cwd(4096);
    if (::getcwd(cwd.data(), cwd.size()) == nullptr) return;  // the kernel will say
    at = cwd.data();
  }
  push_path(dir);
  int links = 0;
  while (!todo.empty()) {
    const std::string part = todo.back();
    todo.pop_back();
    if (part == "..") {
      at = directory_of(at);
      continue;
    }
    const std::string next = (at == "/" ? "/" : at + "/") + part;
    struct stat st {};
    if (::lstat(next.c_str(), &st) != 0) return;
    if (!S_ISLNK(st.st_mode)) {
      at = next;
      continue;
    }
    if (++links > 40) return;  // ELOOP, reported when the file is created
    check_link_owner(name, given, next, st);
    std::vector<char> buf(static_cast<std::size_t>(st.st_size > 0 ? st.st_size : 255) + 2);
    const ssize_t n = ::readlink(next.c_str(), buf.data(), buf.size() - 1);
    if (n <= 0) return;
    const std::string to(buf.data(), static_cast<std::size_t>(n));
    if (to[0] == '/') at = "/";
    push_path(to);
  }
}

// Follows symbolic links in the last component (the kernel resolves those in the directories,
// after check_directory_links) and classifies what is found.  Fails for anything that is neither
// missing, a regular file, a character device, a FIFO nor an open descriptor's name.
Resolved resolve(const std::string& name, const std::string& given) {
  if (given.empty()) fail(name, given, "empty file name");
  if (given.back() == '/') fail(name, given, "names a directory (ends in /)");
  Resolved r;
  r.path = given;
  // Linux gives up after 40 links too (ELOOP).
  for (int hop = 0; hop <= 40; ++hop) {
    const std::string what = r.path == given ? "" : "symbolic link to " + r.path + ", which ";
    check_directory_links(name, given, directory_of(r.path));
    if (const int fd = descriptor_of(r.path); fd >= 0) {
      const int flags = ::fcntl(fd, F_GETFL);
      if (flags < 0)
        fail(name, given, what + "names descriptor " + std::to_string(fd) + ": not open");
      if ((flags & O_ACCMODE) == O_RDONLY)
        fail(name, given,
             what + "names descriptor " + std::to_string(fd) + ": open for reading only");
      if (::fstat(fd, &r.st) != 0) fail(name, given, errno_text());
      if (S_ISDIR(r.st.st_mode)) fail(name, given, what + "is a directory");
      r.kind = Kind::Descriptor;
      r.fd = fd;
      return r;
    }
    if (::lstat(r.path.c_str(), &r.st) != 0) {
      if (errno == ENOENT) {
        r.kind = Kind::Missing;
        return r;
      }
      fail(name, given, (r.path == given ? "" : "target " + r.path + ": ") + errno_text());
    }
    if (S_ISLNK(r.st.st_mode)) {
      check_link_owner(name, given, r.path, r.st);
      std::vector<char> buf(static_cast<std::size_t>(r.st.st_size > 0 ? r.st.st_size : 255) + 2);
      const ssize_t n = ::readlink(r.path.c_str(), buf.data(), buf.size() - 1);
      if (n < 0) fail(name, given, "cannot read the symbolic link: " + errno_text());
      const std::string to(buf.data(), static_cast<std::size_t>(n));
      if (to.empty()) fail(name, given, "empty symbolic link");
      r.path = to[0] == '/' ? to : directory_of(r.path) + "/" + to;
      if (r.path.back() == '/') fail(name, given, "symbolic link to a directory: " + r.path);
      continue;
    }
    if (S_ISREG(r.st.st_mode)) {
      r.kind = Kind::Regular;
    } else if (S_ISCHR(r.st.st_mode) || S_ISFIFO(r.st.st_mode)) {
      r.kind = Kind::Through;
    } else if (S_ISDIR(r.st.st_mode)) {
      fail(name, given, what + "is a directory");
    } else {
      fail(name, given, what + "is neither a regular file, a character device nor a FIFO");
    }
    // Replacing a file the user may not write would bypass its permissions.
    if (::access(r.path.c_str(), W_OK) != 0) {
      fail(name, given,
           (what.empty() ? "" : "target " + r.path + ": ") + "not writable: " + errno_text());
    }
    return r;
  }
  fail(name, given, "too many levels of symbolic links");
}

// Creates a temporary file next to `path` (in its directory, so that rename() is atomic);
// returns the descriptor and fills `tmp`.
int make_temporary(const std::string& name, const std::string& given, const std::string& path,
                   std::string& tmp) {
  const std::string pattern = directory_of(path) + "/.flaplag-tmp.XXXXXX";
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  const int fd = ::mkstemp(buf.data());
  if (fd < 0) {
    fail(name, given, "cannot create a file in " + directory_of(path) + ": " + errno_text());
  }
  tmp.assign(buf.data());
  return fd;
}

void replace_atomically(const std::string& name, const std::string& given, const Resolved& r,
                        const std::string& content) {
  std::string tmp;
  const int fd = make_temporary(name, given, r.path, tmp);
  auto abandon = [&](const std::string& what) {
    const std::string reason = what + ": " + errno_text();
    ::close(fd);
    ::unlink(tmp.c_str());
    fail(name, given, reason);
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
    fail(name, given, reason);
  }
  if (::rename(tmp.c_str(), r.path.c_str()) != 0) {
    const std::string reason = "cannot replace " + r.path + ": " + errno_text();
    ::unlink(tmp.c_str());
    fail(name, given, reason);
  }
}

// Runs f with SIGPIPE ignored: a pipe or FIFO whose reader went away must give an error (EPIPE),
// not kill us.
template <class F>
void without_sigpipe(F f) {
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGPIPE, &ignore, &previous);
  f();
  ::sigaction(SIGPIPE, &previous, nullptr);
}

void write_through(const std::string& name, const std::string& given, const Resolved& r,
                   const std::string& content) {
  std::string reason;
  without_sigpipe([&] {
    // No O_CREAT: a device or FIFO that vanished since resolve() is not recreated as a file.
    const int fd = ::open(r.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) {
      reason = "cannot open: " + errno_text();
    } else {
      if (!write_all(fd, content)) reason = "write failed: " + errno_text();
      if (::close(fd) != 0 && reason.empty()) reason = "write failed: " + errno_text();
    }
  });
  if (!reason.empty()) fail(name, given, reason);
}

}  // namespace

std::string write_descriptor(int fd, const std::string& content, bool ignore_sigpipe) {
  std::string reason;
  const auto write = [&] {
    if (!write_all(fd, content)) reason = "write failed: " + errno_text();
  };
  if (ignore_sigpipe)
    without_sigpipe(write);
  else
    write();
  return reason;
}

OutputTarget::OutputTarget(std::string path, std::string name)
    : path_(std::move(path)), name_(std::move(name)) {
  if (path_.empty()) return;
  const Resolved r = resolve(name_, path_);
  // Opening a FIFO would wait for a reader; a descriptor is open already.
  if (r.kind == Kind::Through || r.kind == Kind::Descriptor) return;
  // The rename needs a writable directory: find out now, leaving nothing behind.
  std::string tmp;
  const int fd = make_temporary(name_, path_, r.path, tmp);
  ::close(fd);
  ::unlink(tmp.c_str());
}

void OutputTarget::write(const std::string& content) const {
  if (path_.empty()) return;
  // Resolved again: the path may have changed during the analysis.
  const Resolved r = resolve(name_, path_);
  if (r.kind == Kind::Descriptor) {
    const std::string reason = write_descriptor(r.fd, content);
    if (!reason.empty()) fail(name_, path_, reason);
  } else if (r.kind == Kind::Through) {
    write_through(name_, path_, r, content);
  } else {
    replace_atomically(name_, path_, r, content);
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

}  // namespace flaplag::documents
