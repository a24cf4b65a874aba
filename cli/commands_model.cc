// flaplag CLI — the equations themselves: `flaplag system` (A(psi), f(psi), the spanwise
// integrals at one azimuth) and `flaplag models` (the compiled ordering models and their specs).
#include <string>
#include <vector>

#include "commands_internal.h"
#include "flaplag/core/format.h"
#include "output.h"

namespace flaplag::cli::cmd {

namespace {

std::vector<std::string> state_names(int M, int N) {
  std::vector<std::string> s;
  for (int col = 0; col < 2 * (M + N); ++col) s.push_back(model::state_name(col, M, N));
  return s;
}

// Paper (Appendix B) name of an integral, looked up by its canonical name.
template <typename Integral>
std::string paper_name(const Integral* list, int n, const std::string& name) {
  for (int i = 0; i < n; ++i) {
    if (name == list[i].name) return list[i].paper_name;
  }
  return "";
}

void add_integrals_json(const SystemSnapshot& s, const model::ModelDescriptor& m, Json& j) {
  Json aero = Json::array();
  for (std::size_t i = 0; i < s.aero_integrals.size(); ++i) {
    const std::string& name = s.aero_integrals[i].first;
    Json a{{"name", name},
           {"paper_name", paper_name(m.aero, m.n_aero, name)},
           {"normal", jnum(s.aero_integrals[i].second)}};
    a["at_psi"] = i < s.aero_integrals_region.size() ? jnum(s.aero_integrals_region[i].second)
                                                     : Json(nullptr);
    aero.push_back(a);
  }
  j["aero_integrals"] = aero;
  Json st = Json::array();
  for (const auto& [name, value] : s.structural_integrals) {
    st.push_back(Json{{"name", name},
                      {"paper_name", paper_name(m.structural, m.n_structural, name)},
                      {"value", jnum(value)}});
  }
  j["structural_integrals"] = st;
}

Json system_json(const Request& r, const Analysis& an, const SystemSnapshot& s, Status status,
                 const std::string& message) {
  const model::ModelDescriptor& m = an.model();
  Json j = header_json("system", an, false);
  j["mu"] = s.mu;
  j["psi"] = jnum(s.psi);
  j["region"] = s.region;
  j["state"] = state_names(m.flap_modes, m.lag_modes);
  Json A = Json::array();
  for (Eigen::Index i = 0; i < s.A.rows(); ++i) {
    Json row = Json::array();
    for (Eigen::Index k = 0; k < s.A.cols(); ++k) row.push_back(jnum(s.A(i, k)));
    A.push_back(row);
  }
  j["A"] = A;
  Json f = Json::array();
  for (Eigen::Index i = 0; i < s.f.size(); ++i) f.push_back(jnum(s.f[i]));
  j["f"] = f;
  j["hover"] = hover_json(r, an);
  add_integrals_json(s, m, j);
  return status_json(j, status, message);
}

// The table of A(psi), with f(psi) as its last column.
std::string matrix_text(const SystemSnapshot& s, const std::vector<std::string>& states) {
  auto state = [&](Eigen::Index i) {
    return i < static_cast<Eigen::Index>(states.size()) ? states[static_cast<std::size_t>(i)]
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

std::string integrals_text(const SystemSnapshot& s, const model::ModelDescriptor& m) {
  std::string out = "Aerodynamic spanwise integrals (int x^p ... dx0 over the aerodynamic span)\n";
  TextTable a({"integral", "paper", "normal flow", "used at psi"});
  a.left_align(1);
  for (std::size_t i = 0; i < s.aero_integrals.size(); ++i) {
    const std::string& name = s.aero_integrals[i].first;
    const std::string pn = paper_name(m.aero, m.n_aero, name);
    a.add_row({name, pn.empty() ? "-" : pn, cell(s.aero_integrals[i].second),
               i < s.aero_integrals_region.size() ? cell(s.aero_integrals_region[i].second) : "-"});
  }
  out += a.render() + "\nGeneralized masses and structural integrals (by I_b)\n";
  TextTable g({"integral", "paper", "value"});
  g.left_align(1);
  for (const auto& [name, value] : s.structural_integrals) {
    const std::string pn = paper_name(m.structural, m.n_structural, name);
    g.add_row({name, pn.empty() ? "-" : pn, cell(value)});
  }
  return out + g.render();
}

std::string system_text(const Request& r, const Analysis& an, const SystemSnapshot& s,
                        Status status, const std::string& message) {
  const model::ModelDescriptor& m = an.model();
  const std::vector<std::string> states = state_names(m.flap_modes, m.lag_modes);
  std::string out = header_text(an, false) + "\n" + warnings_text(an);
  out += "System y' = A(psi) y + f(psi) at mu = " + num(s.mu) + ", psi = " + cell(s.psi) +
         " rad: " + s.region + " flow region\n";
  std::string state_list;
  for (const std::string& x : states) state_list += (state_list.empty() ? "" : ", ") + x;
  out += "  state y = [" + state_list + "]\n\nA(psi)\n";
  out += matrix_text(s, states) + status_text(status, message) + "\n" + hover_text(r, an) + "\n";
  return out + integrals_text(s, m);
}

}  // namespace

Output system_snapshot(const Request& r, const Analysis& an) {
  const SystemSnapshot s = an.snapshot(r.mu, r.psi);
  std::optional<Json> j = result_document(
      r, [&] { return system_json(r, an, s, s.status, s.message); }, nullptr);
  if (r.json) return std::move(*j);
  return text_output(r, system_text(r, an, s, s.status, s.message), std::move(j));
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
