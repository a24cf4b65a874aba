// flaplag documents — rows of a described struct (core/fields.h) as the cells of a text table or a
// CSV line: one writer for every table whose columns are rows of a result's table.
//
// A column names a row of T's table by its key; a text table gives it a heading, CSV heads it
// with the key itself.  Cells by the row's type: numbers by cell() in text (a non-finite number
// is "-") and exact_num() in CSV (empty when not finite; a row that allows -inf writes it as
// "-inf"), integers in decimal, flags yes/no (CSV true/false), described enums by name, message
// text (kFieldMessage) in the command line's vocabulary, an empty optional "-" (text) or empty
// (CSV).  A key that T's table lacks, or a row of a type no cell can hold (a list, a struct),
// is a bug of the caller: std::logic_error.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "flaplag/core/field_traits.h"
#include "flaplag/core/fields.h"
#include "flaplag/documents/json_fields.h"
#include "flaplag/documents/numbers.h"
#include "flaplag/documents/output.h"

namespace flaplag::documents {

struct Column {
  const char* key;      // a row of the struct's table
  const char* heading;  // the text table's heading
};

enum class CellStyle { Text, Csv };

namespace table_detail {

template <class V>
std::string cell_text(const V& v, unsigned flags, CellStyle style, const MessageText& message) {
  const bool csv = style == CellStyle::Csv;
  if constexpr (std::is_same_v<V, double>) {
    if (flags & kFieldNegativeInfinity)
      return csv ? (zeta_ok(v) ? exact_zeta_text(v) : std::string()) : zeta_cell(v);
    if (csv) return std::isfinite(v) ? exact_num(v) : std::string();
    return cell(v);
  } else if constexpr (std::is_same_v<V, int>) {
    return std::to_string(v);
  } else if constexpr (std::is_same_v<V, bool>) {
    return csv ? (v ? "true" : "false") : (v ? "yes" : "no");
  } else if constexpr (std::is_same_v<V, std::string>) {
    return (flags & kFieldMessage) ? message(v) : v;
  } else if constexpr (is_described_enum_v<V>) {
    return enum_name(v);
  } else if constexpr (is_optional_field<V>::value) {
    return v ? cell_text(*v, flags, style, message) : std::string(csv ? "" : "-");
  } else {
    throw std::logic_error("a table cell cannot hold this value");
  }
}

// Whether a cell can hold a value of type V (cell_text): a number, an integer, a flag, text, a
// described enum, or an optional of one of these.
template <class V>
constexpr bool is_cell_value() {
  if constexpr (is_optional_field<V>::value) {
    return is_cell_value<typename V::value_type>();
  } else {
    return std::is_same_v<V, double> || std::is_same_v<V, int> || std::is_same_v<V, bool> ||
           std::is_same_v<V, std::string> || is_described_enum_v<V>;
  }
}

}  // namespace table_detail

// The keys of T's rows whose values a cell can hold, in table order, without those in `placed`:
// what a text or CSV table writes after the columns it places itself, so that a row added to a
// result's table reaches its text and CSV with no change to the writer.
template <class T>
std::vector<const char*> other_cell_keys(const std::vector<const char*>& placed) {
  std::vector<const char*> keys;
  for_each_row<T>([&](const auto& row) {
    using V = typename std::decay_t<decltype(row)>::value_type;
    if constexpr (table_detail::is_cell_value<V>()) {
      bool seen = false;
      for (const char* k : placed) seen |= std::string(k) == row.name;
      if (!seen) keys.push_back(row.name);
    }
  });
  return keys;
}

// The cells of `object` under the rows `keys`, in their order.
template <class T>
std::vector<std::string> described_cells(const T& object, const std::vector<const char*>& keys,
                                         CellStyle style, const MessageText& message) {
  std::vector<std::string> out(keys.size());
  std::vector<bool> found(keys.size(), false);
  for_each_field(object, [&](const auto& row, const auto& v) {
    for (std::size_t c = 0; c < keys.size(); ++c) {
      if (std::string(keys[c]) != row.name) continue;
      out[c] = table_detail::cell_text(v, row.flags, style, message);
      found[c] = true;
    }
  });
  for (std::size_t c = 0; c < keys.size(); ++c)
    if (!found[c]) throw std::logic_error(std::string("no row `") + keys[c] + "`");
  return out;
}

// The heading of row `key` of T's table: the key, with the row's units in brackets when it has
// some ("zeta [1/rev]"; a dimensionless "-" is not shown).
template <class T>
std::string described_heading(const char* key) {
  std::string heading;
  if (!visit_row<T>(key, [&](const auto& row) {
        const std::string units = row.units;
        heading = key + (units.empty() || units[0] == '-' ? "" : " [" + units + "]");
      }))
    throw std::logic_error(std::string("no row `") + key + "`");
  return heading;
}

// One line per element of `lines` under `columns`; the first column left-aligned, the others
// right-aligned (TextTable).
template <class T>
TextTable described_table(const std::vector<T>& lines, const std::vector<Column>& columns,
                          const MessageText& message) {
  std::vector<std::string> head;
  std::vector<const char*> keys;
  for (const Column& c : columns) {
    head.push_back(c.heading);
    keys.push_back(c.key);
  }
  TextTable t(head);
  for (const T& x : lines) t.add_row(described_cells(x, keys, CellStyle::Text, message));
  return t;
}

// A CSV field: quoted (RFC 4180) when it holds a comma, a quote or a line break.
inline std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// The fields joined by commas (each csv_field), without the line break.
inline std::string csv_fields(const std::vector<std::string>& fields) {
  std::string out;
  for (std::size_t i = 0; i < fields.size(); ++i) out += (i ? "," : "") + csv_field(fields[i]);
  return out;
}

}  // namespace flaplag::documents
