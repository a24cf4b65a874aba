// Ordering specs at run time (runtime_spec/): the interpreted family of a shipped spec gives
// the numbers of its compiled family, a user's spec in a scratch directory runs, and a bad spec
// is one line.
#include "flaplag_spec/runtime_spec.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "flaplag/analysis.h"
#include "flaplag/core/errors.h"
#include "flaplag/model_api.h"

namespace runtime_spec_test {

namespace {

namespace fm = flaplag::model;
// The directions' places in the per-direction model inputs.
constexpr int kF = fm::index(fm::Direction::Flap), kL = fm::index(fm::Direction::Lag);
namespace fs = std::filesystem;

const fm::ModelFamily& compiled(const std::string& name) {
  for (const fm::ModelFamily* f : fm::compiled_families())
    if (name == f->name) return *f;
  throw std::runtime_error("no compiled family " + name);
}

std::string shipped(const std::string& name) {
  return std::string(FLAPLAG_SPEC_DIR) + "/" + name + ".toml";
}

// Random inputs of the right sizes for M x N (the integral values too: the functions only
// combine them).
struct Inputs {
  Inputs(const fm::ModelFamily& f, int M, int N, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto fill = [&](std::vector<double>& v, std::size_t n) {
      v.resize(n);
      for (double& x : v) x = u(rng);
    };
    std::size_t n_aero = 0, n_structural = 0;
    for (int j = 0; j < f.n_aero; ++j)
      n_aero += static_cast<std::size_t>(fm::template_size(f.aero[j], M, N));
    for (int j = 0; j < f.n_structural; ++j)
      n_structural += static_cast<std::size_t>(fm::template_size(f.structural[j], M, N));
    const auto m = static_cast<std::size_t>(M), n = static_cast<std::size_t>(N);
    fill(g0, m), fill(h0, n), fill(omega_flap, m), fill(omega_lag, n), fill(damping_flap, m);
    fill(damping_lag, n), fill(es_flap, m * m), fill(es_lag, n * n), fill(ecs_flap_lag, m * n);
    fill(ecs_lag_flap, n * m), fill(aero, n_aero), fill(structural, n_structural);
    fill(y, 2 * (m + n));
    in.lock = 5.0 + u(rng);
    in.lr = 0.9 + 0.1 * u(rng);
    in.theta = 0.2 * u(rng);
    in.inflow = 0.05 * u(rng);
    in.precone = 0.05 * u(rng);
    in.droop = 0.05 * u(rng);
    in.cdo_a = 0.002 * (1.0 + u(rng));
    in.mu = 0.5 + 0.4 * u(rng);
    in.theta1c = 0.1 * u(rng);
    in.theta1s = 0.1 * u(rng);
    in.q0[kF] = g0.data(), in.q0[kL] = h0.data(), in.omega[kF] = omega_flap.data();
    in.omega[kL] = omega_lag.data(), in.damping[kF] = damping_flap.data();
    in.damping[kL] = damping_lag.data(), in.elastic[kF][kF] = es_flap.data();
    in.elastic[kL][kL] = es_lag.data(), in.elastic[kF][kL] = ecs_flap_lag.data();
    in.elastic[kL][kF] = ecs_lag_flap.data();
    in.aero = aero.data(), in.structural = structural.data();
    in.modes[kF] = M;
    in.modes[kL] = N;
  }
  std::vector<double> g0, h0, omega_flap, omega_lag, damping_flap, damping_lag, es_flap, es_lag,
      ecs_flap_lag, ecs_lag_flap, aero, structural, y;
  fm::CoefficientInputs in{};
};

// Every element within 1e-13 relative (of the larger magnitude; both zero is equal).
void expect_close(const std::vector<double>& compiled_out, const std::vector<double>& run_time,
                  const std::string& what) {
  ASSERT_EQ(compiled_out.size(), run_time.size()) << what;
  int nonzero = 0;
  for (std::size_t k = 0; k < compiled_out.size(); ++k) {
    const double a = compiled_out[k], b = run_time[k];
    nonzero += a != 0.0;
    EXPECT_LE(std::abs(a - b), 1e-13 * std::max(std::abs(a), std::abs(b)))
        << what << " element " << k << ": compiled " << a << ", run time " << b;
  }
  EXPECT_GT(nonzero, 0) << what << ": all zero, nothing compared";
}

class SpecFamilies : public ::testing::TestWithParam<std::string> {};

TEST_P(SpecFamilies, InterpreterGivesTheNumbersOfTheCompiledFamily) {
  const std::string name = GetParam();
  const fm::ModelFamily& c = compiled(name);
  const fm::ModelFamily& r = flaplag::spec::load_spec(shipped(name));
  EXPECT_EQ(std::string(r.name), "spec:" + name);
  EXPECT_STREQ(r.spec_text, c.spec_text);
  ASSERT_EQ(r.n_aero, c.n_aero);
  ASSERT_EQ(r.n_structural, c.n_structural);
  for (int j = 0; j < c.n_aero; ++j) EXPECT_STREQ(r.aero[j].name, c.aero[j].name);
  for (int j = 0; j < c.n_structural; ++j) EXPECT_STREQ(r.structural[j].name, c.structural[j].name);
  ASSERT_EQ(r.n_harmonics, c.n_harmonics);
  ASSERT_EQ(r.n_nonlinear_harmonics, c.n_nonlinear_harmonics);
  const int H = c.n_harmonics, Hn = c.n_nonlinear_harmonics;
  unsigned seed = 1;
  for (const auto& [M, N] : {std::pair{1, 1}, {2, 2}, {3, 1}}) {
    const std::string size = " " + name + " " + std::to_string(M) + "x" + std::to_string(N);
    Inputs x(c, M, N, seed++);
    fm::CoefficientInputs in_r = x.in;
    in_r.context = r.context;
    const auto n = static_cast<std::size_t>(M + N), hs = static_cast<std::size_t>(H),
               hn = static_cast<std::size_t>(Hn);
    auto run = [&](auto call) {
      std::vector<double> out_c, out_r;
      call(c, x.in, out_c);
      call(r, in_r, out_r);
      return std::pair{out_c, out_r};
    };
    {
      auto [a, b] = run(
          [&](const fm::ModelFamily& f, const fm::CoefficientInputs& in, std::vector<double>& out) {
            out.assign(n * n, 7.0);
            f.mass(in, out.data());
          });
      expect_close(a, b, "mass" + size);
    }
    for (const bool thrust : {false, true}) {
      auto [a, b] = run(
          [&](const fm::ModelFamily& f, const fm::CoefficientInputs& in, std::vector<double>& out) {
            const std::size_t rows = thrust ? 1 : n;
            out.assign(hs * rows * 2 * n + hs * rows, 7.0);
            const fm::CoefficientOutputs o{out.data(), out.data() + hs * rows * 2 * n};
            (thrust ? f.thrust : f.coefficients)(in, o);
          });
      expect_close(a, b, (thrust ? "thrust" : "coefficients") + size);
    }
    {
      auto [a, b] = run(
          [&](const fm::ModelFamily& f, const fm::CoefficientInputs& in, std::vector<double>& out) {
            out.assign(n * n + n, 7.0);
            f.equilibrium(in, {out.data(), out.data() + n * n});
          });
      expect_close(a, b, "equilibrium" + size);
    }
    for (const bool thrust : {false, true}) {
      auto [a, b] = run(
          [&](const fm::ModelFamily& f, const fm::CoefficientInputs& in, std::vector<double>& out) {
            const std::size_t rows = thrust ? 1 : n;
            out.assign(hn * rows + hn * rows * 2 * n, 7.0);
            const fm::NonlinearOutputs o{out.data(), out.data() + hn * rows};
            (thrust ? f.nonlinear_thrust : f.nonlinear)(in, x.y.data(), o);
          });
      expect_close(a, b, (thrust ? "nonlinear_thrust" : "nonlinear") + size);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Shipped, SpecFamilies,
                         ::testing::Values("paper", "no-radial-flow", "lag-order-2"),
                         [](const auto& test) {
                           std::string s = test.param;
                           std::replace(s.begin(), s.end(), '-', '_');
                           return s;
                         });

TEST(RunTimeSpec, AnalysisOfASpecEqualsTheCompiledModel) {
  flaplag::spec::load_spec(shipped("paper"));
  flaplag::RotorParameters p;
  p.modes = flaplag::ModeKind::Exact;
  p.model = flaplag::find_model("paper", 2, 1).name;
  flaplag::RotorParameters q = p;
  q.model = flaplag::find_model("spec:paper", 2, 1).name;
  EXPECT_EQ(q.model, "spec:paper-2x1");
  const flaplag::CriticalResult a = flaplag::Analysis(p, {}).critical({});
  const flaplag::CriticalResult b = flaplag::Analysis(q, {}).critical({});
  ASSERT_TRUE(a.mu_c.has_value());
  ASSERT_TRUE(b.mu_c.has_value());
  EXPECT_EQ(*a.mu_c, *b.mu_c);
  EXPECT_EQ(a.mode, b.mode);
}

// A user's spec in a scratch directory, with its base next to it: no build, and the numbers of
// the compiled model of the same physics.
TEST(RunTimeSpec, UserSpecInAScratchDirectoryRuns) {
  const fs::path dir =
      fs::temp_directory_path() / ("flaplag_spec_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::copy_file(shipped("paper"), dir / "paper.toml", fs::copy_options::overwrite_existing);
  std::ofstream(dir / "mine.toml") << "base = \"paper\"\n[terms]\nradial_flow = false\n";
  const fm::ModelFamily& f = flaplag::spec::load_spec((dir / "mine.toml").string());
  EXPECT_EQ(std::string(f.name), "spec:mine");
  EXPECT_GE(flaplag::spec::derivation_seconds(f), 0.0);
  // loading it again is the same family
  EXPECT_EQ(&flaplag::spec::load_spec((dir / "mine.toml").string()), &f);
  flaplag::RotorParameters p;
  p.model = "no-radial-flow";
  flaplag::RotorParameters q = p;
  q.model = "spec:mine";
  const flaplag::CriticalResult a = flaplag::Analysis(p, {}).critical({});
  const flaplag::CriticalResult b = flaplag::Analysis(q, {}).critical({});
  ASSERT_TRUE(a.mu_c.has_value());
  ASSERT_TRUE(b.mu_c.has_value());
  EXPECT_EQ(*a.mu_c, *b.mu_c);
  EXPECT_EQ(a.mode, b.mode);
  const std::string audit = flaplag::spec::audit_report("spec:mine");
  EXPECT_NE(audit.find("Every term, for any number of modes"), std::string::npos);
  fs::remove_all(dir);
}

TEST(RunTimeSpec, BadSpecIsOneLine) {
  const fs::path dir =
      fs::temp_directory_path() / ("flaplag_spec_bad_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "bad.toml") << "[kept]\nflap = \"two\"\n";
  std::ofstream(dir / "orphan.toml") << "base = \"nowhere\"\n";
  for (const char* file : {"bad.toml", "orphan.toml", "missing.toml"}) {
    const std::string path = (dir / file).string();
    try {
      flaplag::spec::load_spec(path);
      ADD_FAILURE() << file << " was accepted";
    } catch (const flaplag::InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_EQ(what.rfind("spec = " + path + ": ", 0), 0u) << what;
      EXPECT_NE(what.find(file), std::string::npos) << what;
    }
  }
  fs::remove_all(dir);
}

}  // namespace

}  // namespace runtime_spec_test
