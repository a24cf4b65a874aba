// flaplag — transition matrix Phi(2 pi, 0) of y' = A(psi) y (paper Section 3.3).
//
// Three methods share one grid rule (grid.h, equal_grid): the period is cut into equal steps,
// and a step that contains a piece edge is split there, so that A(psi) is smooth (a
// trigonometric polynomial of one harmonic set) on every substep.  Each substep uses the
// harmonics of the piece that contains its midpoint; at a substep end that lies on an edge
// that is the one-sided limit, which is what the integrators need.  A system with an evaluator
// piece (the exact reversed flow, periodic_system.h) goes to transition_varying.cc instead.
//
// Speed: the dimension is a template parameter (fixed-size, stack-allocated Eigen matrices for
// n = 2, 4, 6, 8; dynamic matrices with preallocated temporaries otherwise); only the entries
// of A that vary with psi are summed over the harmonics (in the rotor equations about half of
// them); the harmonic basis on the equal grid comes from a rotation recurrence
// e^{i(j+1)d} = e^{ijd} e^{id} instead of sin/cos calls (reseeded exactly every kReseed points
// so that rounding cannot accumulate); Hsu's J = 4 Taylor polynomial takes two matrix products
// (Paterson-Stockmeyer) plus one for the accumulated product.  Nothing in the interval loops
// allocates.  Hsu (J = 4) and Magnus at 4, 8 and 12 states run on the plain kernels further down
// (plain_input() decides; a system that the plain kernels cannot evaluate from harmonic matrices
// alone must make it return false), Magnus at more than 8 other states on the wide kernel
// (balanced, any size: wide_magnus()), everything else on Kernel<N>.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"
#include "flaplag/numerics/dense.h"
#include "flaplag/numerics/floquet.h"
#include "flaplag/numerics/gauss_legendre.h"
#include "grid.h"
#include "sinc.h"
#include "transition_varying.h"

namespace flaplag {
namespace {

using detail::Segment;
using detail::sinc;

constexpr int kReseed = 32;

// Upper bounds keep memory (one grid segment per step) and time bounded for any caller.
void check_count(const char* name, int value, int hi = TransitionOptions::kMaxSteps) {
  if (value < 1 || value > hi)
    throw InvalidInput(name, std::to_string(value), "must be 1.." + std::to_string(hi));
}

// Unit phasors e^{i psi} = (cos psi, sin psi) are kept as plain doubles rather than
// std::complex: the complex operator* carries inf/nan recovery that unit phasors never need,
// and packing the two parts through memory costs store-forwarding stalls in the inner loops.
struct Phasor {
  double c, s;
};
inline Phasor phasor(double psi) { return {std::cos(psi), std::sin(psi)}; }

// e^{i (offset + j d)}, j = 0 .. count-1, interleaved (cos, sin), by the rotation recurrence
// e^{i(j+1)d} = e^{ijd} e^{id}, reseeded exactly every kReseed points so that rounding cannot
// accumulate: two sin/cos evaluations per kReseed points instead of two per point.
std::vector<double> phasor_grid(double offset, double d, int count) {
  std::vector<double> out(2 * static_cast<std::size_t>(count));
  const Phasor step = phasor(d);
  double c = 1.0, s = 0.0;
  for (int j = 0; j < count; ++j) {
    if (j % kReseed == 0) {
      const Phasor z = phasor(offset + j * d);
      c = z.c;
      s = z.s;
    } else {
      const double t = c * step.c - s * step.s;
      s = c * step.s + s * step.c;
      c = t;
    }
    out[2 * j] = c;
    out[2 * j + 1] = s;
  }
  return out;
}

// Harmonic basis values for h = 1 .. H-1 from z = e^{i psi}, scaled by damp[k] for order k:
// col[2k-2] = cos(k psi) damp[k], col[2k-1] = sin(k psi) damp[k].  damp = 1 gives point
// values, damp[k] = sinc(k d/2) interval means over [psi - d/2, psi + d/2] (eqs 4.2-4.5).
inline void fill_basis(double zc, double zs, int H, const double* damp, double* col) {
  double wc = zc, ws = zs;
  for (int h = 1; h < H; h += 2) {
    const double f = damp[(h + 1) / 2];
    col[h - 1] = wc * f;
    if (h + 1 < H) col[h] = ws * f;
    const double t = wc * zc - ws * zs;
    ws = wc * zs + ws * zc;
    wc = t;
  }
}

template <int N>
class Kernel {
 public:
  using Mat = Eigen::Matrix<double, N, N>;

  explicit Kernel(const PeriodicSystem& sys) : sys_(sys), n_(sys.n) {
    idx_.reserve(static_cast<std::size_t>(n_) * n_);
    for (Eigen::Index l = 0; l < static_cast<Eigen::Index>(n_) * n_; ++l) {
      bool varies = false;
      for (const HarmonicSet& set : sys.sets)
        for (std::size_t h = 1; h < set.A.size(); ++h) varies |= set.A[h](l) != 0.0;
      if (varies) idx_.push_back(l);
    }
    const Eigen::Index m = static_cast<Eigen::Index>(idx_.size());
    region_.resize(sys.sets.size());
    int max_h = 1;
    for (std::size_t r = 0; r < sys.sets.size(); ++r) {
      const HarmonicSet& set = sys.sets[r];
      Region& g = region_[r];
      g.H = static_cast<int>(set.A.size());
      g.A0 = set.A[0];
      g.V = Eigen::MatrixXd::Zero((m + 3) / 4 * 4, g.H - 1);
      for (int h = 1; h < g.H; ++h)
        for (Eigen::Index e = 0; e < m; ++e) g.V(e, h - 1) = set.A[h](idx_[e]);
      max_h = std::max(max_h, g.H);
    }
    max_order_ = max_h / 2;
    basis_.resize(static_cast<std::size_t>(max_h));
    w_.resize((idx_.size() + 3) / 4 * 4);
    ones_.assign(static_cast<std::size_t>(max_order()) + 1, 1.0);
  }

  Mat identity() const { return Mat::Identity(n_, n_); }

  // Hsu, eqs 3.21-3.28: constant C_k = exact interval mean of A, exp(Delta C_k) by J Taylor
  // terms, H(K) = prod exp(Delta_k C_k) with later intervals multiplied from the left (3.25).
  Mat hsu(int K, int J) {
    const std::vector<Segment> grid = detail::equal_grid(sys_, K);
    const double d = kTwoPi / K;
    // Means of cos k psi, sin k psi over an equal interval are the midpoint values times
    // sinc(k d / 2) (eqs 4.2-4.5): one damping table for the whole grid.
    std::vector<double> damp, dsub;
    sinc_table(0.5 * d, damp);
    const std::vector<double> mids = phasor_grid(0.5 * d, d, K);  // interval midpoints
    Mat Phi = identity();
    Mat X(n_, n_), X2(n_, n_), T(n_, n_), E(n_, n_), P(n_, n_);
    for (const Segment& s : grid) {
      const double delta = s.b - s.a;
      // X = Delta C_k with C_k the exact mean of A over the substep.
      if (s.node >= 0) {
        evaluate(s.set, mids[2 * s.node], mids[2 * s.node + 1], damp.data(), delta, X);
      } else {
        // A substep cut at a sector edge: the same formula with its own width.
        sinc_table(0.5 * delta, dsub);
        const Phasor z = phasor(0.5 * (s.a + s.b));
        evaluate(s.set, z.c, z.s, dsub.data(), delta, X);
      }
      taylor(X, J, X2, T, E);
      P.noalias() = E * Phi;
      Phi = P;
    }
    return Phi;
  }

