// flaplag — aerodynamic spanwise integrals through exact Chebyshev antiderivatives.
#include "flaplag/blade/aero_integrals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/core/format.h"

namespace flaplag {

AeroIntegrals::AeroIntegrals(const model::ModelDescriptor& m, const ModeSet& modes,
                             const SpanGeometry& g)
    : a_(g.tip_loss_a), b_(g.tip_loss_b), e1_(g.e1), lr_(g.lr) {
  validate(g);
  if (!(a_ < b_)) {
    throw InvalidInput("tip_loss_a", round_trip_text(a_),
                       "the aerodynamic span needs A < B = " + round_trip_text(b_));
  }
  count_ = m.n_aero;
  // One piece for a smooth blade; a blade table's corners (and the mesh of finite-element modes)
  // inside [A, B] end pieces, each with a
  // degree in proportion to its length (the integrands are smooth within a piece).
  std::vector<double> edges = {a_};
  for (double c : blade_corners(modes))
    if (c > a_ + 1e-9 && c < b_ - 1e-9) edges.push_back(c);
  edges.push_back(b_);
  const std::size_t m_count = static_cast<std::size_t>(count_);
  std::vector<double> start(m_count, 0.0);
  for (std::size_t p = 0; p + 1 < edges.size(); ++p) {
    const double lo = edges[p], hi = edges[p + 1];
    int n = kDegree;
    if (edges.size() > 2) {
      n = std::clamp(static_cast<int>(std::ceil(kDegree * (hi - lo) / (b_ - a_))) + 16, 16,
                     kDegree);
    }
    Piece piece{lo, hi, n + 2, coef_.size(), start};
    add_piece(m, modes, g, piece, n);
    pieces_.push_back(piece);
    // int_A^{hi} = start + the piece's antiderivative at its right end (t = 1: sum of C_i).
    for (std::size_t j = 0; j < m_count; ++j) {
      double at_plus1 = 0.0;
      for (int i = 0; i < piece.terms; ++i) at_plus1 += coef_[piece.offset + i * m_count + j];
      start[j] += at_plus1;
    }
  }
  // Integrands that vanish identically (the twist integrals of an untwisted blade) are 0 at
  // every split point: the recurrences run over the others only.
  for (int j = 0; j < count_; ++j) {
    bool live = false;
    for (const Piece& p : pieces_)
      for (int i = 0; i < p.terms && !live; ++i)
        live = coef_[p.offset + static_cast<std::size_t>(i) * m_count + j] != 0.0;
    if (live) live_.push_back(j);
  }
  if (live_.size() < m_count) {
    const std::size_t live = live_.size();
    std::vector<double> compact;
    for (Piece& p : pieces_) {
      const std::size_t offset = compact.size();
      for (int i = 0; i < p.terms; ++i)
        for (std::size_t k = 0; k < live; ++k)
          compact.push_back(coef_[p.offset + static_cast<std::size_t>(i) * m_count + live_[k]]);
      p.offset = offset;
      std::vector<double> start_live(live);
      for (std::size_t k = 0; k < live; ++k) start_live[k] = p.start[live_[k]];
      p.start = std::move(start_live);
    }
    coef_ = std::move(compact);
  }
  partial(b_, normal_);
}

namespace {

// cos(pi i k / n), i, k = 0 .. n (row i), for the discrete cosine transform.
std::vector<double> cosine_table(int n) {
  std::vector<double> table(static_cast<std::size_t>((n + 1) * (n + 1)));
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= n; ++k) table[i * (n + 1) + k] = std::cos(kPi * i * k / n);
  return table;
}

// The table of a degree; that of kDegree (every smooth blade) made once per process.
const std::vector<double>& cosines(int n, std::vector<double>& scratch) {
  static const std::vector<double> common = cosine_table(AeroIntegrals::kDegree);
  if (n == AeroIntegrals::kDegree) return common;
  scratch = cosine_table(n);
  return scratch;
}

}  // namespace

