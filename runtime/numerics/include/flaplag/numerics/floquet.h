// flaplag — transition matrix Phi(2 pi, 0) and Floquet analysis (paper Section 3).
//
// Exponents lambda_k = zeta_k + i omega_k = ln(Lambda_k) / T, T = 2 pi, per rev (eqs 3.16-3.19).
// omega is defined only up to an integer; floquet_exponents() returns the principal value and
// the continuation in continuation.h fixes the integer.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "flaplag/core/outcome.h"
#include "flaplag/core/validation.h"
#include "flaplag/numerics/periodic_system.h"

namespace flaplag {

enum class TransitionMethod {
  RK4,      // classical Runge-Kutta, N equal steps per period (paper 3.3.2), split at sector edges
  Hsu,      // K intervals, exact interval means of A, J Taylor terms (eqs 3.21-3.28)
  Magnus4,  // 4th-order Magnus with Richardson error estimate (reference method)
  // The fastest of them at the default accuracy for the system's size: automatic_method().
  Automatic,
};

// The methods in help order, and their names (the table: the one place of names <-> enum).
inline constexpr TransitionMethod kTransitionMethods[] = {
    TransitionMethod::RK4, TransitionMethod::Hsu, TransitionMethod::Magnus4,
    TransitionMethod::Automatic};
constexpr auto describe(Tag<TransitionMethod>) {
  return std::array<EnumName<TransitionMethod>, 4>{{{TransitionMethod::RK4, "rk4"},
                                                    {TransitionMethod::Hsu, "hsu"},
                                                    {TransitionMethod::Magnus4, "magnus"},
                                                    {TransitionMethod::Automatic, "auto"}}};
}
const char* method_name(TransitionMethod m);  // "rk4", "hsu", "magnus", "auto"
// The method called `name` (exactly method_name's text) into *method; false when none is.
bool method_from_name(const std::string& name, TransitionMethod* method);
// "rk4, hsu, magnus, auto": the names for an error message.
std::string method_names();

// The method Automatic stands for on a system of `state_size` states (>= 1): Hsu for up to 4
// states (one flap and one lag mode: its pair of counts from one pass is the cheapest resolved
// evaluation there), Magnus4 above, where the highest mode sets the step and Magnus4's sixth
// order (after its Richardson pass) and its raw levels for the sign checks need the fewest
// matrix products (bench/README.md, "Many modes").
TransitionMethod automatic_method(int state_size);

// How Phi(2 pi, 0) is computed.  Validated as every options struct (core/validation.h).
struct TransitionOptions {
  static constexpr int kAutomatic = 0;
  static constexpr int kMaxSteps = 1000000;
  static constexpr int kMaxTerms = 30;
  static constexpr Range kStepsRange{{0, kMaxSteps, false, false}, "0 (automatic) or 1..1000000"};
  static constexpr Range kTermsRange{{1, kMaxTerms, false, false}, "1..30"};

  // Automatic (the default): the method of automatic_method() for the system's state size.
  TransitionMethod method = TransitionMethod::Automatic;
  // RK4 steps / Hsu intervals K / Magnus steps per period, 1..kMaxSteps; kAutomatic (the
  // default): the step control chooses them per system so that the estimated exponent error is
  // at most zeta_tolerance (floquet_evaluator.h).  The transition_matrix* functions need a fixed
  // count.
  int steps = kAutomatic;
  int terms = 4;                 // Hsu Taylor terms J, 1..kMaxTerms
  double zeta_tolerance = 1e-5;  // target exponent error per rev (floquet_evaluator.h), > 0

  // The paper's setting: Hsu, K = 50 intervals, J = 4 terms (Section 3.3, Fig. 3).
  static TransitionOptions Paper() { return {TransitionMethod::Hsu, 50, 4, 1e-5}; }

