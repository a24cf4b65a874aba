// flaplag CLI — the equations themselves: `flaplag system` (A(psi), f(psi), the spanwise
// integrals at one azimuth) and `flaplag models` (the compiled ordering models and their specs).
#include <string>
#include <vector>

#include "commands_internal.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/output.h"

namespace flaplag::cli::cmd {

namespace {

// The document: SystemSnapshot's rows, the hover after f(psi).
Json system_json(const Request& r, const Analysis& an, const SystemSnapshot& s) {
  const MessageText message = in_vocabulary(r);
  Json j = header_json("system", an, false);
  j.update(rows_json(s, {"mu", "psi", "region", "state", "A", "f"}, message));
  j["hover"] = hover_json(r, an);
  j.update(rows_json(s, {"aero_integrals", "structural_integrals", "status", "message"}, message));
  return j;
}

// The table of A(psi), with f(psi) as its last column.
std::string matrix_text(const SystemSnapshot& s) {
  auto state = [&](Eigen::Index i) {
    return i < static_cast<Eigen::Index>(s.states.size()) ? s.states[static_cast<std::size_t>(i)]
                                                          : std::to_string(i);
  };
  std::vector<std::string> header{"row"};
  for (Eigen::Index k = 0; k < s.A.cols(); ++k) header.push_back(state(k));
  header.push_back("f(psi)");
  TextTable t(header);
  for (Eigen::Index i = 0; i < s.A.rows(); ++i) {
    std::vector<std::string> row{state(i) + "'"};
    for (Eigen::Index k = 0; k < s.A.cols(); ++k) row.push_back(cell(s.A(i, k)));
    row.push_back(i < s.f.size() ? cell(s.f[i]) : "");
    t.add_row(row);
  }
  return t.render();
}

std::string integrals_text(const SystemSnapshot& s) {
  auto paper = [](const std::string& name) { return name.empty() ? "-" : name; };
  std::string out = "Aerodynamic spanwise integrals (int x^p ... dx0 over the aerodynamic span)\n";
  TextTable a({"integral", "paper", "normal flow", "used at psi"});
  a.left_align(1);
  for (const AeroIntegral& x : snapshot_aero_integrals(s))
    a.add_row({x.name, paper(x.paper_name), cell(x.normal), x.at_psi ? cell(*x.at_psi) : "-"});
  out += a.render() + "\nGeneralized masses and structural integrals (by I_b)\n";
  TextTable g({"integral", "paper", "value"});
  g.left_align(1);
  for (const StructuralIntegral& x : snapshot_structural_integrals(s))
    g.add_row({x.name, paper(x.paper_name), cell(x.value)});
  return out + g.render();
}

std::string system_text(const Request& r, const Analysis& an, const SystemSnapshot& s) {
  std::string out = header_text(an, false) + "\n" + warnings_text(an);
  out += "System y' = A(psi) y + f(psi) at mu = " + num(s.mu) + ", psi = " + cell(s.psi) +
         " rad: " + s.region + " flow region\n";
  std::string state_list;
  for (const std::string& x : s.states) state_list += (state_list.empty() ? "" : ", ") + x;
  out += "  state y = [" + state_list + "]\n\nA(psi)\n";
  out +=
      matrix_text(s) + status_text(s.status, vocab(r, s.message)) + "\n" + hover_text(r, an) + "\n";
  return out + integrals_text(s);
}

}  // namespace

Output system_snapshot(const Request& r, const Analysis& an) {
  const SystemSnapshot s = an.snapshot(r.mu, r.psi);
  std::optional<Json> j = result_document(
      r, [&] { return system_json(r, an, s); }, nullptr);
  if (r.json) return std::move(*j);
  return text_output(r, system_text(r, an, s), std::move(j));
}

Output models(const Request& r) {
  if (!r.spec.empty()) {
    const model::ModelDescriptor& m = find_model(r.spec);
    if (r.json) {
      return Json{{"name", m.name}, {"spec_file", m.spec_file}, {"spec_text", m.spec_text}};
    }
    std::string text = m.spec_text;
    if (!text.empty() && text.back() != '\n') text += '\n';
    return text;
  }
  // Each model is listed at its spec's mode counts; every other M x N is made on demand.
  if (r.json) {
    Json list = Json::array();
    for (const model::ModelDescriptor* m : compiled_models()) list.push_back(model_json(*m));
    return Json{{"command", "models"},
                {"models", list},
                {"max_modes", model::kMaxModes},
                {"modes",
                 "each model also as <model>-<M>x<N> for M flap x N lag exact modes, "
                 "1 <= M, N <= " +
                     std::to_string(model::kMaxModes)}};
  }
  TextTable t({"model", "spec file", "modes", "summary"});
  t.left_align(1);
  t.left_align(3);
  for (const model::ModelDescriptor* m : compiled_models()) {
    t.add_row({m->name, m->spec_file,
               std::to_string(m->flap_modes) + "x" + std::to_string(m->lag_modes), m->summary});
  }
  return "Compiled ordering models, one per spec (flaplag --model NAME; flaplag models --spec "
         "NAME)\n" +
         t.render() + "\nEach model also exists for M flap x N lag exact modes, 1 <= M, N <= " +
         std::to_string(model::kMaxModes) +
         ":\n<model>-<M>x<N>, e.g. paper-4x2 (or --modes exact --flap-modes M --lag-modes N).\n";
}

}  // namespace flaplag::cli::cmd