  // Classical RK4 on the matrix ODE Phi' = A Phi (paper 3.3.2, all columns at once).
  Mat rk4(int steps) {
    const std::vector<Segment> grid = detail::equal_grid(sys_, steps);
    // A is needed at the start (unless it equals the previous end), the midpoint and the end of
    // every substep; on unsplit steps these are the points psi_j = j d/2.
    const double* damp = ones_.data();
    const std::vector<double> pts = phasor_grid(0.0, 0.5 * kTwoPi / steps, 2 * steps + 1);
    auto at = [&](int j, Mat& out, int set) {
      evaluate(set, pts[2 * j], pts[2 * j + 1], damp, 1.0, out);
    };
    auto at_psi = [&](double psi, Mat& out, int set) {
      const Phasor z = phasor(psi);
      evaluate(set, z.c, z.s, damp, 1.0, out);
    };
    Mat Phi = identity();
    Mat Aa(n_, n_), Am(n_, n_), Ab(n_, n_);
    detail::Rk4<Mat> rk;
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const Segment& s = grid[i];
      const double h = s.b - s.a;
      const bool reuse = i > 0 && !s.after_break;  // A at a is the previous end
      if (s.node >= 0) {
        if (reuse) {
          Aa = Ab;
        } else {
          at(2 * s.node, Aa, s.set);
        }
        at(2 * s.node + 1, Am, s.set);
        at(2 * s.node + 2, Ab, s.set);
      } else {
        if (reuse) {
          Aa = Ab;
        } else {
          at_psi(s.a, Aa, s.set);
        }
        at_psi(0.5 * (s.a + s.b), Am, s.set);
        at_psi(s.b, Ab, s.set);
      }
      rk.step(h, Phi, [&](int stage, const Mat& y, Mat& k) {
        k.noalias() = (stage == 0 ? Aa : stage == 3 ? Ab : Am) * y;
      });
    }
    return Phi;
  }

  // Fourth-order Magnus (gauss::magnus4_step) on every substep.
  Mat magnus(const std::vector<Segment>& grid) {
    Mat Phi = identity();
    Mat A1(n_, n_), A2(n_, n_), Om(n_, n_), E(n_, n_), P(n_, n_);
    for (const Segment& s : grid) {
      const gauss::Magnus4Step st = gauss::magnus4_step(s.a, s.b);
      point(s.set, st.psi1, A1);
      point(s.set, st.psi2, A2);
      Om = st.c1 * (A1 + A2);
      P.noalias() = A2 * A1;
      P.noalias() -= A1 * A2;
      Om += st.c2 * P;
      E = matrix_exponential(Om);  // scaling and squaring, Pade approximant (dense.h)
      P.noalias() = E * Phi;
      Phi = P;
    }
    return Phi;
  }

 private:
  struct Region {
    int H = 1;
    Mat A0;
    Eigen::MatrixXd V;  // m (padded to 4k) x (H-1): coefficients (h >= 1) of varying entries
  };

  int max_order() const { return max_order_; }

  // table[k] = sinc(k x), k = 0 .. max order (a few sin calls per grid, not per interval).
  void sinc_table(double x, std::vector<double>& table) const {
    const int kmax = max_order();
    table.resize(static_cast<std::size_t>(kmax) + 1);
    table[0] = 1.0;
    for (int k = 1; k <= kmax; ++k) table[k] = sinc(k * x);
  }

  // out = scale * A: the constant harmonic plus the entries that vary with psi, each a dot
  // product of its harmonic coefficients (h >= 1) with the basis of z = e^{i psi} scaled by
  // damp (fill_basis).
  void evaluate(int set, double zc, double zs, const double* damp, double scale, Mat& out) {
    const Region& g = region_[set];
    out = scale * g.A0;
    const Eigen::Index m = static_cast<Eigen::Index>(idx_.size());
    const int hb = g.H - 1;
    if (m == 0 || hb < 1) return;
    fill_basis(zc, zs, g.H, damp, basis_.data());
    // w = V b in blocks of four entries whose partial sums stay in registers (a loop over h
    // that reloads w from memory is bound by store-to-load latency).  V's rows are padded to a
    // multiple of four.
    const double* b = basis_.data();
    const double* v = g.V.data();
    double* w = w_.data();
    const Eigen::Index mp = g.V.rows();
    for (Eigen::Index e = 0; e < mp; e += 4) {
      double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0;
      for (int h = 0; h < hb; ++h) {
        const double* vh = v + h * mp + e;
        const double bh = b[h];
        a0 += vh[0] * bh;
        a1 += vh[1] * bh;
        a2 += vh[2] * bh;
        a3 += vh[3] * bh;
      }
      w[e] = a0;
      w[e + 1] = a1;
      w[e + 2] = a2;
      w[e + 3] = a3;
    }
    double* o = out.data();
    for (Eigen::Index e = 0; e < m; ++e) o[idx_[e]] += scale * w[e];
  }

  // A at psi with the harmonics of the given region (one-sided value at an edge).
  void point(int set, double psi, Mat& out) {
    const Phasor z = phasor(psi);
    evaluate(set, z.c, z.s, ones_.data(), 1.0, out);
  }

  // E = sum_{j=0}^{J} X^j / j!  (eq 3.27).  J <= 4 by Paterson-Stockmeyer (at most two
  // products), beyond by Horner.
  void taylor(const Mat& X, int J, Mat& X2, Mat& T, Mat& E) const {
    E = identity();  // exp(X) ~ I + ...
    switch (J) {
      case 1:
        E += X;
        return;
      case 2:
        X2.noalias() = X * X;
        E += X + 0.5 * X2;
        return;
      case 3:
        X2.noalias() = X * X;
        T = (1.0 / 6.0) * X;
        T.diagonal().array() += 0.5;
        E += X;
        E.noalias() += X2 * T;
        return;
      case 4:
        X2.noalias() = X * X;
        T = (1.0 / 6.0) * X + (1.0 / 24.0) * X2;
        T.diagonal().array() += 0.5;
        E += X;
        E.noalias() += X2 * T;
        return;
      default:
        // I + X/1 (I + X/2 (... (I + X/J))).
        T = identity() + X / static_cast<double>(J);
        for (int j = J - 1; j >= 1; --j) {
          X2.noalias() = X * T;
          T = identity() + X2 / static_cast<double>(j);
        }
        E = T;
        return;
    }
  }

