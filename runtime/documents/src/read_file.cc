// flaplag documents — bounded reading and parsing of the files flaplag is given.
#include "flaplag/documents/read_file.h"

#include <errno.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <limits>
#include <set>
#include <vector>

#include "flaplag/core/errors.h"
#include "flaplag/limits.h"

namespace flaplag::documents {

namespace {

class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

// Skips the string starting at text[i] (a quote character) and returns the index of its last
// character; counts the newlines inside.  `escapes`: a backslash escapes the next character.
// TOML's multi-line strings (three quotes) end at the last quote of a run of 3 to 5; a
// single-line string that meets a newline (an error for the parser) ends before it.
std::size_t skip_string(std::string_view text, std::size_t i, bool escapes, bool may_be_multiline,
                        std::size_t& line) {
  const char q = text[i];
  const std::size_t n = text.size();
  const bool multi = may_be_multiline && i + 2 < n && text[i + 1] == q && text[i + 2] == q;
  if (!multi) {
    for (++i; i < n; ++i) {
      if (text[i] == q) return i;
      if (text[i] == '\n') return i - 1;
      if (escapes && text[i] == '\\') ++i;
    }
    return n;
  }
  for (i += 3; i < n; ++i) {
    if (text[i] == '\n') ++line;
    if (escapes && text[i] == '\\') {
      if (i + 1 < n && text[i + 1] == '\n') ++line;
      ++i;
      continue;
    }
    if (text[i] == q && i + 2 < n && text[i + 1] == q && text[i + 2] == q) {
      i += 2;
      while (i + 1 < n && text[i + 1] == q) ++i;  // quotes just before the closing three
      return i;
    }
  }
  return n;
}

template <class J>
JsonParse parse_json_as(const std::string& text, J* out, std::string* error) {
  if (const std::size_t line = json_too_deep(text)) {
    *error = "nested deeper than " + std::to_string(kMaxNesting) + " levels (line " +
             std::to_string(line) + ")";
    return JsonParse::Refused;
  }
  // The keys met in each open object (nullptr for an array), and the key path for messages.
  struct Level {
    bool object = false;
    std::set<std::string> keys;
    std::string key;
  };
  struct DuplicateKey {
    std::string message;
  };
  std::vector<Level> open;
  auto path = [&open] {
    std::string p;
    for (const Level& l : open) {
      if (!l.object)
        p += "[]";
      else
        p += (p.empty() ? "" : ".") + l.key;
    }
    return p;
  };
  const typename J::parser_callback_t check = [&](int, nlohmann::json::parse_event_t event,
                                                  J& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start:
        open.push_back({true, {}, {}});
        break;
      case E::array_start:
        open.push_back({false, {}, {}});
        break;
      case E::object_end:
      case E::array_end:
        if (!open.empty()) open.pop_back();
        break;
      case E::key:
        if (!open.empty() && open.back().object) {
          const std::string key = parsed.template get<std::string>();
          open.back().key = key;
          if (!open.back().keys.insert(key).second)
            throw DuplicateKey{"key " + nlohmann::json(key).dump() +
                               " given twice in one object (at " + path() + ")"};
        }
        break;
      case E::value:
        break;
    }
    return true;
  };
  try {
    *out = J::parse(text, check);
  } catch (const DuplicateKey& d) {
    *error = d.message;
    return JsonParse::Refused;
  } catch (const nlohmann::json::exception& e) {
    *error = e.what();
    return JsonParse::NotJson;
  }
  return JsonParse::Ok;
}

}  // namespace

