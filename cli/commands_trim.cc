// flaplag CLI — trim (trim.h): `flaplag trim`, and the trim shown by point, sweep, critical and
// study under --trim.
#include <string>

#include "commands_internal.h"
#include "flaplag/core/format.h"
#include "flaplag/documents/output.h"
#include "flaplag/trim.h"

namespace flaplag::cli::cmd {

// ---- trim (trim.h) ----------------------------------------------------------------------------

bool trimmed(const Request& r) { return r.trim.kind != TrimKind::None; }

// One vocabulary for `flaplag trim`, the trim of point/sweep/critical --trim and of study rows,
// and the Python module's TrimResult: TrimResult's table (trim.h).  (The trimmed rotor's
// parameters are the header's for `flaplag trim`; alpha_R is the case's shaft_angle.)
Json trim_json(const Request& r, const TrimResult& t) { return to_json(t, in_vocabulary(r)); }

Json equilibrium_json(const Request& r, const PeriodicEquilibrium& q) {
  // A failed q° has no truncation to report: its K and a 0 would read as a perfect one.
  if (q.status == Status::Failed) return Json(nullptr);
  return to_json(TrimEquilibrium{q.harmonics, q.truncation}, in_vocabulary(r));
}

std::string trim_text(const Request& r, const TrimResult& t) {
  std::string out = std::string("Trim (") + trim_kind_name(t.kind) + ") at mu = " + cell(t.mu) +
                    ", C_T = " + cell(t.target) + ", alpha_R = " + cell(r.trim.shaft_angle) +
                    " rad\n";
  KeyValues kv;
  kv.add("theta0", cell(t.theta0) + " rad");
  kv.add("theta1c", cell(t.theta1c) + " rad");
  kv.add("theta1s", cell(t.theta1s) + " rad");
  kv.add("lambda", cell(t.inflow) + "  (eq 2.25)");
  kv.add("C_T achieved", cell(t.thrust_coefficient) + "  (the model's own lift, azimuth mean)");
  kv.add("flap tip 1st harmonic", cell(t.flap_1c) + " cos psi + " + cell(t.flap_1s) + " sin psi");
  if (t.linearization == Linearization::PeriodicEquilibrium) {
    kv.add("trimmed about",
           "the periodic equilibrium of the nonlinear equations (harmonic "
           "balance, K = " +
               std::to_string(t.equilibrium.harmonics) + "; last harmonic " +
               cell(t.equilibrium.truncation) + " of the largest)");
  }
  kv.add("iterations", std::to_string(t.iterations));
  out += kv.render();
  return out + status_text(t.status, vocab(r, t.message));
}

Output trim_command(const Request& r) {
  const TrimResult t = trim(r.params, r.mu, r.trim, nullptr, r.linearization);
  const auto json = [&] {
    Json j =
        header_json("trim", Analysis(t.parameters, r.transition, OperatingCondition::At(t)), false);
    j.update(trim_json(r, t));
    return j;
  };
  std::optional<Json> j = result_document(r, json, nullptr);
  if (r.json) return std::move(*j);
  return text_output(r, trim_text(r, t), std::move(j));
}

}  // namespace flaplag::cli::cmd