  const PeriodicSystem& sys_;
  int n_;
  std::vector<Eigen::Index> idx_;  // column-major indices of the entries that vary with psi
  std::vector<Region> region_;     // per harmonic set of the system
  int max_order_ = 0;
  std::vector<double> basis_, w_;  // workspace of evaluate()
  std::vector<double> ones_;       // damping factors of point values
};

// ---- Hsu and Magnus on plain fixed-size arrays (n = 4, 8, 12) ----------------------------------
//
// The state sizes of 1x1 .. 3x3 modes (4 .. 12 states) get kernels on plain column-major arrays
// whose loops have compile-time bounds, so that GCC unrolls and vectorizes them for the target of
// each clone: function multi-versioning (target_clones) builds an AVX2 and a baseline x86-64
// version and the loader picks one per machine, so the binary runs on any x86-64.  Only add and
// multiply appear (no FMA contraction: "avx2" does not enable FMA), each element is computed
// by the same sequence of operations in either clone, so both give the same bits.  Nothing
// here allocates: the grid is walked on the fly, Magnus reads the harmonic matrices in place and
// Hsu a per-thread transposed copy (plain_hsu_input()).  Hsu's kernel can also give Phi at K / 2
// in the same pass (transition_matrix_hsu_pair: the automatic rule's error estimate).

// Largest harmonic count and order the plain kernel takes (the generated models have 11
// harmonics); beyond, the Eigen kernel is used.
constexpr int kPlainMaxHarmonics = 64;

// Most pieces (and edges) the plain and wide kernels take; beyond, the Eigen kernel is used.
constexpr int kPlainMaxPieces = 8;

struct PlainHsuInput {
  int K = 0;
  int n_edges = 0;
  double edges[kPlainMaxPieces] = {};  // the piece edges inside (0, 2 pi)
  int n_pieces = 0;
  double piece_end[kPlainMaxPieces] = {};
  int piece_set[kPlainMaxPieces] = {};
  int H[2] = {0, 0};                                  // harmonics of each set
  const double* A[2][kPlainMaxHarmonics] = {{}, {}};  // column-major n x n, in place
  double damp[kPlainMaxHarmonics / 2 + 2] = {};       // sinc(k d / 2), the equal-step means
  double ones[kPlainMaxHarmonics / 2 + 2] = {};       // 1: point values
  int max_order = 0;
};

// The harmonic set of the piece that contains mid (in (0, 2 pi)).
[[gnu::always_inline]] inline int plain_set(const PlainHsuInput& in, double mid) {
  int i = 0;
  while (i + 1 < in.n_pieces && !(mid < in.piece_end[i])) ++i;
  return in.piece_set[i];
}

// Matrices of the plain kernel: column-major, each column as N/4 vectors of four doubles (GCC
// vector extensions: one AVX register, or two SSE2 registers in the baseline clone).
typedef double V4 __attribute__((vector_size(32)));

template <int N>
struct PlainMat {
  static constexpr int Q = N / 4;  // vectors per column
  V4 c[N * Q];
  double& at(int i, int j) { return c[j * Q + i / 4][i % 4]; }
  double at(int i, int j) const { return c[j * Q + i / 4][i % 4]; }
};

template <int N>
[[gnu::always_inline]] inline void plain_load(const double* src, PlainMat<N>& m) {
  __builtin_memcpy(m.c, src, sizeof m.c);
}
template <int N>
[[gnu::always_inline]] inline void plain_store(const PlainMat<N>& m, double* dst) {
  __builtin_memcpy(dst, m.c, sizeof m.c);
}
template <int N>
[[gnu::always_inline]] inline void plain_identity(PlainMat<N>& m) {
  for (V4& v : m.c) v = V4{0.0, 0.0, 0.0, 0.0};
  for (int i = 0; i < N; ++i) m.at(i, i) = 1.0;
}

// m += v I.  One vector add per diagonal entry, with -0.0 in the other lanes (x + -0.0 == x
// for every x, signed zeros included, so the bits are those of adding v to the diagonal
// alone): writing the diagonal entries one by one stores scalars into vectors that are loaded
// whole right after, which stalls store forwarding (measured: a fifth of the Hsu interval).
template <int N>
[[gnu::always_inline]] inline void plain_add_diagonal(PlainMat<N>& m, double v) {
  constexpr int Q = N / 4;
  for (int j = 0; j < N; ++j) {
    V4 d = {-0.0, -0.0, -0.0, -0.0};
    d[j % 4] = v;
    m.c[j * Q + j / 4] += d;
  }
}

// C = A B: column j of C is sum_k A(:, k) B(k, j).
template <int N>
[[gnu::always_inline]] inline void plain_mul(const PlainMat<N>& A, const PlainMat<N>& B,
                                             PlainMat<N>& C) {
  constexpr int Q = N / 4;
  for (int j = 0; j < N; ++j) {
    for (int q = 0; q < Q; ++q) {
      V4 acc = A.c[q] * B.at(0, j);
      for (int k = 1; k < N; ++k) acc += A.c[k * Q + q] * B.at(k, j);
      C.c[j * Q + q] = acc;
    }
  }
}

// X = delta C over one substep: the harmonics of the region weighted by w (w[0] = delta, w[h]
// = delta times the interval mean of phi_h).
template <int N>
[[gnu::always_inline]] inline void plain_weighted_sum(const double* const* A, int H,
                                                      const double* w, PlainMat<N>& X) {
  constexpr int V = N * N / 4;
  for (int e = 0; e < V; ++e) {
    V4 a;
    __builtin_memcpy(&a, A[0] + 4 * e, sizeof a);
    X.c[e] = a * w[0];
  }
  for (int h = 1; h < H; ++h) {
    const double* ah = A[h];
    const double wh = w[h];
    for (int e = 0; e < V; ++e) {
      V4 a;
      __builtin_memcpy(&a, ah + 4 * e, sizeof a);
      X.c[e] += a * wh;
    }
  }
}

// Weights of the harmonic sum for a substep of width delta centred at z = e^{i mid}, damped by
// damp[k] (eqs 4.2-4.5); w[0] = delta.
[[gnu::always_inline]] inline void plain_weights(double zc, double zs, int H, const double* damp,
                                                 double delta, double* w) {
  w[0] = delta;
  double wc = zc, ws = zs;
  for (int h = 1; h < H; h += 2) {
    const double f = damp[(h + 1) / 2] * delta;
    w[h] = wc * f;
    if (h + 1 < H) w[h + 1] = ws * f;
    const double t = wc * zc - ws * zs;
    ws = wc * zs + ws * zc;
    wc = t;
  }
}

// Hsu's plain kernel works on transposes: it computes Phi^T = E_1^T E_2^T ... E_K^T from the
// transposed harmonics.  Each product is computed as the transpose of the one it stands for,
// with the same terms summed in the same order (C^T(i, j) = sum_k B^T(i, k) A^T(k, j) against
// C(j, i) = sum_k A(j, k) B(k, i)), so Phi has the bits of the untransposed product.  What the
// layout buys: in the rotor equations of 1 x 1 modes (y = [g', g, h', h]) every second row of
// A(psi), q' = q', does not vary with psi, and rows of A are whole columns, i.e. whole vectors, of
// A^T, so the harmonic sum skips them (kEvenRows: only the rows 0, 2, 4, ... take the harmonics
// h >= 1).  With more modes the varying rows come in blocks (model_api.h: y = [g'_1..g'_M,
// g_1..g_M, ...]) and the kernel takes every row.  So 4 states are compiled with kEvenRows only
// (a 4-state system whose odd rows vary takes the Eigen kernel) and 8 and 12 without it: one
// variant per size and target, not two.

// X^T = sum_h w_h A_h^T over one substep, A_h^T column-major.
template <int N, bool kEvenRows>
[[gnu::always_inline]] inline void plain_weighted_sum_t(const double* const* At, int H,
                                                        const double* w, PlainMat<N>& Y) {
  constexpr int V = N * N / 4;
  constexpr int Q = N / 4;
  for (int e = 0; e < V; ++e) {
    V4 a;
    __builtin_memcpy(&a, At[0] + 4 * e, sizeof a);
    Y.c[e] = a * w[0];
  }
  for (int h = 1; h < H; ++h) {
    const double* ah = At[h];
    const double wh = w[h];
    for (int e = 0; e < V; ++e) {
      if (kEvenRows && (e / Q) % 2 == 1) continue;  // column e / Q of A^T: an odd row of A
      V4 a;
      __builtin_memcpy(&a, ah + 4 * e, sizeof a);
      Y.c[e] += a * wh;
    }
  }
}

// Phi^T <- Phi^T exp(X)^T, Y = X^T, with exp(X) ~ I + X + X^2 (I/2 + X/6 + X^2/24) (eq 3.27,
// J = 4, two products by Paterson-Stockmeyer) and one product for the accumulation (eq 3.25).
template <int N>
[[gnu::always_inline]] inline void plain_taylor4_step_t(const PlainMat<N>& Y, PlainMat<N>& Phit) {
  PlainMat<N> Y2, T, E;
  plain_mul<N>(Y, Y, Y2);
  for (int e = 0; e < N * N / 4; ++e) T.c[e] = Y.c[e] * (1.0 / 6.0) + Y2.c[e] * (1.0 / 24.0);
  plain_add_diagonal<N>(T, 0.5);
  plain_mul<N>(T, Y2, E);  // (X^2 T)^T
  for (int e = 0; e < N * N / 4; ++e) E.c[e] += Y.c[e];
  plain_add_diagonal<N>(E, 1.0);
  plain_mul<N>(Phit, E, Y2);  // (E Phi)^T
  Phit = Y2;
}

template <int N>
[[gnu::always_inline]] inline void plain_store_transposed(const PlainMat<N>& Mt, double* dst) {
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) dst[j * N + i] = Mt.at(j, i);
}