  std::optional<InvalidInput> Validate() const;
  bool IsValid(std::string* error) const { return IsValidReport(Validate(), error); }
  void Check() const { ThrowIfInvalid(Validate()); }
};

constexpr auto describe(Tag<TransitionOptions>) {
  using O = TransitionOptions;
  return std::make_tuple(
      Option{"method", &O::method, "",
             "transition matrix: rk4 (paper 3.3.2), hsu (eqs 3.21-3.28), magnus (4th-order "
             "Magnus, Richardson-extrapolated) or auto (hsu for one flap and one lag mode, "
             "magnus above)"},
      Option{"steps", &O::steps, "",
             "RK4 steps, Hsu intervals K or Magnus steps per period; 0: automatic",
             &O::kStepsRange},
      Option{"terms", &O::terms, "", "Hsu Taylor terms J", &O::kTermsRange},
      Option{"zeta_tolerance", &O::zeta_tolerance, "per rev",
             "error allowed in each damping exponent zeta: an exponent counts as resolved when "
             "its estimated error is at most this times max(1, 100 |zeta|) -- absolute near "
             "zeta = 0, where stability is decided, relative for modes with |zeta| > 0.01",
             &kPositive});
}

struct TransitionResult {
  Eigen::MatrixXd phi;          // Phi(2 pi, 0)
  double error_estimate = 0.0;  // Magnus: Richardson estimate of ||Phi error||_max; else 0
                                // (the analysis estimates exponent errors itself)
};

// opt.Check() and a fixed step count (not kAutomatic) are required, else InvalidInput.  An
// Automatic method is automatic_method(sys.n).
TransitionResult transition_matrix(const PeriodicSystem& sys, const TransitionOptions& opt);
Eigen::MatrixXd transition_matrix_rk4(const PeriodicSystem& sys, int steps);
Eigen::MatrixXd transition_matrix_hsu(const PeriodicSystem& sys, int intervals, int terms);
// The same into *phi, reusing its storage (nothing allocates once it is n x n, for the systems
// with a plain kernel: 8 and 12 states, and 4 in the layout of 1 x 1 modes, whose odd rows do
// not vary).
void transition_matrix_hsu(const PeriodicSystem& sys, int intervals, int terms,
                           Eigen::MatrixXd* phi);
// Hsu at `intervals` (even) and at intervals / 2 in one pass, into *phi and *phi_half.  An
// interval of the coarse grid that holds no sector edge has Delta C_k = the sum of those of its
// two fine intervals (the exact means are additive), so *phi_half costs only its Taylor steps.
// *phi has the bits of transition_matrix_hsu(sys, intervals, terms); *phi_half equals
// transition_matrix_hsu(sys, intervals / 2, terms) to rounding.  Systems without a plain kernel
// (state size, layout, J != 4, a varying region) get the two separate calls.
void transition_matrix_hsu_pair(const PeriodicSystem& sys, int intervals, int terms,
                                Eigen::MatrixXd* phi, Eigen::MatrixXd* phi_half);
TransitionResult transition_matrix_magnus4(const PeriodicSystem& sys, int steps);
// Phi by fourth-order Magnus alone (no Richardson pass) on the grid of `steps` steps with every
// substep bisected `bisections` times (0..20): level l + 1 is level l on a grid twice as fine,
// so (16 level(l + 1) - level(l)) / 15 is transition_matrix_magnus4's extrapolation at
// steps * 2^l and a caller walking consecutive levels computes each once.  Not for a system
// with a varying region (InvalidInput); steps * 2^bisections <= kMaxSteps.
Eigen::MatrixXd transition_matrix_magnus4_level(const PeriodicSystem& sys, int steps,
                                                int bisections);

// A zero multiplier (possible only for a Phi that no smooth ODE produces, e.g. an exactly
// singular input) is represented by zeta = -infinity and omega = 0.
struct FloquetExponent {
  std::complex<double> multiplier;  // Lambda_k
  double zeta = 0.0;                // ln|Lambda| / T (-infinity for Lambda = 0)
  double omega = 0.0;               // arg(Lambda) / T, principal value in (-1/2, 1/2]
  // Eigenvector of Phi(T) (unit 2-norm).  Empty when the result was computed with
  // FloquetVectors::OnDemand: add_eigenvectors() computes it then from FloquetResult::phi.
  Eigen::VectorXcd eigenvector;
};

// The eigen-decomposition of a transition matrix with its vectors, as the eigen-solve gives it
// (the fixed-size solvers of floquet_exponents for 4 and 8 states, so the same eigenvalues in
// the same order); ok false when phi is not square, not finite or the solve did not converge.
struct FloquetEigenSystem {
  Eigen::VectorXcd values;
  Eigen::MatrixXcd vectors;  // column k belongs to values(k); not normalized
  bool ok = false;
};
FloquetEigenSystem floquet_eigensystem(const Eigen::MatrixXd& phi);

struct FloquetResult : Outcome {
  std::vector<FloquetExponent> exponents;
  // |det Phi - exp(int trace A)| / exp(int trace A), from log|det Phi| so that neither
  // determinant need be representable; 1 for a singular Phi.
  double liouville_residual = 0.0;
  // Failed when Phi has non-finite entries or the eigen-solve does not give finite
  // multipliers (and, when computed, eigenvectors): then the exponents are NaN (or partly so)
  // and must not be used; message says why.
  // The transition matrix the exponents are of, kept so that the eigenvectors can be computed
  // when they are needed (add_eigenvectors(); the mode identification of continuation.h asks
  // for them only when two candidates are close).
  Eigen::MatrixXd phi;
  // The eigen-decomposition of phi with its vectors when it was computed ahead (track_exponents
  // does so on worker threads where the identification may need it); null: computed from phi
  // when needed.  The eigenvectors drawn from it are those drawn from phi, bit for bit.
  std::shared_ptr<const FloquetEigenSystem> eigensystem;

