// flaplag documents — the reference of the result structs in the JSON documents (docs/json.md),
// generated from the field tables; the front end's part (which command writes which document,
// under which options) is its own.
#pragma once

#include <string>

namespace flaplag::documents {

// The sections "Results" and "Python results": one table per described result struct (key,
// type, units, description), markdown.
std::string results_reference();

// The head of a table of keys, one row of it ('|' in a text escaped), and a link to the section
// of a result struct ("[PointResult](#pointresult)").
inline constexpr const char* kTableHead =
    "| key | type | units | description |\n|---|---|---|---|\n";
std::string table_row(const std::string& key, const std::string& type, const std::string& units,
                      const std::string& doc);
std::string section_link(const char* name);

}  // namespace flaplag::documents