// The grid rule of detail::equal_grid() walked without storing it: step i of K, split at a sector
// edge strictly inside it (beyond rounding), each substep in the region of its midpoint.
//
// kPair: Phi at K / 2 as well (K even) into out_half.  The exact interval means are additive,
// so Delta C of an unsplit coarse step is the sum of those of its two fine steps (equal to its
// own harmonic sum to rounding) and costs only its Taylor step; a coarse step that contains a
// sector edge is computed as on its own grid.
template <int N, bool kEvenRows, bool kPair>
[[gnu::always_inline]] inline void plain_hsu_impl(const PlainHsuInput& in, double* out,
                                                  double* out_half) {
  PlainMat<N> Phi, Phic, Y, Ya;
  plain_identity<N>(Phi);
  plain_identity<N>(Phic);
  plain_identity<N>(Ya);  // set before use; quiets -Wmaybe-uninitialized
  const int K = in.K;
  const double d = kTwoPi / K;
  const double dc = kTwoPi / (K / 2);  // the coarse step (kPair)
  const Phasor step = phasor(d);
  double zc = 1.0, zs = 0.0;  // e^{i mid_i}, the rotation recurrence of phasor_grid()
  double w[kPlainMaxHarmonics], dsub[kPlainMaxHarmonics / 2 + 2];
  auto split_inside = [&](double a, double b) __attribute__((always_inline)) {
    return detail::edge_inside(a, b, in.edges, in.n_edges);
  };
  auto substep = [&](double a, double b, PlainMat<N>& P) __attribute__((always_inline)) {
    const double delta = b - a;
    const double mid = 0.5 * (a + b);
    const int r = plain_set(in, mid);
    dsub[0] = 1.0;
    for (int k = 1; k <= in.max_order; ++k) dsub[k] = sinc(k * 0.5 * delta);
    const Phasor z = phasor(mid);
    plain_weights(z.c, z.s, in.H[r], dsub, delta, w);
    plain_weighted_sum_t<N, kEvenRows>(in.A[r], in.H[r], w, Y);
    plain_taylor4_step_t<N>(Y, P);
  };
  auto split_step = [&](double a, double b, PlainMat<N>& P) __attribute__((always_inline)) {
    detail::split_step(
        a, b, in.edges, in.n_edges, [&](double lo, double hi) __attribute__((always_inline)) {
          substep(lo, hi, P);
        });
  };
  for (int i = 0; i < K; ++i) {
    if (i % kReseed == 0) {
      const Phasor z = phasor(0.5 * d + i * d);
      zc = z.c;
      zs = z.s;
    } else {
      const double t = zc * step.c - zs * step.s;
      zs = zc * step.s + zs * step.c;
      zc = t;
    }
    const double a = i * d;
    const double b = (i + 1 == K) ? kTwoPi : (i + 1) * d;
    const bool split = split_inside(a, b);
    if (!split) {
      const int r = plain_set(in, 0.5 * (a + b));
      plain_weights(zc, zs, in.H[r], in.damp, b - a, w);
      plain_weighted_sum_t<N, kEvenRows>(in.A[r], in.H[r], w, Y);
      plain_taylor4_step_t<N>(Y, Phi);
    } else {
      split_step(a, b, Phi);
    }
    if constexpr (kPair) {
      if (i % 2 == 0) {
        Ya = Y;  // X^T of the coarse step's first half (used only if the coarse step is unsplit)
        continue;
      }
      // Coarse step i / 2 has the ends of fine steps i - 1 and i (dc = 2 d exactly), so if no
      // edge is inside it, none is inside either fine step and Ya, Y hold their X^T.
      const int ci = i / 2;
      const double ac = ci * dc;
      const double bc = (ci + 1 == K / 2) ? kTwoPi : (ci + 1) * dc;
      if (!split_inside(ac, bc)) {
        for (int e = 0; e < N * N / 4; ++e) Y.c[e] += Ya.c[e];
        plain_taylor4_step_t<N>(Y, Phic);
      } else {
        split_step(ac, bc, Phic);
      }
    }
  }
  plain_store_transposed<N>(Phi, out);
  if constexpr (kPair) plain_store_transposed<N>(Phic, out_half);
}

// Whether the plain Hsu kernel of n states sums the harmonics into the even rows only (above).
constexpr bool plain_even_rows(int n) { return n == 4; }

// One clone pair per state size with a plain kernel (plain_size()) and variant: P Phi at K / 2
// as well.  in.A holds the transposed harmonics (plain_hsu_input()).
#define FLAPLAG_PLAIN_HSU_VARIANT(N, NAME, P)                                \
  __attribute__((target_clones("avx2", "default"))) void plain_hsu##N##NAME( \
      const PlainHsuInput& in, double* Phi, double* half) {                  \
    plain_hsu_impl<N, plain_even_rows(N), P>(in, Phi, half);                 \
  }
#define FLAPLAG_PLAIN_HSU(N)                                              \
  FLAPLAG_PLAIN_HSU_VARIANT(N, _single, false)                            \
  FLAPLAG_PLAIN_HSU_VARIANT(N, _pair, true)                               \
  void plain_hsu##N(const PlainHsuInput& in, double* Phi, double* half) { \
    if (half != nullptr)                                                  \
      plain_hsu##N##_pair(in, Phi, half);                                 \
    else                                                                  \
      plain_hsu##N##_single(in, Phi, nullptr);                            \
  }
FLAPLAG_PLAIN_HSU(4)
FLAPLAG_PLAIN_HSU(8)
FLAPLAG_PLAIN_HSU(12)
#undef FLAPLAG_PLAIN_HSU_VARIANT
#undef FLAPLAG_PLAIN_HSU

// exp(X) by scaling and squaring with the degree-12 Taylor polynomial: X / 2^s with
// ||X / 2^s||_1 <= 1/4 (then the truncation is below 0.25^13 / 13! = 2.4e-18 relative), the
// polynomial in Paterson-Stockmeyer form with X^2, X^3, X^4 (five products in all), then s
// squarings.  X is overwritten with exp(X); a non-finite X gives a non-finite result.
template <int N>
[[gnu::always_inline]] inline void plain_expm(PlainMat<N>& X) {
  constexpr int V = N * N / 4;
  double norm = 0.0;
  for (int j = 0; j < N; ++j) {
    double col = 0.0;
    for (int i = 0; i < N; ++i) col += std::abs(X.at(i, j));
    norm = std::max(norm, col);
  }
  if (!std::isfinite(norm)) {
    for (V4& v : X.c) v = v * std::numeric_limits<double>::quiet_NaN();
    return;
  }
  int s = 0;
  if (norm > 0.25) {
    int e = 0;
    std::frexp(norm / 0.25, &e);  // norm / 0.25 < 2^e
    s = e;
  }
  const double scale = std::ldexp(1.0, -s);
  for (V4& v : X.c) v = v * scale;
  PlainMat<N> X2, X3, X4, P, Q;
  plain_mul<N>(X, X, X2);
  plain_mul<N>(X2, X, X3);
  plain_mul<N>(X2, X2, X4);
  // c_j = 1 / j!
  constexpr double c[13] = {1.0,
                            1.0,
                            1.0 / 2,
                            1.0 / 6,
                            1.0 / 24,
                            1.0 / 120,
                            1.0 / 720,
                            1.0 / 5040,
                            1.0 / 40320,
                            1.0 / 362880,
                            1.0 / 3628800,
                            1.0 / 39916800,
                            1.0 / 479001600};
  // B_k = c_{4k} I + c_{4k+1} X + c_{4k+2} X^2 + c_{4k+3} X^3; p = B0 + X4 (B1 + X4 (B2 + c12 X4)).
  auto block = [&](int k, PlainMat<N>& B) __attribute__((always_inline)) {
    for (int e = 0; e < V; ++e)
      B.c[e] = X.c[e] * c[4 * k + 1] + X2.c[e] * c[4 * k + 2] + X3.c[e] * c[4 * k + 3];
    plain_add_diagonal<N>(B, c[4 * k]);
  };
  block(2, P);
  for (int e = 0; e < V; ++e) P.c[e] += X4.c[e] * c[12];
  plain_mul<N>(X4, P, Q);
  block(1, P);
  for (int e = 0; e < V; ++e) Q.c[e] += P.c[e];
  plain_mul<N>(X4, Q, P);
  block(0, Q);
  for (int e = 0; e < V; ++e) X.c[e] = P.c[e] + Q.c[e];
  for (int k = 0; k < s; ++k) {
    plain_mul<N>(X, X, P);
    X = P;
  }
}