  // Every exponent carries its eigenvector (of the size of Phi).
  bool has_eigenvectors() const;
};

// Whether floquet_exponents computes the eigenvectors with the multipliers.  They cost about as
// much as the eigenvalues themselves (4x4: the eigen-solve takes twice as long with them).
enum class FloquetVectors {
  Compute,   // every exponent gets its eigenvector
  OnDemand,  // multipliers only; add_eigenvectors() adds the eigenvectors from phi later
};

// With eigenvectors.  phi square and non-empty, trace_integral finite (else InvalidInput).
FloquetResult floquet_exponents(const Eigen::MatrixXd& phi, double trace_integral);
// The same into *out, reusing its storage: once *out has held a result of the same size, its
// exponents are overwritten in place (with OnDemand: the point path of the analysis).
void floquet_exponents(const Eigen::MatrixXd& phi, double trace_integral, FloquetVectors vectors,
                       FloquetResult* out);

// Unit-2-norm eigenvectors of phi for the multipliers `multipliers` (eigenvalues of phi as a
// previous eigen-solve gave them): each gets the eigenvector of the eigen-solve's eigenvalue
// equal to it (the eigen-solve is deterministic, so the same eigenvalues come out), else of the
// nearest one not yet used.  *vectors is resized to multipliers.size().  false when the
// eigen-solve does not converge or gives non-finite vectors, or the sizes do not match.
bool floquet_eigenvectors(const Eigen::MatrixXd& phi,
                          const std::vector<std::complex<double>>& multipliers,
                          std::vector<Eigen::VectorXcd>* vectors);
// The same from a decomposition computed before: floquet_eigenvectors(phi, m, v) is this on
// floquet_eigensystem(phi).
bool floquet_eigenvectors(const FloquetEigenSystem& system,
                          const std::vector<std::complex<double>>& multipliers,
                          std::vector<Eigen::VectorXcd>* vectors);
// Adds the eigenvectors to a result computed with OnDemand (nothing to do when it has them);
// false when they cannot be computed (no phi, a Failed result, a failed eigen-solve).
bool add_eigenvectors(FloquetResult* result);

}  // namespace flaplag
