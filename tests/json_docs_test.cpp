// docs/json.md equals a fresh generation from the field tables (cli/json_docs.h), and the JSON
// writer (cli/json_fields.h) writes every row of a table under its key, in table order.  On a
// stale docs/json.md the test prints the first differing line and the refresh command.
#include "json_docs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "flaplag/campbell.h"
#include "flaplag/documents/table_fields.h"
#include "flaplag/rotor/hover.h"
#include "flaplag/study.h"

namespace flaplag::cli::json_docs_test {
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
  for (const char* section : {"### ThrustResult", "### FloquetSample"})
    EXPECT_NE(std::string::npos, doc.find(section)) << section;
  for_each_row<FloquetSample>([&](const auto& row) {
    EXPECT_NE(std::string::npos, doc.find("| `" + std::string(row.name) + "` |")) << row.name;
  });
}

TEST(TableFields, CellsOfARowByItsType) {
  PointResult p;
  p.mu = 0.25;
  p.liouville_residual = std::nullopt;
  p.error = 0.5;
  p.stable = true;
  p.status = Status::Warning;
  p.message = "`steps`, too few";
  const auto vocabulary = [](const std::string& m) { return "<" + m + ">"; };
  const std::vector<const char*> keys = {
      "mu", "liouville_residual", "error_estimate", "stable", "status", "message"};
  EXPECT_EQ((std::vector<std::string>{"0.25", "", "0.5", "true", "warning", "<`steps`, too few>"}),
            documents::described_cells(p, keys, documents::CellStyle::Csv, vocabulary));
  EXPECT_EQ((std::vector<std::string>{"0.25", "-", "0.5", "yes", "warning", "<`steps`, too few>"}),
            documents::described_cells(p, keys, documents::CellStyle::Text, vocabulary));
  EXPECT_EQ("0.25,,\"a \"\"b\"\", c\"", documents::csv_fields({"0.25", "", "a \"b\", c"}));
  p.stable = std::nullopt;
  p.liouville_residual = std::numeric_limits<double>::quiet_NaN();  // not representable
  EXPECT_EQ((std::vector<std::string>{"", ""}),
            documents::described_cells(p, {"stable", "liouville_residual"},
                                       documents::CellStyle::Csv, vocabulary));
  EXPECT_EQ((std::vector<std::string>{"-", "-"}),
            documents::described_cells(p, {"stable", "liouville_residual"},
                                       documents::CellStyle::Text, vocabulary));
  EXPECT_THROW(
      documents::described_cells(p, {"no_such_row"}, documents::CellStyle::Csv, vocabulary),
      std::logic_error);
  EXPECT_THROW(documents::described_cells(p, {"exponents"}, documents::CellStyle::Csv, vocabulary),
               std::logic_error);  // a list is no cell
}

TEST(TableFields, ATableOfResults) {
  std::vector<CampbellCrossing> crossings(2);
  crossings[0] = {"lag", 1, 0.5, 0.5};
  crossings[1] = {"flap", 3, 0.25, 0.75};
  const std::string text =
      documents::described_table(crossings,
                                 {{"label", "mode"}, {"harmonic", "n"}, {"speed", "speed"}},
                                 [](const std::string& m) { return m; })
          .render();
  EXPECT_EQ("  mode  n  speed\n  lag   1    0.5\n  flap  3   0.25\n", text);
}

TEST(JsonFields, EveryRowUnderItsKeyInTableOrder) {
  PointResult p;
  p.mu = 0.25;
  p.exponents = {{"flap", -std::numeric_limits<double>::infinity(), 0.5, {0.0, 0.0}, {}}};
  p.error = 1e-7;
  p.status = Status::Warning;
  p.message = "`steps` too small";
  const documents::Json j =
      documents::to_json(p, [](const std::string& m) { return "<" + m + ">"; });
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
            documents::to_json(p, [](const std::string& m) { return "<" + m + ">"; })["notes"][0]);
}

std::vector<std::string> keys_of(const documents::Json& j) {
  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  return keys;
}

std::string same(const std::string& m) { return m; }