// A at psi in the given region into X (point values of the harmonics).
template <int N>
[[gnu::always_inline]] inline void plain_point(const PlainHsuInput& in, int r, double psi,
                                               double* w, PlainMat<N>& X) {
  const Phasor z = phasor(psi);
  plain_weights(z.c, z.s, in.H[r], in.ones, 1.0, w);
  plain_weighted_sum<N>(in.A[r], in.H[r], w, X);
}

// Fourth-order Magnus (gauss::magnus4_step) on the given grid, as Kernel::magnus.
template <int N>
[[gnu::always_inline]] inline void plain_magnus_impl(const PlainHsuInput& in, const Segment* grid,
                                                     int count, double* out) {
  constexpr int V = N * N / 4;
  PlainMat<N> Phi, A1, A2, Om, P, Q;
  plain_identity<N>(Phi);
  double w[kPlainMaxHarmonics];
  for (int i = 0; i < count; ++i) {
    const Segment& sg = grid[i];
    const gauss::Magnus4Step st = gauss::magnus4_step(sg.a, sg.b);
    plain_point<N>(in, sg.set, st.psi1, w, A1);
    plain_point<N>(in, sg.set, st.psi2, w, A2);
    plain_mul<N>(A2, A1, P);
    plain_mul<N>(A1, A2, Q);
    for (int e = 0; e < V; ++e) Om.c[e] = (A1.c[e] + A2.c[e]) * st.c1 + (P.c[e] - Q.c[e]) * st.c2;
    plain_expm<N>(Om);
    plain_mul<N>(Om, Phi, P);
    Phi = P;
  }
  plain_store<N>(Phi, out);
}

#define FLAPLAG_PLAIN_MAGNUS(N)                                               \
  __attribute__((target_clones("avx2", "default"))) void plain_magnus##N(     \
      const PlainHsuInput& in, const Segment* grid, int count, double* Phi) { \
    plain_magnus_impl<N>(in, grid, count, Phi);                               \
  }
FLAPLAG_PLAIN_MAGNUS(4)
FLAPLAG_PLAIN_MAGNUS(8)
FLAPLAG_PLAIN_MAGNUS(12)
#undef FLAPLAG_PLAIN_MAGNUS

// The state sizes with a plain kernel.  Not 16: there the wide kernel's Magnus, the default, is
// 15-30 % faster than the unrolled one (measured side by side), and the unrolled kernels of 16
// states were 12 s of the compile time of the numerics; Hsu, not the default there, takes
// Kernel<N> at 16 states, in about twice the time.  (At 20 states the unrolled kernels spill
// registers: 0.67 ms against Eigen's 0.42 ms for a K = 50 point.)
bool plain_size(int n) { return n == 4 || n == 8 || n == 12; }

// The input of the plain kernels for grids of K equal steps; false when they do not apply
// (n without a plain kernel, or more than kPlainMaxHarmonics harmonics).
bool plain_input(const PeriodicSystem& sys, int K, PlainHsuInput& in) {
  // evaluator pieces: transition_varying.cc
  if (!plain_size(sys.n) || sys.has_evaluator() || sys.sets.size() > 2 ||
      sys.pieces.size() > static_cast<std::size_t>(kPlainMaxPieces))
    return false;
  in.K = K;
  for (std::size_t r = 0; r < sys.sets.size(); ++r) {
    const HarmonicSet& set = sys.sets[r];
    const int H = static_cast<int>(set.A.size());
    if (H > kPlainMaxHarmonics) return false;
    in.H[r] = H;
    for (int h = 0; h < H; ++h) in.A[r][h] = set.A[static_cast<std::size_t>(h)].data();
    in.max_order = std::max(in.max_order, H / 2);
  }
  for (const SystemPiece& p : sys.pieces) {
    if (in.n_pieces > 0) in.edges[in.n_edges++] = p.begin;
    in.piece_end[in.n_pieces] = p.end;
    in.piece_set[in.n_pieces++] = p.set;
  }
  in.damp[0] = 1.0;
  for (int k = 1; k <= in.max_order; ++k) in.damp[k] = sinc(k * 0.5 * kTwoPi / K);
  for (double& one : in.ones) one = 1.0;
  return true;
}

// The plain Hsu kernel's input: plain_input() with the harmonics transposed into `work` (the
// kernel works on transposes); false also for 4 states whose odd rows vary (plain_even_rows()).
bool plain_hsu_input(const PeriodicSystem& sys, int K, std::vector<double>& work,
                     PlainHsuInput& in) {
  if (!plain_input(sys, K, in)) return false;
  const int n = sys.n;
  const bool same = sys.sets.size() == 1;  // set 1 is set 0
  const std::size_t count = static_cast<std::size_t>(in.H[0] + (same ? 0 : in.H[1]));
  if (work.size() < count * n * n) work.resize(count * n * n);
  double* t = work.data();
  if (plain_even_rows(n))
    for (int r = 0; r < (same ? 1 : 2); ++r)
      for (int h = 1; h < in.H[r]; ++h) {
        const double* a = in.A[r][h];
        for (int j = 0; j < n; ++j)
          for (int i = 1; i < n; i += 2)
            if (a[j * n + i] != 0.0) return false;
      }
  for (int r = 0; r < (same ? 1 : 2); ++r) {
    for (int h = 0; h < in.H[r]; ++h, t += n * n) {
      const double* a = in.A[r][h];
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) t[i * n + j] = a[j * n + i];
      in.A[r][h] = t;
    }
  }
  if (same)
    for (int h = 0; h < in.H[1]; ++h) in.A[1][h] = in.A[0][h];
  return true;
}

// Hsu by the plain kernel when it applies (plain_size(n), J = 4, few harmonics); false otherwise.
// half != null: Phi at K / 2 as well (K even).
bool plain_hsu(const PeriodicSystem& sys, int K, int J, Eigen::MatrixXd& phi,
               Eigen::MatrixXd* half = nullptr) {
  // The transposed harmonics, per thread: nothing allocates once they fit.
  thread_local std::vector<double> work;
  PlainHsuInput in;
  if (J != 4 || !plain_hsu_input(sys, K, work, in)) return false;
  phi.resize(sys.n, sys.n);
  if (half != nullptr) half->resize(sys.n, sys.n);
  double* h = half != nullptr ? half->data() : nullptr;
  switch (sys.n) {
    case 4:
      plain_hsu4(in, phi.data(), h);
      break;
    case 8:
      plain_hsu8(in, phi.data(), h);
      break;
    default:
      plain_hsu12(in, phi.data(), h);
      break;
  }
  return true;
}

