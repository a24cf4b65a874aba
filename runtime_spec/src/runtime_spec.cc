// flaplag — ordering specs derived at run time (runtime_spec.h).
#include "flaplag_spec/runtime_spec.h"

#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include "flaplag/core/errors.h"
#include "flaplag_derive/derive.h"
#include "flaplag_derive/emit.h"
#include "flaplag_derive/generic.h"
#include "flaplag_derive/spec.h"
#include "interpreter.h"

namespace flaplag::spec {

namespace {

constexpr std::uintmax_t kMaxSpecBytes = 1 << 20;

// A family made at run time: the ModelFamily and everything its pointers refer to.
struct RunTimeFamily {
  RunTimeFamily(derive::OrderingSpec s, const derive::GenericModel& g)
      : spec(std::move(s)), program(g), generic(g) {}
  derive::OrderingSpec spec;
  Program program;
  derive::GenericModel generic;  // for the audit report
  std::string name, file, text, summary;
  double seconds = 0.0;
  model::ModelFamily family{};
};

const Program& program(const model::CoefficientInputs& in) {
  if (in.context == nullptr)
    throw std::logic_error("a run-time model called without its context (CoefficientInputs)");
  return static_cast<const RunTimeFamily*>(in.context)->program;
}

void mass(const model::CoefficientInputs& in, double* out) { program(in).mass(in, out); }
void coefficients(const model::CoefficientInputs& in, const model::CoefficientOutputs& out) {
  program(in).coefficients(in, out);
}
void equilibrium(const model::CoefficientInputs& in, const model::EquilibriumOutputs& out) {
  program(in).equilibrium(in, out);
}
void thrust(const model::CoefficientInputs& in, const model::CoefficientOutputs& out) {
  program(in).thrust(in, out);
}
void nonlinear(const model::CoefficientInputs& in, const double* y,
               const model::NonlinearOutputs& out) {
  program(in).nonlinear(in, y, out);
}
void nonlinear_thrust(const model::CoefficientInputs& in, const double* y,
                      const model::NonlinearOutputs& out) {
  program(in).nonlinear_thrust(in, y, out);
}

// The family summary of the emitted code: the spec's summary without its mode counts.
std::string family_summary(const derive::OrderingSpec& s) {
  const std::string text = s.summary();
  const auto semi = text.find("; ");
  return semi == std::string::npos ? text : text.substr(semi + 2);
}

struct Loaded {
  std::mutex mutex;  // also serializes GiNaC, which is not thread-safe
  std::deque<std::unique_ptr<RunTimeFamily>> families;
};
Loaded& loaded() {
  static Loaded* l = new Loaded;  // never destroyed: registered families live to the end
  return *l;
}

const RunTimeFamily* find_loaded(const model::ModelFamily& f) {
  for (const auto& r : loaded().families)
    if (&r->family == &f) return r.get();
  return nullptr;
}

}  // namespace

bool available() { return true; }

const model::ModelFamily& load_spec(const std::string& path) {
  Loaded& l = loaded();
  const std::lock_guard<std::mutex> lock(l.mutex);
  // A spec is a few lines: refuse what is not a regular file of sensible size before reading
  // (a FIFO or /dev/zero would never end).
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st))
    throw InvalidInput("spec", path, ec ? "cannot be read: " + ec.message() : "no such file");
  if (!std::filesystem::is_regular_file(st)) throw InvalidInput("spec", path, "not a regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxSpecBytes)
    throw InvalidInput(
        "spec", path,
        "larger than " + std::to_string(kMaxSpecBytes) + " bytes (a spec is a few lines)");
  derive::OrderingSpec s;
  try {
    s = derive::load_spec(path);
  } catch (const derive::SpecError& e) {
    throw InvalidInput("spec", path, e.what());
  }
  const std::string name = "spec:" + s.name;
  const std::string text = s.canonical_text();
  for (const auto& r : l.families) {
    if (r->name != name) continue;
    if (r->text == text) return r->family;
    throw InvalidInput("spec", path,
                       "another spec named " + s.name + " (" + r->file +
                           ") is loaded already: give this one another file name");
  }
  const auto start = std::chrono::steady_clock::now();
  derive::GenericModel g;
  try {
    g = derive::extract_generic(s);
  } catch (const derive::SpecError& e) {
    throw InvalidInput("spec", path, e.what());
  } catch (const std::exception& e) {
    // a spec the generator cannot turn into a family (its limits, e.g. kMaxFactors)
    throw InvalidInput("spec", path, std::string("cannot be derived: ") + e.what());
  }
  auto r = std::make_unique<RunTimeFamily>(s, g);
  r->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r->name = name;
  r->file = s.file;
  r->text = text;
  r->summary = family_summary(s);
  model::ModelFamily& f = r->family;
  f.name = r->name.c_str();
  f.spec_file = r->file.c_str();
  f.spec_text = r->text.c_str();
  f.summary = r->summary.c_str();
  f.default_flap_modes = s.flap_modes;
  f.default_lag_modes = s.lag_modes;
  f.n_harmonics = g.H;
  f.n_nonlinear_harmonics = g.H_nonlinear;
  f.n_aero = static_cast<int>(r->program.aero().size());
  f.aero = r->program.aero().data();
  f.n_structural = static_cast<int>(r->program.structural().size());
  f.structural = r->program.structural().data();
  f.mass = &mass;
  f.coefficients = &coefficients;
  f.equilibrium = &equilibrium;
  f.thrust = &thrust;
  f.nonlinear = &nonlinear;
  f.nonlinear_thrust = &nonlinear_thrust;
  f.context = r.get();
  f.n_linear_aero = derive::linear_aero_templates(g);
  try {
    model::register_family(f);
  } catch (const std::invalid_argument& e) {
    throw InvalidInput("spec", path, e.what());
  }
  l.families.push_back(std::move(r));
  return f;
}

double derivation_seconds(const model::ModelFamily& f) {
  const std::lock_guard<std::mutex> lock(loaded().mutex);
  const RunTimeFamily* r = find_loaded(f);
  return r != nullptr ? r->seconds : 0.0;
}

std::string audit_report(const std::string& name) {
  const std::lock_guard<std::mutex> lock(loaded().mutex);
  const RunTimeFamily* r = nullptr;
  for (const auto& l : loaded().families)
    if (l->name == name) r = l.get();
  if (r == nullptr) throw InvalidInput("spec", name, "not a spec loaded at run time");
  // As flaplag-derive writes <name>.md: the paper layout at the spec's modes (every feature
  // on), then the family's terms.
  derive::OrderingSpec concrete = r->spec;
  concrete.cyclic_pitch = true;
  concrete.nonlinear = true;
  return derive::emit_report(derive::derive_model(concrete)) +
         derive::emit_family_report(r->generic);
}

}  // namespace flaplag::spec
