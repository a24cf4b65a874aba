// docs/json.md equals a fresh generation from the field tables (cli/json_docs.h), and the JSON
// writer (cli/json_fields.h) writes every row of a table under its key, in table order.  On a
// stale docs/json.md the test prints the first differing line and the refresh command.
#include "json_docs.h"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "json_fields.h"

namespace flaplag::cli {
namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> v;
  std::stringstream ss(text);
  std::string s;
  while (std::getline(ss, s)) v.push_back(s);
  return v;
}

TEST(JsonDocs, CheckedInReferenceIsFresh) {
  std::ifstream in(FLAPLAG_JSON_DOCS, std::ios::binary);
  ASSERT_TRUE(in) << "cannot read " << FLAPLAG_JSON_DOCS;
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string fresh = json_reference();
  if (ss.str() == fresh) return;
  const auto a = lines(ss.str()), b = lines(fresh);
  std::size_t i = 0;
  while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
  ADD_FAILURE() << "docs/json.md is stale (refresh: cmake --build build --target refresh-docs); "
                << "first difference at line " << i + 1
                << ":\n  checked in: " << (i < a.size() ? a[i] : "(end)")
                << "\n  fresh:      " << (i < b.size() ? b[i] : "(end)");
}

TEST(JsonDocs, ReferenceListsEveryKeyOfTheTables) {
  const std::string doc = json_reference();
  for_each_row<PointResult>([&](const auto& row) {
    EXPECT_NE(std::string::npos, doc.find("| `" + std::string(row.name) + "` |")) << row.name;
  });
  for_each_row<CriticalResult>([&](const auto& row) {
    EXPECT_NE(std::string::npos, doc.find("| `" + std::string(row.name) + "` |")) << row.name;
  });
}

TEST(JsonFields, EveryRowUnderItsKeyInTableOrder) {
  PointResult p;
  p.mu = 0.25;
  p.exponents = {{"flap", -std::numeric_limits<double>::infinity(), 0.5, {0.0, 0.0}, {}}};
  p.error = 1e-7;
  p.status = Status::Warning;
  p.message = "`steps` too small";
  const cmd::Json j = cmd::to_json(p, [](const std::string& m) { return "<" + m + ">"; });
  std::vector<std::string> keys, rows;
  for (const auto& item : j.items()) keys.push_back(item.key());
  for_each_row<PointResult>([&](const auto& row) {
    if (std::string(row.name) != "notes") rows.push_back(row.name);  // absent when empty
  });
  EXPECT_EQ(rows, keys);
  EXPECT_EQ(0.25, j["mu"].get<double>());
  EXPECT_EQ("-inf", j["exponents"][0]["zeta"]);  // the one non-finite value JSON holds
  EXPECT_TRUE(j["liouville_residual"].is_null());
  EXPECT_EQ(1e-7, j["error_estimate"].get<double>());
  EXPECT_EQ("warning", j["status"]);
  EXPECT_EQ("<`steps` too small>", j["message"]);  // in the front end's vocabulary
  p.Note("a remark");
  EXPECT_EQ("<a remark>",
            cmd::to_json(p, [](const std::string& m) { return "<" + m + ">"; })["notes"][0]);
}

}  // namespace
}  // namespace flaplag::cli