// Magnus on `grid` by the plain kernel when it applies; false otherwise.
bool plain_magnus(const PeriodicSystem& sys, const std::vector<Segment>& grid,
                  Eigen::MatrixXd& phi) {
  PlainHsuInput in;
  if (!plain_input(sys, 1, in)) return false;
  phi.resize(sys.n, sys.n);
  const int count = static_cast<int>(grid.size());
  switch (sys.n) {
    case 4:
      plain_magnus4(in, grid.data(), count, phi.data());
      break;
    case 8:
      plain_magnus8(in, grid.data(), count, phi.data());
      break;
    default:
      plain_magnus12(in, grid.data(), count, phi.data());
      break;
  }
  return true;
}

// ---- Magnus on many states (more than 8, no plain kernel) -------------------------------------
//
// The models with more than 8 states but 12 (4 x 1, 3 x 2, 4 x 4, 5 x 5, ...) have no plain
// kernel; on Eigen's dynamic matrices a Magnus step costs about 26 us at 20 states (measured), most
// of it Eigen's Pade exponential (an LU solve and, at the norms of the rotor's Omega, four
// squarings) and the packing of its blocked products, built for SSE2 in a baseline build.  This
// kernel takes a few times less (bench/README.md, "Many modes") by three changes:
// - the state is balanced once per system: D = diag(2^e_i) from the Parlett-Reinsch iteration
//   (radix 2) on sum_h |A_h| of both regions, so that the exponential works on D^-1 Omega D,
//   whose norm is set by the frequencies rather than by the stiffness entries (20 states at 436
//   steps: ||Omega||_1 from 76 to 1.6).  Powers of two make the similarity exact:
//   exp(D^-1 Omega D) = D^-1 exp(Omega) D and Phi = D Phi_b D^-1 with no rounding of their own;
// - exp by plain_expm's rule (degree-12 Taylor polynomial, ||X||_1 <= 1/4 after scaling, five
//   products, then the squarings), no solve;
// - products on columns of four-double vectors (the size padded to a multiple of four; the
//   padding stays zero in A and the identity in exp and Phi, so it never reaches the states),
//   in AVX2 and baseline clones with the same operations, hence the same bits, in either.

// A wide matrix: np x np column-major, np = n rounded up to a multiple of 4, each column as
// np / 4 vectors of four doubles.
struct WideShape {
  int n = 0, np = 0, q = 0;  // states, padded size, vectors per column
  std::size_t size() const { return static_cast<std::size_t>(np) * q; }
};

// Zeroed storage of `count` V4 aligned for vector loads (a std::vector<V4> would not be: the
// vector type's alignment does not survive as a template argument).
class WideBuffer {
 public:
  WideBuffer() = default;
  explicit WideBuffer(std::size_t count) { resize(count); }
  WideBuffer(const WideBuffer&) = delete;
  WideBuffer& operator=(const WideBuffer&) = delete;
  void resize(std::size_t count) {
    raw_.assign(4 * count + 4, 0.0);
    void* p = raw_.data();
    std::size_t space = raw_.size() * sizeof(double);
    data_ = static_cast<V4*>(std::align(sizeof(V4), count * sizeof(V4), p, space));
  }
  V4* data() { return data_; }
  const V4* data() const { return data_; }

 private:
  std::vector<double> raw_;
  V4* data_ = nullptr;
};

// The balanced, padded harmonics of both regions and the sector, for the wide kernel.
struct WideInput {
  WideShape shape;
  int H[2] = {0, 0};
  WideBuffer A[2];  // harmonic h of set r at A[r].data() + h * shape.size()
};

// C = A B on wide matrices: column j of C is sum_k A(:, k) B(k, j), in blocks of B vectors of
// a column whose sums stay in registers.
template <int B>
[[gnu::always_inline]] inline void wide_mul_block(const V4* A, const V4* bcol, V4* ccol, int np,
                                                  int q, int q0) {
  V4 acc[B];
  const double b0 = bcol[0][0];
  for (int i = 0; i < B; ++i) acc[i] = A[q0 + i] * b0;
  for (int k = 1; k < np; ++k) {
    const double bk = bcol[k / 4][k % 4];
    const V4* ak = A + static_cast<std::size_t>(k) * q + q0;
    for (int i = 0; i < B; ++i) acc[i] += ak[i] * bk;
  }
  for (int i = 0; i < B; ++i) ccol[q0 + i] = acc[i];
}

[[gnu::always_inline]] inline void wide_mul(const WideShape& s, const V4* A, const V4* B, V4* C) {
  // blocks of at most five vectors (ten AVX registers of sums and loads), as even as possible
  const int blocks = (s.q + 4) / 5;
  for (int j = 0; j < s.np; ++j) {
    const V4* bcol = B + static_cast<std::size_t>(j) * s.q;
    V4* ccol = C + static_cast<std::size_t>(j) * s.q;
    int q0 = 0;
    for (int b = 0; b < blocks; ++b) {
      const int width = (s.q - q0) / (blocks - b);
      switch (width) {
        case 1:
          wide_mul_block<1>(A, bcol, ccol, s.np, s.q, q0);
          break;
        case 2:
          wide_mul_block<2>(A, bcol, ccol, s.np, s.q, q0);
          break;
        case 3:
          wide_mul_block<3>(A, bcol, ccol, s.np, s.q, q0);
          break;
        case 4:
          wide_mul_block<4>(A, bcol, ccol, s.np, s.q, q0);
          break;
        default:
          wide_mul_block<5>(A, bcol, ccol, s.np, s.q, q0);
          break;
      }
      q0 += width;
    }
  }
}

// m += v I over the padded size (plain_add_diagonal's -0.0 lanes: the bits of adding v alone).
[[gnu::always_inline]] inline void wide_add_diagonal(const WideShape& s, V4* m, double v) {
  for (int j = 0; j < s.np; ++j) {
    V4 d = {-0.0, -0.0, -0.0, -0.0};
    d[j % 4] = v;
    m[static_cast<std::size_t>(j) * s.q + j / 4] += d;
  }
}

// exp(X) into X by plain_expm's rule; t holds five wide matrices of scratch.
[[gnu::always_inline]] inline void wide_expm(const WideShape& s, V4* X, V4* t) {
  const std::size_t size = s.size();
  double norm = 0.0;
  for (int j = 0; j < s.np; ++j) {
    V4 col = {0.0, 0.0, 0.0, 0.0};
    for (int i = 0; i < s.q; ++i) {
      const V4 x = X[static_cast<std::size_t>(j) * s.q + i];
      col += x < 0.0 ? -x : x;
    }
    norm = std::max(norm, col[0] + col[1] + col[2] + col[3]);
  }
  if (!std::isfinite(norm)) {
    for (std::size_t e = 0; e < size; ++e) X[e] = X[e] * std::numeric_limits<double>::quiet_NaN();
    return;
  }
  int sq = 0;
  if (norm > 0.25) {
    int e = 0;
    std::frexp(norm / 0.25, &e);  // norm / 0.25 < 2^e
    sq = e;
  }
  const double scale = std::ldexp(1.0, -sq);
  for (std::size_t e = 0; e < size; ++e) X[e] = X[e] * scale;
  V4 *X2 = t, *X3 = t + size, *X4 = t + 2 * size, *P = t + 3 * size, *Q = t + 4 * size;
  wide_mul(s, X, X, X2);
  wide_mul(s, X2, X, X3);
  wide_mul(s, X2, X2, X4);
  constexpr double c[13] = {1.0,
                            1.0,
                            1.0 / 2,
                            1.0 / 6,
                            1.0 / 24,
                            1.0 / 120,
                            1.0 / 720,
                            1.0 / 5040,
                            1.0 / 40320,
                            1.0 / 362880,
                            1.0 / 3628800,
                            1.0 / 39916800,
                            1.0 / 479001600};
  // B_k = c_{4k} I + c_{4k+1} X + c_{4k+2} X^2 + c_{4k+3} X^3; p = B0 + X4 (B1 + X4 (B2 + c12 X4)).
  auto block = [&](int k, V4* B) __attribute__((always_inline)) {
    for (std::size_t e = 0; e < size; ++e)
      B[e] = X[e] * c[4 * k + 1] + X2[e] * c[4 * k + 2] + X3[e] * c[4 * k + 3];
    wide_add_diagonal(s, B, c[4 * k]);
  };
  block(2, P);
  for (std::size_t e = 0; e < size; ++e) P[e] += X4[e] * c[12];
  wide_mul(s, X4, P, Q);
  block(1, P);
  for (std::size_t e = 0; e < size; ++e) Q[e] += P[e];
  wide_mul(s, X4, Q, P);
  block(0, Q);
  for (std::size_t e = 0; e < size; ++e) X[e] = P[e] + Q[e];
  for (int k = 0; k < sq; ++k) {
    wide_mul(s, X, X, P);
    std::copy(P, P + size, X);
  }
}