void AeroIntegrals::add_piece(const model::ModelDescriptor& m, const ModeSet& modes,
                              const SpanGeometry& g, const Piece& piece, int n) {
  const double lo = piece.lo, hi = piece.hi;
  // Chebyshev-Gauss-Lobatto nodes on [lo, hi].
  std::vector<double> t(n + 1), x0(n + 1);
  for (int k = 0; k <= n; ++k) {
    t[k] = std::cos(kPi * k / n);
    x0[k] = 0.5 * (lo + hi) + 0.5 * (hi - lo) * t[k];
  }
  const double half = 0.5 * (hi - lo);
  std::vector<double> scratch;
  const std::vector<double>& cos_table = cosines(n, scratch);
  const std::vector<std::vector<double>> values = aero_integrands(m, modes, g, x0);
  const std::size_t nj = static_cast<std::size_t>(m.n_aero);
  // The Chebyshev coefficients c_i of every interpolant (discrete cosine transform, O(n^2)
  // once), the integrands side by side: node k's end weight times f_j(x_k) at wf[k nj + j],
  // c_i of integrand j at c[i nj + j].  Each sum runs over k in order, as one integrand's would.
  std::vector<double> wf((n + 1) * nj), c((n + 1) * nj), s(nj);
  for (int k = 0; k <= n; ++k) {
    const double w = (k == 0 || k == n) ? 0.5 : 1.0;
    for (std::size_t j = 0; j < nj; ++j) wf[k * nj + j] = w * values[j][k];
  }
  for (int i = 0; i <= n; ++i) {
    std::fill(s.begin(), s.end(), 0.0);
    for (int k = 0; k <= n; ++k) {
      const double ct = cos_table[i * (n + 1) + k];
      const double* f = &wf[k * nj];
      for (std::size_t j = 0; j < nj; ++j) s[j] += f[j] * ct;
    }
    for (std::size_t j = 0; j < nj; ++j)
      c[i * nj + j] = s[j] * 2.0 / n * ((i == 0 || i == n) ? 0.5 : 1.0);
  }
  const int terms = n + 2;
  coef_.resize(coef_.size() + static_cast<std::size_t>(terms) * count_, 0.0);
  std::vector<double> C(n + 2);
  for (std::size_t j = 0; j < nj; ++j) {
    // Antiderivative in t: C_i = (c_{i-1} - c_{i+1}) / (2 i), i >= 1; C_0 fixes F(-1) = 0.
    for (int i = 1; i <= n + 1; ++i) {
      const double cm = i - 1 == 0 ? 2.0 * c[j] : c[(i - 1) * nj + j];
      const double cp = i + 1 <= n ? c[(i + 1) * nj + j] : 0.0;
      C[i] = (cm - cp) / (2.0 * i) * half;
    }
    double at_minus1 = 0.0;
    for (int i = 1; i <= n + 1; ++i) at_minus1 += (i % 2 == 0 ? 1.0 : -1.0) * C[i];
    C[0] = -at_minus1;
    for (int i = 0; i < terms; ++i)
      coef_[piece.offset + static_cast<std::size_t>(i) * count_ + j] = C[i];
  }
}

namespace {

// The Clenshaw recurrences for sum_i C_i T_i(t) of m integrals side by side (coefficient i of
// integral j at coef[i * stride + j], m <= stride): b1 ends as the sums, b2 is scratch; both
// start at zero.  The same operations per integral as one recurrence at a time, so any m gives
// the same bits for the integrals it covers.  An AVX2 and a baseline clone
// (numerics/src/transition.cc explains why both give the same bits: add and multiply only, no
// FMA contraction).
__attribute__((target_clones("avx2", "default"))) void clenshaw_sums(const double* coef, int terms,
                                                                     std::size_t stride,
                                                                     std::size_t m, double t,
                                                                     double* __restrict b1,
                                                                     double* __restrict b2) {
  for (int i = terms - 1; i >= 1; --i) {
    const double* C = coef + static_cast<std::size_t>(i) * stride;
    for (std::size_t j = 0; j < m; ++j) {
      const double b0 = 2.0 * t * b1[j] - b2[j] + C[j];
      b2[j] = b1[j];
      b1[j] = b0;
    }
  }
  for (std::size_t j = 0; j < m; ++j) b1[j] = t * b1[j] - b2[j] + coef[j];
}

}  // namespace