// A study document's row is StudyRow's table: every row in order, those a document asks for
// (trim, damping_crossings) null or [] when empty, basis_error only with exact modes.
TEST(JsonFields, StudyRowsAreTheRowsOfTheirTable) {
  StudyRow row;
  row.value = 1.25;
  row.critical.mu_c = 0.5;
  row.critical.mode = "lag";
  row.critical.intervals = {{0.5, std::nullopt, {}, {}, "lag", 0.0, InstabilityKind::Periodic}};
  std::vector<std::string> all;
  for_each_row<StudyRow>([&](const auto& r) { all.push_back(r.name); });
  auto without = [&](std::vector<std::string> names) {
    std::vector<std::string> keys;
    for (const std::string& k : all)
      if (std::find(names.begin(), names.end(), k) == names.end()) keys.push_back(k);
    return keys;
  };
  const documents::Json plain = documents::to_json(row, same);
  EXPECT_EQ(without({"basis_error", "trim", "damping_crossings"}), keys_of(plain));
  EXPECT_EQ(0.5, plain["intervals"][0][0].get<double>());
  EXPECT_TRUE(plain["intervals"][0][1].is_null());
  EXPECT_EQ("lag", plain["mode"]);
  const documents::Json asked = documents::to_json(row, same, {"trim", "damping_crossings"});
  EXPECT_EQ(without({"basis_error"}), keys_of(asked));
  EXPECT_TRUE(asked["trim"].is_null());
  EXPECT_TRUE(asked["damping_crossings"].empty());
  row.critical.basis = 8;
  EXPECT_TRUE(documents::to_json(row, same)["basis_error"].is_null());
  row.critical.mu_c.reset();  // mode, omega, kind: null without mu_c
  EXPECT_TRUE(documents::to_json(row, same)["mode"].is_null());
}

// Hover's rows: numbers by name as an object, a matrix as its rows, the exponents as objects;
// its stability unknown when failed or neutral.
TEST(JsonFields, HoverRowsByType) {
  HoverResult h;
  h.inflow = 0.05;
  h.equilibrium = {{"g0_1", 0.1}, {"h0_1", 0.01}};
  h.A0 = Eigen::MatrixXd::Identity(2, 2);
  h.eigenvalues = {{-0.5, 1.0}};
  h.labels = {"flap"};
  const documents::Json j = documents::to_json(h, same);
  std::vector<std::string> rows;
  for_each_row<HoverResult>([&](const auto& r) { rows.push_back(r.name); });
  EXPECT_EQ(rows, keys_of(j));
  EXPECT_EQ((std::vector<std::string>{"g0_1", "h0_1"}), keys_of(j["equilibrium"]));
  EXPECT_EQ(1.0, j["A0"][1][1].get<double>());
  EXPECT_EQ(0.0, j["A0"][0][1].get<double>());
  EXPECT_EQ("flap", j["exponents"][0]["label"]);
  EXPECT_EQ(1.0, j["exponents"][0]["omega"].get<double>());
  EXPECT_EQ(true, j["stable"].get<bool>());
  h.neutral = true;
  EXPECT_TRUE(documents::to_json(h, same)["stable"].is_null());
  h.neutral = false;
  h.status = Status::Failed;  // Python's hover too: no stability from a failed analysis
  EXPECT_TRUE(documents::to_json(h, same)["stable"].is_null());
  EXPECT_FALSE(hover_stable(h).has_value());
  const documents::Json doc = documents::rows_json(h, {"inflow", "stable"}, same);
  EXPECT_EQ((std::vector<std::string>{"inflow", "stable"}), keys_of(doc));
  EXPECT_THROW(documents::rows_json(h, {"no_such_row"}, same), std::logic_error);
}

// A text table's heading is the row's key with its units, where the row has units.
TEST(TableFields, HeadingsCarryTheUnits) {
  EXPECT_EQ("zeta [1/rev]", documents::described_heading<LabelledExponent>("zeta"));
  EXPECT_EQ("omega [per rev]", documents::described_heading<HoverExponent>("omega"));
  EXPECT_EQ("label", documents::described_heading<LabelledExponent>("label"));
  EXPECT_EQ("damping_ratio", documents::described_heading<LabelledExponent>("damping_ratio"));
  EXPECT_THROW(documents::described_heading<LabelledExponent>("no_such_row"), std::logic_error);
}

}  // namespace
}  // namespace flaplag::cli::json_docs_test