// A at psi in region r into X (point values of the harmonics).
[[gnu::always_inline]] inline void wide_point(const WideInput& in, int r, double psi, V4* X) {
  const WideShape& s = in.shape;
  const std::size_t size = s.size();
  double w[kPlainMaxHarmonics], ones[kPlainMaxHarmonics / 2 + 2];
  for (double& one : ones) one = 1.0;
  const Phasor z = phasor(psi);
  plain_weights(z.c, z.s, in.H[r], ones, 1.0, w);
  const V4* a = in.A[r].data();
  for (std::size_t e = 0; e < size; ++e) X[e] = a[e] * w[0];
  for (int h = 1; h < in.H[r]; ++h) {
    const V4* ah = a + h * size;
    const double wh = w[h];
    for (std::size_t e = 0; e < size; ++e) X[e] += ah[e] * wh;
  }
}

// Fourth-order Magnus (gauss::magnus4_step) on the given grid into phi (a wide matrix);
// work holds nine wide matrices of scratch.
__attribute__((target_clones("avx2", "default"))) void wide_magnus_steps(const WideInput& in,
                                                                         const Segment* grid,
                                                                         int count, V4* phi,
                                                                         V4* work) {
  const WideShape& s = in.shape;
  const std::size_t size = s.size();
  V4 *A1 = work, *A2 = work + size, *P = work + 2 * size, *Q = work + 3 * size;
  V4* t = work + 4 * size;  // five matrices for wide_expm
  std::fill(phi, phi + size, V4{0.0, 0.0, 0.0, 0.0});
  wide_add_diagonal(s, phi, 1.0);
  for (int i = 0; i < count; ++i) {
    const Segment& sg = grid[i];
    const gauss::Magnus4Step st = gauss::magnus4_step(sg.a, sg.b);
    wide_point(in, sg.set, st.psi1, A1);
    wide_point(in, sg.set, st.psi2, A2);
    wide_mul(s, A2, A1, P);
    wide_mul(s, A1, A2, Q);
    for (std::size_t e = 0; e < size; ++e) A1[e] = (A1[e] + A2[e]) * st.c1 + (P[e] - Q[e]) * st.c2;
    wide_expm(s, A1, t);
    wide_mul(s, A1, phi, P);
    std::copy(P, P + size, phi);
  }
}

// Powers of two e_i that balance the state (Parlett & Reinsch, radix 2) on M = sum over the
// regions and harmonics of |A_h|: each state's off-diagonal row and column sums of
// D^-1 M D, D = diag(2^e_i), end within a factor of about 2 of each other.
std::vector<int> balancing_exponents(const PeriodicSystem& sys) {
  const int n = sys.n;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  for (const HarmonicSet& set : sys.sets)
    for (const Eigen::MatrixXd& a : set.A) m += a.cwiseAbs();
  std::vector<int> e(static_cast<std::size_t>(n), 0);
  for (int sweep = 0; sweep < 64; ++sweep) {
    bool done = true;
    for (int i = 0; i < n; ++i) {
      double c = m.col(i).sum() - m(i, i), r = m.row(i).sum() - m(i, i);
      if (!(c > 0.0 && r > 0.0 && std::isfinite(c + r))) continue;
      const double total = c + r;
      int f = 0;  // scale state i by 2^f
      while (c < r / 2.0 && f < 64) {
        c *= 4.0;
        ++f;
      }
      while (c >= r * 2.0 && f > -64) {
        c /= 4.0;
        --f;
      }
      if (f == 0 || !((c + r) / std::ldexp(1.0, f) < 0.95 * total)) continue;
      // D^-1 M D with d_i *= 2^f: column i times 2^f, row i over 2^f
      m.col(i) *= std::ldexp(1.0, f);
      m.row(i) *= std::ldexp(1.0, -f);
      e[static_cast<std::size_t>(i)] += f;
      done = false;
    }
    if (done) break;
  }
  return e;
}

// The wide kernel's input: the harmonics balanced by e (entry (i, j) times 2^(e_j - e_i), exact)
// and padded; false when the system has more harmonics than the kernel takes.
bool wide_input(const PeriodicSystem& sys, const std::vector<int>& e, WideInput& in) {
  WideShape& s = in.shape;
  s.n = sys.n;
  s.np = (sys.n + 3) / 4 * 4;
  s.q = s.np / 4;
  if (sys.sets.size() > 2) return false;
  for (std::size_t r = 0; r < sys.sets.size(); ++r) {
    const int H = static_cast<int>(sys.sets[r].A.size());
    if (H > kPlainMaxHarmonics) return false;
    in.H[r] = H;
    in.A[r].resize(static_cast<std::size_t>(H) * s.size());
    for (int h = 0; h < H; ++h) {
      V4* dst = in.A[r].data() + static_cast<std::size_t>(h) * s.size();
      const Eigen::MatrixXd& a = sys.sets[r].A[static_cast<std::size_t>(h)];
      for (int j = 0; j < s.n; ++j)
        for (int i = 0; i < s.n; ++i)
          dst[static_cast<std::size_t>(j) * s.q + i / 4][i % 4] =
              std::ldexp(a(i, j), e[static_cast<std::size_t>(j)] - e[static_cast<std::size_t>(i)]);
    }
  }
  return true;
}

// The state sizes that take the wide kernel: more than 8 states without a plain kernel.
bool wide_size(int n) { return n > 8 && !plain_size(n); }

// Magnus on `grid` by the wide kernel when it applies; false otherwise.
bool wide_magnus(const PeriodicSystem& sys, const std::vector<Segment>& grid,
                 Eigen::MatrixXd& phi) {
  if (!wide_size(sys.n) || sys.has_evaluator()) return false;
  const std::vector<int> e = balancing_exponents(sys);
  WideInput in;
  if (!wide_input(sys, e, in)) return false;
  const WideShape& s = in.shape;
  WideBuffer out(s.size()), work(9 * s.size());
  wide_magnus_steps(in, grid.data(), static_cast<int>(grid.size()), out.data(), work.data());
  // Phi = D Phi_b D^-1: entry (i, j) times 2^(e_i - e_j)
  phi.resize(s.n, s.n);
  for (int j = 0; j < s.n; ++j)
    for (int i = 0; i < s.n; ++i)
      phi(i, j) = std::ldexp(out.data()[static_cast<std::size_t>(j) * s.q + i / 4][i % 4],
                             e[static_cast<std::size_t>(i)] - e[static_cast<std::size_t>(j)]);
  return true;
}