std::string size_text(std::size_t bytes) {
  if (bytes % (std::size_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

std::string read_text_file(const std::string& path, std::size_t max_bytes, const std::string& noun,
                           const std::string& cannot_read, const std::string& why) {
  const Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) refuse_file(path, cannot_read);
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) refuse_file(path, cannot_read);
  if (S_ISDIR(st.st_mode)) refuse_file(path, "is a directory, not a " + noun);
  const std::string too_large =
      "larger than " + size_text(max_bytes) + " (the limit on a " + noun + why + ")";
  if (S_ISREG(st.st_mode) && static_cast<unsigned long long>(st.st_size) > max_bytes)
    refuse_file(path, too_large);
  std::string text;
  if (S_ISREG(st.st_mode)) text.reserve(static_cast<std::size_t>(st.st_size));
  std::vector<char> buffer(std::size_t{1} << 16);
  for (;;) {
    const ssize_t got = ::read(fd.get(), buffer.data(), buffer.size());
    if (got < 0) {
      if (errno == EINTR) continue;
      if (errno == EISDIR) refuse_file(path, "is a directory, not a " + noun);
      refuse_file(path, cannot_read);
    }
    if (got == 0) break;
    if (text.size() + static_cast<std::size_t>(got) > max_bytes) refuse_file(path, too_large);
    text.append(buffer.data(), static_cast<std::size_t>(got));
  }
  return text;
}

std::size_t json_too_deep(std::string_view text, std::size_t limit) {
  std::size_t depth = 0, line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    switch (text[i]) {
      case '\n':
        ++line;
        break;
      case '"':
        i = skip_string(text, i, true, false, line);
        break;
      case '[':
      case '{':
        if (++depth > limit) return line;
        break;
      case ']':
      case '}':
        if (depth > 0) --depth;
        break;
      default:
        break;
    }
  }
  return 0;
}

std::size_t toml_too_deep(std::string_view text, std::size_t limit) {
  std::size_t line = 1;
  // The dots of dotted keys (and floats) met at each open [ or { (index 0: outside them) since
  // the last ',' or newline at that level, and their sum.
  std::vector<std::size_t> dots{0};
  std::size_t total = 0;
  std::size_t base = 0;          // the parts of the last [table] header
  bool header = false;           // in a [table] or [[array]] header
  std::size_t header_parts = 0;  // its parts so far
  bool value = false;            // '=' met on this line outside brackets
  auto depth = [&] { return header ? header_parts + 1 : base + (dots.size() - 1) + total; };
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n; ++i) {
    const char c = text[i];
    switch (c) {
      case '\n':
        ++line;
        if (header) {
          base = header_parts + 1;
          header = false;
          header_parts = 0;
        }
        total -= dots.back();
        dots.back() = 0;
        if (dots.size() == 1) value = false;
        break;
      case '#':  // a comment, to the end of the line
        while (i + 1 < n && text[i + 1] != '\n') ++i;
        break;
      case '"':
      case '\'':
        i = skip_string(text, i, c == '"', true, line);
        break;
      case '[':
      case '{':
        if (header) break;  // the second [ of [[
        if (c == '[' && dots.size() == 1 && !value) {
          header = true;
          header_parts = 0;
          break;
        }
        dots.push_back(0);
        break;
      case ']':
      case '}':
        if (!header && dots.size() > 1) {
          total -= dots.back();
          dots.pop_back();
        }
        break;
      case ',':
        if (!header) {
          total -= dots.back();
          dots.back() = 0;
        }
        break;
      case '=':
        if (!header && dots.size() == 1) value = true;
        break;
      case '.':
        if (header) {
          ++header_parts;
        } else {
          ++dots.back();
          ++total;
        }
        break;
      default:
        break;
    }
    if (depth() > limit) return line;
  }
  return 0;
}

JsonParse parse_json(const std::string& text, nlohmann::json* out, std::string* error) {
  return parse_json_as(text, out, error);
}

JsonParse parse_json(const std::string& text, nlohmann::ordered_json* out, std::string* error) {
  return parse_json_as(text, out, error);
}

}  // namespace flaplag::documents

namespace flaplag::documents {

std::size_t json_read_limit(std::uint64_t memory_limit) {
  const std::uint64_t bytes = memory_limit / kJsonMemoryFactor;
  return bytes > std::numeric_limits<std::size_t>::max() / 2
             ? std::numeric_limits<std::size_t>::max() / 2
             : static_cast<std::size_t>(bytes);
}

std::string read_json_file(const std::string& path, std::uint64_t memory_limit,
                           const std::string& noun, const std::string& cannot_read,
                           const Spelling& option) {
  const std::string limit = option("memory_limit");
  return read_text_file(path, json_read_limit(memory_limit), noun, cannot_read,
                        " under " + limit + " " + memory_text(memory_limit) +
                            ", which reading JSON of this size may need: raise " + limit);
}

}  // namespace flaplag::documents
