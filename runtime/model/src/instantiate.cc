// flaplag — descriptors of the model families for given mode counts (model_api.h).
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "flaplag/model_api.h"

namespace flaplag::model {

namespace {

// A descriptor with the storage its pointers refer to.
struct Instance {
  ModelDescriptor descriptor{};
  std::string name, summary;
  std::deque<std::string> texts;  // integral names, identifiers and paper names (stable)
  std::vector<AeroIntegral> aero;
  std::vector<StructuralIntegral> structural;

  const char* keep(std::string s) {
    texts.push_back(std::move(s));
    return texts.back().c_str();
  }
};

std::string mode_text(int m) { return m <= 9 ? std::to_string(m) : "(" + std::to_string(m) + ")"; }

bool is_var(char ch, const std::vector<int>& modes) {
  return ch >= 'a' && ch < 'a' + static_cast<char>(modes.size());
}

// Integral name: "x eta_a eta_b'" with a = 0, b = 1 -> "x eta1 eta2'" (mode numbers 1-based,
// above 9 in parentheses so that the name stays unambiguous).
std::string concrete_name(const char* text, const std::vector<int>& modes) {
  std::string out;
  const std::string s = text;
  for (size_t j = 0; j < s.size(); ++j) {
    if (s[j] == '_' && j + 1 < s.size() && is_var(s[j + 1], modes) &&
        (j + 2 == s.size() || s[j + 2] == ' ' || s[j + 2] == '\'' || s[j + 2] == ']')) {
      out += mode_text(modes[static_cast<size_t>(s[j + 1] - 'a')] + 1);
      ++j;
      continue;
    }
    out += s[j];
  }
  return out;
}

// Paper name: the trailing letters of each '/'-separated part are the subscripts,
// "F6_ab" -> "F6_12", "M_Faa" -> "M_F11".
std::string concrete_paper_name(const char* text, const std::vector<int>& modes) {
  std::string out, part;
  std::string s = text;
  size_t start = 0;
  while (start <= s.size()) {
    const size_t slash = s.find('/', start);
    part = s.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    size_t e = part.size();
    while (e > 0 && is_var(part[e - 1], modes) && part.find('_') < e - 1) --e;
    std::string p = part.substr(0, e);
    for (size_t j = e; j < part.size(); ++j)
      p += mode_text(modes[static_cast<size_t>(part[j] - 'a')] + 1);
    out += (out.empty() ? "" : "/") + p;
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return out;
}

// Identifier: factor segments end in their letter, "x1_etaa_detab" -> "x1_eta1_deta2".
std::string concrete_ident(const char* ident, const std::vector<int>& modes) {
  std::string out;
  const std::string s = ident;
  size_t start = 0;
  while (start <= s.size()) {
    const size_t us = s.find('_', start);
    std::string seg = s.substr(start, us == std::string::npos ? std::string::npos : us - start);
    const bool factor = seg.rfind("eta", 0) == 0 || seg.rfind("deta", 0) == 0 ||
                        seg.rfind("gam", 0) == 0 || seg.rfind("dgam", 0) == 0;
    if (factor && !seg.empty() && is_var(seg.back(), modes)) {
      const int m = modes[static_cast<size_t>(seg.back() - 'a')] + 1;
      seg = seg.substr(0, seg.size() - 1) + std::to_string(m);
    }
    out += seg;
    if (us == std::string::npos) break;
    out += '_';
    start = us + 1;
  }
  return out;
}

FactorRef concrete_factor(const FactorRef& f, const std::vector<int>& modes) {
  return {f.kind, has_mode(f.kind) ? modes[static_cast<size_t>(f.mode)] : 0};
}

// Calls f(modes) for every assignment of the template's variables, row-major (variable 0
// slowest): the order of TemplateTensors.
template <class F>
void for_each_assignment(const IntegralTemplate& t, int M, int N, F f) {
  std::vector<int> modes(static_cast<size_t>(t.n_vars), 0);
  const int total = template_size(t, M, N);
  for (int flat = 0; flat < total; ++flat) {
    int rest = flat;
    for (int v = t.n_vars - 1; v >= 0; --v) {
      const int d = t.var_dirs[v] == Direction::Flap ? M : N;
      modes[static_cast<size_t>(v)] = rest % d;
      rest /= d;
    }
    f(modes);
  }
}

std::unique_ptr<Instance> make(const ModelFamily& f, int M, int N) {
  auto in = std::make_unique<Instance>();
  const bool named = M == f.default_flap_modes && N == f.default_lag_modes;
  in->name = named ? std::string(f.name)
                   : std::string(f.name) + "-" + std::to_string(M) + "x" + std::to_string(N);
  in->summary = in->name + ": " + std::to_string(M) + " flap x " + std::to_string(N) +
                " lag modes; " + f.summary;
  std::size_t linear_aero = 0;  // concrete integrals of the first f.n_linear_aero templates
  for (int j = 0; j < f.n_aero; ++j) {
    const IntegralTemplate& t = f.aero[j];
    if (j == f.n_linear_aero) linear_aero = in->aero.size();
    for_each_assignment(t, M, N, [&](const std::vector<int>& modes) {
      AeroIntegral a{};
      a.name = in->keep(concrete_name(t.name, modes));
      a.ident = in->keep(concrete_ident(t.ident, modes));
      a.x_power = t.x_power;
      a.n_factors = t.n_factors;
      for (int k = 0; k < t.n_factors; ++k) a.factors[k] = concrete_factor(t.factors[k], modes);
      a.paper_name = in->keep(concrete_paper_name(t.paper_name, modes));
      in->aero.push_back(a);
    });
  }
  for (int j = 0; j < f.n_structural; ++j) {
    const IntegralTemplate& t = f.structural[j];
    for_each_assignment(t, M, N, [&](const std::vector<int>& modes) {
      StructuralIntegral s{};
      s.name = in->keep(concrete_name(t.name, modes));
      s.ident = in->keep(concrete_ident(t.ident, modes));
      s.outer_mass = t.outer_mass;
      s.n_outer = t.n_factors;
      for (int k = 0; k < t.n_factors; ++k) s.outer[k] = concrete_factor(t.factors[k], modes);
      s.inner = t.inner;
      s.inner_mass = t.inner_mass;
      s.n_inner = t.n_inner;
      for (int k = 0; k < t.n_inner; ++k)
        s.inner_factors[k] = concrete_factor(t.inner_factors[k], modes);
      s.paper_name = in->keep(concrete_paper_name(t.paper_name, modes));
      in->structural.push_back(s);
    });
  }
  ModelDescriptor& d = in->descriptor;
  d.name = in->name.c_str();
  d.base = f.name;
  d.spec_file = f.spec_file;
  d.spec_text = f.spec_text;
  d.summary = in->summary.c_str();
  d.flap_modes = M;
  d.lag_modes = N;
  d.n_harmonics = f.n_harmonics;
  d.n_aero = static_cast<int>(in->aero.size());
  d.aero = in->aero.data();
  d.n_structural = static_cast<int>(in->structural.size());
  d.structural = in->structural.data();
  d.mass = f.mass;
  d.coefficients = f.coefficients;
  d.equilibrium = f.equilibrium;
  d.thrust = f.thrust;
  d.n_nonlinear_harmonics = f.n_nonlinear_harmonics;
  d.nonlinear = f.nonlinear;
  d.nonlinear_thrust = f.nonlinear_thrust;
  d.context = f.context;
  d.n_linear_aero = f.n_linear_aero > 0 && f.n_linear_aero < f.n_aero
                        ? static_cast<int>(linear_aero)
                        : static_cast<int>(in->aero.size());
  return in;
}

}  // namespace

const ModelDescriptor& instantiate(const ModelFamily& f, int M, int N) {
  if (M < 1 || M > kMaxModes || N < 1 || N > kMaxModes) {
    throw std::invalid_argument("mode counts " + std::to_string(M) + " x " + std::to_string(N) +
                                " outside 1.." + std::to_string(kMaxModes));
  }
  static std::mutex mutex;
  static std::map<std::tuple<const ModelFamily*, int, int>, std::unique_ptr<Instance>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[{&f, M, N}];
  if (!slot) slot = make(f, M, N);
  return slot->descriptor;
}

namespace {

// The families registered at run time, under their lock.
struct RunTimeFamilies {
  std::mutex mutex;
  std::vector<const ModelFamily*> families;
};
RunTimeFamilies& run_time_families() {
  static RunTimeFamilies r;
  return r;
}

}  // namespace

void register_family(const ModelFamily& f) {
  RunTimeFamilies& r = run_time_families();
  const std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<const ModelFamily*> all = compiled_families();
  all.insert(all.end(), r.families.begin(), r.families.end());
  for (const ModelFamily* g : all) {
    if (std::string(g->name) == f.name)
      throw std::invalid_argument("a model family named " + std::string(f.name) + " exists");
  }
  r.families.push_back(&f);
}

std::vector<const ModelFamily*> registered_families() {
  std::vector<const ModelFamily*> out = compiled_families();
  RunTimeFamilies& r = run_time_families();
  const std::lock_guard<std::mutex> lock(r.mutex);
  out.insert(out.end(), r.families.begin(), r.families.end());
  return out;
}

std::vector<const ModelDescriptor*> registered_models() {
  std::vector<const ModelDescriptor*> out;
  for (const ModelFamily* f : compiled_families())
    out.push_back(&instantiate(*f, f->default_flap_modes, f->default_lag_modes));
  return out;
}

}  // namespace flaplag::model