// Runs `fn` with the kernel of the right dimension and returns a MatrixXd.
template <typename Fn>
Eigen::MatrixXd dispatch(const PeriodicSystem& sys, Fn&& fn) {
  switch (sys.n) {
    case 2: {
      Kernel<2> k(sys);
      return fn(k);
    }
    case 4: {
      Kernel<4> k(sys);
      return fn(k);
    }
    case 6: {
      Kernel<6> k(sys);
      return fn(k);
    }
    case 8: {
      Kernel<8> k(sys);
      return fn(k);
    }
    default: {
      Kernel<Eigen::Dynamic> k(sys);
      return fn(k);
    }
  }
}

}  // namespace

// The names are the enum's table (floquet.h): written once.
const char* method_name(TransitionMethod m) {
  const char* name = enum_name(m);
  return *name != '\0' ? name : "unknown";
}

TransitionMethod automatic_method(int state_size) {
  if (state_size < 1)
    throw InvalidInput("state_size", std::to_string(state_size), "must be at least 1");
  return state_size <= 4 ? TransitionMethod::Hsu : TransitionMethod::Magnus4;
}

bool method_from_name(const std::string& name, TransitionMethod* method) {
  return enum_from_name(name, method);
}

std::string method_names() { return enum_names<TransitionMethod>(); }

Eigen::MatrixXd transition_matrix_rk4(const PeriodicSystem& sys, int steps) {
  check_count("steps", steps);
  sys.validate();
  if (sys.has_evaluator()) return detail::varying_rk4(sys, steps);  // transition_varying.cc
  return dispatch(sys, [&](auto& k) { return Eigen::MatrixXd(k.rk4(steps)); });
}

void transition_matrix_hsu(const PeriodicSystem& sys, int intervals, int terms,
                           Eigen::MatrixXd* phi) {
  if (phi == nullptr) throw InvalidInput("phi", "null", "a matrix to fill is required");
  check_count("intervals", intervals);
  check_count("terms", terms, TransitionOptions::kMaxTerms);
  sys.validate();
  if (sys.has_evaluator()) {
    *phi = detail::varying_hsu(sys, intervals, terms);
  } else if (!plain_hsu(sys, intervals, terms, *phi)) {
    *phi = dispatch(sys, [&](auto& k) { return Eigen::MatrixXd(k.hsu(intervals, terms)); });
  }
}

void transition_matrix_hsu_pair(const PeriodicSystem& sys, int intervals, int terms,
                                Eigen::MatrixXd* phi, Eigen::MatrixXd* phi_half) {
  if (phi == nullptr || phi_half == nullptr)
    throw InvalidInput("phi", "null", "two matrices to fill are required");
  check_count("intervals", intervals);
  if (intervals % 2 != 0)
    throw InvalidInput("intervals", std::to_string(intervals), "must be even");
  check_count("terms", terms, TransitionOptions::kMaxTerms);
  sys.validate();
  if (!plain_hsu(sys, intervals, terms, *phi, phi_half)) {  // no plain kernel: two products
    transition_matrix_hsu(sys, intervals, terms, phi);
    transition_matrix_hsu(sys, intervals / 2, terms, phi_half);
  }
}

Eigen::MatrixXd transition_matrix_hsu(const PeriodicSystem& sys, int intervals, int terms) {
  Eigen::MatrixXd phi;
  transition_matrix_hsu(sys, intervals, terms, &phi);
  return phi;
}

// Accuracy: Magnus4 is fourth order and symmetric, so Phi_h - Phi = c4 h^4 + c6 h^6 + ...
// With Phi_h (steps) and Phi_{h/2} (every substep bisected), the returned
//   (16 Phi_{h/2} - Phi_h) / 15
// is sixth-order accurate, and error_estimate = ||Phi_{h/2} - Phi_h||_max / 15 estimates the
// error of Phi_{h/2}, i.e. it is a conservative (pessimistic) bound for the returned matrix
// once the steps resolve A(psi).  Measured on the rotor-like 4x4 system rotor_like() of
// tests/periodic_fixtures.h (harmonics to 4/rev, a reversed sector, max |A_ij| = 5.7, ||A||_F
// up to 6.2), against 1000 steps, by transition_test: steps = 25 / 50 / 100 give Phi to
// 1e-7 / 2e-9 / 3e-11 relative (sixth order), while the estimate is 1e-5 / 1e-6 / 8e-8, i.e.
// two to three orders of magnitude pessimistic.
TransitionResult transition_matrix_magnus4(const PeriodicSystem& sys, int steps) {
  check_count("steps", steps);
  sys.validate();
  if (sys.has_evaluator()) return detail::varying_magnus4(sys, steps);
  const std::vector<Segment> coarse = detail::equal_grid(sys, steps);
  const std::vector<Segment> fine = detail::bisect(coarse);
  Eigen::MatrixXd ph, ph2;
  if (!plain_magnus(sys, coarse, ph) && !wide_magnus(sys, coarse, ph))
    ph = dispatch(sys, [&](auto& k) { return Eigen::MatrixXd(k.magnus(coarse)); });
  if (!plain_magnus(sys, fine, ph2) && !wide_magnus(sys, fine, ph2))
    ph2 = dispatch(sys, [&](auto& k) { return Eigen::MatrixXd(k.magnus(fine)); });
  TransitionResult out;
  out.phi = (16.0 * ph2 - ph) / 15.0;
  out.error_estimate = (ph2 - ph).cwiseAbs().maxCoeff() / 15.0;
  return out;
}

Eigen::MatrixXd transition_matrix_magnus4_level(const PeriodicSystem& sys, int steps,
                                                int bisections) {
  check_count("steps", steps);
  if (bisections < 0 || bisections > 20)
    throw InvalidInput("bisections", std::to_string(bisections), "must be 0..20");
  if (static_cast<double>(steps) * std::ldexp(1.0, bisections) > TransitionOptions::kMaxSteps)
    throw InvalidInput(
        "bisections", std::to_string(bisections),
        "steps * 2^bisections must be at most " + std::to_string(TransitionOptions::kMaxSteps));
  sys.validate();
  if (sys.has_evaluator())
    throw InvalidInput("sys", "varying region",
                       "the Magnus levels are for sector systems (transition_magnus4 handles the "
                       "varying region)");
  std::vector<Segment> grid = detail::equal_grid(sys, steps);
  for (int b = 0; b < bisections; ++b) grid = detail::bisect(grid);
  Eigen::MatrixXd phi;
  if (!plain_magnus(sys, grid, phi) && !wide_magnus(sys, grid, phi))
    phi = dispatch(sys, [&](auto& k) { return Eigen::MatrixXd(k.magnus(grid)); });
  return phi;
}

std::optional<InvalidInput> TransitionOptions::Validate() const {
  const bool known = method == TransitionMethod::RK4 || method == TransitionMethod::Hsu ||
                     method == TransitionMethod::Magnus4 || method == TransitionMethod::Automatic;
  return Requirements()
      .Require(known,
               [&] {
                 return InvalidInput("method", std::to_string(static_cast<int>(method)),
                                     "unknown method");
               })
      .InRanges(*this)
      .Result();
}

TransitionResult transition_matrix(const PeriodicSystem& sys, const TransitionOptions& opt) {
  opt.Check();
  if (opt.steps == TransitionOptions::kAutomatic)
    throw InvalidInput("steps", "0", "transition_matrix needs a fixed step count");
  const TransitionMethod method =
      opt.method == TransitionMethod::Automatic ? automatic_method(sys.n) : opt.method;
  switch (method) {
    case TransitionMethod::RK4:
      return {transition_matrix_rk4(sys, opt.steps), 0.0};
    case TransitionMethod::Hsu:
      return {transition_matrix_hsu(sys, opt.steps, opt.terms), 0.0};
    case TransitionMethod::Magnus4:
      return transition_matrix_magnus4(sys, opt.steps);
    case TransitionMethod::Automatic:  // resolved above
      break;
  }
  throw InvalidInput("method", std::to_string(static_cast<int>(opt.method)), "unknown method");
}

}  // namespace flaplag