void AeroIntegrals::partial(double s, std::vector<double>& out) const { partial(s, out, count_); }

void AeroIntegrals::partial(double s, std::vector<double>& out, int count) const {
  if (count < 0 || count > count_)
    throw InvalidInput("count", std::to_string(count),
                       "must be 0.." + std::to_string(count_) + " (the model's integrals)");
  s = std::clamp(s, a_, b_);
  // The piece that holds s (the last whose left end is <= s).
  std::size_t p = 0;
  while (p + 1 < pieces_.size() && pieces_[p + 1].lo <= s) ++p;
  const Piece& piece = pieces_[p];
  const double t = (2.0 * s - piece.lo - piece.hi) / (piece.hi - piece.lo);
  const std::size_t stride = live_.size();
  // the live integrals among the first `count` (live_ ascends)
  const std::size_t m =
      static_cast<std::size_t>(std::lower_bound(live_.begin(), live_.end(), count) - live_.begin());
  const bool all = static_cast<int>(m) == count;
  out.resize(static_cast<std::size_t>(count_));
  // b1 in `out`, or in `b1_` when some integrands vanish; b2 in `b2_`.
  thread_local std::vector<double> b1_, b2_;
  b2_.assign(m, 0.0);
  if (!all) b1_.assign(m, 0.0);
  std::fill(out.begin(), out.begin() + count, 0.0);
  std::fill(out.begin() + count, out.end(), std::numeric_limits<double>::quiet_NaN());
  double* b1 = all ? out.data() : b1_.data();
  clenshaw_sums(coef_.data() + piece.offset, piece.terms, stride, m, t, b1, b2_.data());
  if (p > 0)
    for (std::size_t j = 0; j < m; ++j) b1[j] += piece.start[j];
  if (!all)
    for (std::size_t k = 0; k < m; ++k) out[static_cast<std::size_t>(live_[k])] = b1[k];
}

void AeroIntegrals::reversed(double mu, std::vector<double>& out) const {
  reversed(mu, out, count_);
}

void AeroIntegrals::reversed(double mu, std::vector<double>& out, int count) const {
  if (!std::isfinite(mu) || mu < 0.0) {
    throw InvalidInput("mu", round_trip_text(mu), "advance ratio must be finite and >= 0");
  }
  if (count < 0 || count > count_)
    throw InvalidInput("count", std::to_string(count),
                       "must be 0.." + std::to_string(count_) + " (the model's integrals)");
  const std::size_t c = static_cast<std::size_t>(count);
  if (mu >= 1.0) {  // eqs D.5-D.6: the whole span reversed, lift slope negated
    out = normal_;
    for (std::size_t j = 0; j < out.size(); ++j)
      out[j] = j < c ? -out[j] : std::numeric_limits<double>::quiet_NaN();
    return;
  }
  // eqs D.3-D.4: -int_A^{x0(mu)} + int_{x0(mu)}^B = normal - 2 int_A^{x0(mu)}, x0 = (mu - e1)/lr
  partial((mu - e1_) / lr_, out, count);
  for (std::size_t j = 0; j < c; ++j) out[j] = normal_[j] - 2.0 * out[j];
}

std::vector<double> AeroIntegrals::reversed(double mu) const {
  std::vector<double> r;
  reversed(mu, r);
  return r;
}

}  // namespace flaplag
