// flaplag CLI — `flaplag campbell` (campbell.h): the modes' frequencies against the rotor speed,
// as a table, JSON (CampbellResult's table) and a picture.
#include <cmath>
#include <string>
#include <vector>

#include "commands_internal.h"
#include "flaplag/campbell.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/output.h"

namespace flaplag::cli::cmd {

namespace {

std::string campbell_text(const Request& r, const Analysis& an, const CampbellResult& c) {
  std::string out = header_text(an) + "\n";
  out += "Campbell diagram at mu = " + num(c.mu) +
         ": each mode's frequency omega/Omega_0 [per rev at Omega_0] against the rotor speed "
         "Omega/Omega_0\n(the blade's first rotating frequencies by Omega: centrifugal stiffening "
         "of its bending stiffness at Omega_0)\n";
  std::vector<std::string> head = {"Omega/Omega_0", "omega_F1", "omega_L1"};
  for (const std::string& l : c.labels) head.push_back(l);
  head.push_back("status");
  TextTable t(head);
  t.left_align(head.size() - 1);
  for (const CampbellPoint& pt : c.points) {
    std::vector<std::string> row = {num(pt.speed), cell(pt.omega_flap), cell(pt.omega_lag)};
    for (std::size_t m = 0; m < c.labels.size(); ++m)
      row.push_back(m < pt.modes.size() ? cell(pt.modes[m].frequency) : "-");
    row.push_back(status_name(pt.status));
    t.add_row(row);
  }
  out += t.render();
  if (!c.points.empty()) out += notes_text(r, c.points.front().notes);
  out += "\nCrossings with the per-rev lines n Omega (n = 1.." + std::to_string(c.harmonics) +
         "; linear between the speeds around them)\n";
  if (c.crossings.empty()) {
    out += "  none\n";
  } else {
    out += described_table(c.crossings,
                           {{"label", "mode"},
                            {"harmonic", "n"},
                            {"speed", "Omega/Omega_0"},
                            {"frequency", "omega/Omega_0"}},
                           in_vocabulary(r))
               .render();
  }
  return out + status_text(c.status, vocab(r, c.message));
}

}  // namespace

Output campbell(const Request& r, const Analysis& an, std::string& warning) {
  CampbellOptions options = r.campbell;
  options.threads = r.threads;
  const CampbellResult c = campbell_diagram(r.params, r.transition, options);
  const auto json = [&] {
    Json j = header_json("campbell", an);
    j.update(to_json(c, in_vocabulary(r)));
    return j;
  };
  std::optional<Json> j = result_document(r, json, &warning);
  if (r.json) return std::move(*j);
  return text_output(r, campbell_text(r, an, c), std::move(j));
}

}  // namespace flaplag::cli::cmd
