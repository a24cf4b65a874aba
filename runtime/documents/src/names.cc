// flaplag documents — the forms of refused values and JSON keys.
#include "flaplag/documents/names.h"

#include <cstdio>

#include "flaplag/core/errors.h"

namespace flaplag::documents {

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v'; }

}  // namespace

std::string shown(const std::string& text) {
  bool plain = !text.empty() && !is_blank(text.front()) && !is_blank(text.back());
  for (unsigned char ch : text) plain = plain && ch >= 0x20 && ch != 0x7f;
  if (plain) return text;
  // Quoted, with control characters escaped, so that the error stays on one line and shows
  // blanks the user may not see.
  std::string q = "\"";
  for (unsigned char ch : text) {
    if (ch == '"' || ch == '\\') {
      q += '\\';
      q += static_cast<char>(ch);
    } else if (ch == '\n') {
      q += "\\n";
    } else if (ch == '\t') {
      q += "\\t";
    } else if (ch < 0x20 || ch == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", ch);
      q += buf;
    } else {
      q += static_cast<char>(ch);
    }
  }
  return q + "\"";
}

void refuse_file(const std::string& file, const std::string& reason) {
  throw InvalidInput("argument", shown(file), reason);
}

std::string json_word(std::string_view field) {
  std::string s(field);
  for (char& c : s)
    if (c == '_') c = '-';
  return s;
}

std::string json_key(const ParameterSpec& spec) { return json_word(spec.field); }

}  // namespace flaplag::documents
