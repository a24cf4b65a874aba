// The mode-generic model of a spec (generic.h): its index patterns, expanded for M x N modes,
// are term for term the concrete derivation at M x N (exact rational coefficients), for every
// shipped spec, the untruncated test spec and specs with the term keys of examples/specs, including
// sizes below and above the size the patterns were extracted from; the extraction refuses to work
// from too few modes.
#include "flaplag_derive/generic.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "flaplag_derive/derive.h"
#include "flaplag_derive/spec.h"

namespace generic_test {

namespace fd = flaplag::derive;

namespace {

fd::OrderingSpec with_every_feature(fd::OrderingSpec s, int M, int N) {
  s.flap_modes = M;
  s.lag_modes = N;
  s.cyclic_pitch = true;
  s.nonlinear = true;
  return s;
}

// The first difference of two sorted term lists, for the failure message.
std::string first_difference(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  for (size_t j = 0; j < std::min(a.size(), b.size()); ++j) {
    if (a[j] != b[j]) return "derived: " + a[j] + "\nexpanded: " + b[j];
  }
  return "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size());
}

class GenericModel : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(GenericModel, ExpandsToTheConcreteDerivationAtEverySize) {
  const std::string& path = GetParam();
  const fd::OrderingSpec spec = fd::load_spec(path);
  const fd::GenericModel g = fd::extract_generic(spec);
  ASSERT_FALSE(g.slots.empty());
  // 4 x 4 is above the extraction's own 3 x 3 (and 4 x 4 saturation) sizes
  for (const auto& [M, N] : std::vector<std::pair<int, int>>{
           {1, 1}, {2, 1}, {1, 2}, {3, 1}, {1, 3}, {2, 3}, {3, 2}, {4, 2}}) {
    const auto derived = fd::concrete_terms(fd::derive_model(with_every_feature(spec, M, N)));
    const auto expanded = fd::expand_generic(g, M, N);
    EXPECT_EQ(derived, expanded) << spec.name << " " << M << "x" << N << "\n"
                                 << first_difference(derived, expanded);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Specs, GenericModel,
    ::testing::Values(std::string(FLAPLAG_SPEC_DIR) + "/paper.toml",
                      std::string(FLAPLAG_SPEC_DIR) + "/no-radial-flow.toml",
                      std::string(FLAPLAG_SPEC_DIR) + "/lag-order-2.toml",
                      std::string(FLAPLAG_TEST_SPEC_DIR) + "/untruncated.toml",
                      // the per-equation term classes, exclusions and
                      // the order of mu (spec keys of the examples)
                      std::string(FLAPLAG_EXAMPLE_SPEC_DIR) + "/fig06-07-radial-flow-lag-only.toml",
                      std::string(FLAPLAG_EXAMPLE_SPEC_DIR) + "/fig08-lag-damping-only.toml",
                      std::string(FLAPLAG_EXAMPLE_SPEC_DIR) + "/no-induced-lag-damping.toml",
                      std::string(FLAPLAG_TEST_SPEC_DIR) + "/mu-small.toml"),
    [](const auto& tp) {
      std::string s = tp.param.substr(tp.param.rfind('/') + 1);
      s = s.substr(0, s.find('.'));
      for (char& ch : s)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return s;
    });

// From one mode per direction no pattern with two different flap modes can be seen: the
// saturation check (patterns at P and P + 1 modes equal) must refuse it.
TEST(GenericExtraction, TooFewModesIsRefused) {
  const fd::OrderingSpec spec = fd::load_spec(std::string(FLAPLAG_SPEC_DIR) + "/paper.toml");
  EXPECT_THROW(fd::extract_generic(spec, 1), std::logic_error);
}

// The patterns carry the audit: each term keeps its eps order and origin, the modal stiffness
// exists on the diagonal only, and the paper's names come with index letters.
TEST(GenericExtraction, TermsKeepTheirAuditFields) {
  const fd::OrderingSpec spec = fd::load_spec(std::string(FLAPLAG_SPEC_DIR) + "/paper.toml");
  const fd::GenericModel g = fd::extract_generic(spec);
  bool modal_stiffness = false, f6 = false;
  for (const auto& s : g.slots) {
    for (const auto& t : s.terms) {
      EXPECT_FALSE(t.origin.empty());
      if (t.origin.find("modal stiffness") != std::string::npos) {
        // omega_i^2 M_ii q_i involves the equation's own mode only: on the diagonal of the
        // blocks with a column, and with no other mode variable anywhere
        if (s.has_col()) {
          EXPECT_TRUE(t.diagonal) << t.origin;
        }
        EXPECT_EQ(t.vars.size(), 1u) << t.origin;
        modal_stiffness = true;
      }
      if (t.paper_name.rfind("F6_", 0) == 0) f6 = true;
    }
  }
  EXPECT_TRUE(modal_stiffness);
  EXPECT_TRUE(f6);
  // integral templates are named with letters: no mode number after a name's last '_'
  for (const auto& t : g.integrals) {
    std::stringstream names(t.paper_name);
    std::string part;
    while (std::getline(names, part, '/')) {
      const auto us = part.rfind('_');
      if (us == std::string::npos) continue;
      EXPECT_EQ(part.find_first_of("0123456789", us), std::string::npos) << t.paper_name;
    }
  }
}

}  // namespace generic_test
