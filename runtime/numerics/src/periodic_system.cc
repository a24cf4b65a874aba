// flaplag — the periodic system y' = A(psi) y + f(psi): harmonic evaluation, exact interval
// means (eqs 4.2-4.5 generalised to any harmonic) and the exact trace integral used by the
// Liouville check det Phi(2 pi) = exp(int_0^{2 pi} tr A).
#include "flaplag/numerics/periodic_system.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "flaplag/core/constants.h"
#include "flaplag/core/errors.h"
#include "flaplag/numerics/gauss_legendre.h"
#include "sinc.h"

namespace flaplag {
namespace {

// Local formatting so that this library does not depend on errors.cc (another library).
std::string fmt(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Harmonic order k of basis index h: 0 -> 0, 2k-1 and 2k -> k.
int order(int h) { return (h + 1) / 2; }

using detail::sinc;
using gauss::kW8;
using gauss::kX8;

// 0 when every entry is finite, NaN otherwise (x * 0 is NaN exactly for inf and NaN): one
// vectorizable pass, since validate() runs on every transition-matrix call.
double nonfinite_probe(const double* x, Eigen::Index count) {
  double acc = 0.0;
  for (Eigen::Index i = 0; i < count; ++i) acc += x[i] * 0.0;
  return acc;
}

void check_harmonics(const HarmonicSet& set, int n, std::size_t k) {
  // (the name is built only for an error: validate() runs on every transition-matrix call)
  auto region = [k] { return "sets[" + std::to_string(k) + "]"; };
  if (set.A.empty())
    throw InvalidInput(region() + ".A.size()", "0", "at least the constant harmonic is required");
  for (std::size_t h = 0; h < set.A.size(); ++h) {
    const Eigen::MatrixXd& a = set.A[h];
    if (a.rows() != n || a.cols() != n)
      throw InvalidInput(region() + ".A[" + std::to_string(h) + "]",
                         std::to_string(a.rows()) + "x" + std::to_string(a.cols()),
                         "must be n x n with n = " + std::to_string(n));
    if (nonfinite_probe(a.data(), a.size()) != 0.0)
      throw InvalidInput(region() + ".A[" + std::to_string(h) + "]", "non-finite",
                         "coefficients must be finite");
  }
  for (std::size_t h = 0; h < set.f.size(); ++h) {
    if (set.f[h].size() != n)
      throw InvalidInput(region() + ".f[" + std::to_string(h) + "]",
                         std::to_string(set.f[h].size()),
                         "must have n = " + std::to_string(n) + " entries");
  }
}

}  // namespace

double harmonic_basis(int h, double psi) {
  if (h < 0) throw InvalidInput("h", std::to_string(h), "harmonic index must be >= 0");
  if (h == 0) return 1.0;
  const double k = order(h);
  return (h % 2 == 1) ? std::cos(k * psi) : std::sin(k * psi);
}

std::string harmonic_name(int h) {
  if (h < 0) throw InvalidInput("h", std::to_string(h), "harmonic index must be >= 0");
  if (h == 0) return "const";
  const int k = order(h);
  return std::string(h % 2 == 1 ? "cos " : "sin ") + (k == 1 ? "" : std::to_string(k)) + "psi";
}

double harmonic_mean(int h, double a, double b) {
  if (h < 0) throw InvalidInput("h", std::to_string(h), "harmonic index must be >= 0");
  if (!(std::isfinite(a) && std::isfinite(b)))
    throw InvalidInput("interval", "[" + fmt(a) + ", " + fmt(b) + "]", "must be finite");
  if (h == 0) return 1.0;
  // (1/(b-a)) int_a^b cos(k psi) = cos(k m) sin(k d)/(k d), m the midpoint, d the half width;
  // the same with sin.  For k = 1, 2 these are eqs 4.2-4.5.  b == a gives the point value.
  const double k = order(h);
  const double mid = 0.5 * (a + b);
  const double s = sinc(k * 0.5 * (b - a));
  return ((h % 2 == 1) ? std::cos(k * mid) : std::sin(k * mid)) * s;
}

double reduce_azimuth(double psi) {
  double p = std::fmod(psi, kTwoPi);
  if (p < 0.0) p += kTwoPi;
  if (p >= kTwoPi) p = 0.0;  // fmod of a tiny negative number rounds up to 2 pi
  return p;
}

PeriodicSystem::PeriodicSystem(HarmonicSet base) {
  n = base.A.empty() ? 0 : static_cast<int>(base.A[0].rows());
  sets.push_back(std::move(base));
  pieces.push_back({0.0, kTwoPi, 0, {}, {}});
}

namespace {

// The index of the base-set piece that holds [begin, end); throws unless there is one.
std::size_t base_piece(const PeriodicSystem& s, double begin, double end) {
  if (begin >= 0.0 && begin < end && end <= kTwoPi)
    for (std::size_t i = 0; i < s.pieces.size(); ++i)
      if (s.pieces[i].set == 0 && s.pieces[i].begin <= begin && end <= s.pieces[i].end) return i;
  throw InvalidInput("piece", "[" + fmt(begin) + ", " + fmt(end) + ")",
                     "need 0 <= begin < end <= 2 pi inside one piece of the base set");
}

// pieces[i] split so that [p.begin, p.end) becomes p (base_piece() checked that it fits), in
// place (a system rebuilt at every mu keeps the storage of its pieces).
void insert_piece(std::vector<SystemPiece>& pieces, std::size_t i, SystemPiece p) {
  const double outer_begin = pieces[i].begin, outer_end = pieces[i].end;
  const int outer_set = pieces[i].set;
  const double begin = p.begin, end = p.end;
  pieces[i] = std::move(p);
  auto at = [&](std::size_t k) { return pieces.begin() + static_cast<std::ptrdiff_t>(k); };
  if (outer_begin < begin) pieces.insert(at(i++), {outer_begin, begin, outer_set, {}, {}});
  if (end < outer_end) pieces.insert(at(i + 1), {end, outer_end, outer_set, {}, {}});
}

}  // namespace

void PeriodicSystem::add_harmonic_piece(double begin, double end, HarmonicSet set) {
  const std::size_t i = base_piece(*this, begin, end);
  sets.push_back(std::move(set));
  insert_piece(pieces, i, {begin, end, static_cast<int>(sets.size()) - 1, {}, {}});
}

void PeriodicSystem::reset_pieces() {
  // Room for one inserted piece, which splits the base piece in three: a fresh system
  // allocates its pieces once.
  pieces.reserve(3);
  pieces.resize(1);
  pieces[0] = {0.0, kTwoPi, 0, {}, {}};
}

void PeriodicSystem::add_set_piece(double begin, double end, int set) {
  if (set < 1 || set >= static_cast<int>(sets.size()))
    throw InvalidInput("set", std::to_string(set), "must name one of sets[1..] already there");
  insert_piece(pieces, base_piece(*this, begin, end), {begin, end, set, {}, {}});
}

void PeriodicSystem::add_evaluator_piece(double begin, double end, Evaluator evaluator,
                                         std::vector<double> breaks) {
  const std::size_t i = base_piece(*this, begin, end);
  insert_piece(pieces, i, {begin, end, -1, std::move(evaluator), std::move(breaks)});
}

void PeriodicSystem::validate() const {
  if (n < 1) throw InvalidInput("n", std::to_string(n), "state dimension must be >= 1");
  if (sets.empty()) throw InvalidInput("sets", "empty", "a base harmonic set is required");
  for (std::size_t k = 0; k < sets.size(); ++k) check_harmonics(sets[k], n, k);
  if (pieces.empty()) throw InvalidInput("pieces", "empty", "the pieces must cover [0, 2 pi)");
  double last = 0.0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const SystemPiece& p = pieces[i];
    auto name = [i] { return "pieces[" + std::to_string(i) + "]"; };
    if (!(p.begin == last && p.begin < p.end && p.end <= kTwoPi))
      throw InvalidInput(name(), "[" + fmt(p.begin) + ", " + fmt(p.end) + ")",
                         "the pieces must be sorted and cover [0, 2 pi) without gaps");
    last = p.end;
    if (p.set >= static_cast<int>(sets.size()) || p.set < -1)
      throw InvalidInput(name() + ".set", std::to_string(p.set), "no such harmonic set");
    if (p.set == -1 && !p.evaluator)
      throw InvalidInput(name() + ".evaluator", "empty", "a piece without harmonics needs one");
    double b_last = p.begin;
    for (double b : p.breaks) {
      if (!(b > b_last && b < p.end))
        throw InvalidInput(name() + ".breaks", fmt(b),
                           "breaks must be sorted and inside the piece");
      b_last = b;
    }
  }
  if (last != kTwoPi)
    throw InvalidInput("pieces", "end " + fmt(last), "the pieces must cover [0, 2 pi)");
}

int PeriodicSystem::piece_at(double psi) const {
  const double p = reduce_azimuth(psi);
  const int last = static_cast<int>(pieces.size()) - 1;
  for (int i = 0; i < last; ++i)
    if (p < pieces[static_cast<std::size_t>(i)].end) return i;
  return last;
}

bool PeriodicSystem::has_evaluator() const {
  for (const SystemPiece& p : pieces)
    if (p.set < 0) return true;
  return false;
}

Eigen::MatrixXd PeriodicSystem::A(double psi) const {
  // Reduced first: cos(k psi) of a huge psi is NaN (k psi overflows) or meaningless.
  psi = reduce_azimuth(psi);
  const SystemPiece& piece = pieces[static_cast<std::size_t>(piece_at(psi))];
  if (piece.set < 0) {
    Eigen::MatrixXd a;
    Eigen::VectorXd f;
    piece.evaluator(psi, a, f);
    return a;
  }
  const HarmonicSet& set = sets[static_cast<std::size_t>(piece.set)];
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t h = 0; h < set.A.size(); ++h)
    out += harmonic_basis(static_cast<int>(h), psi) * set.A[h];
  return out;
}

Eigen::VectorXd PeriodicSystem::f(double psi) const {
  psi = reduce_azimuth(psi);
  const SystemPiece& piece = pieces[static_cast<std::size_t>(piece_at(psi))];
  if (piece.set < 0) {
    Eigen::MatrixXd a;
    Eigen::VectorXd f;
    piece.evaluator(psi, a, f);
    return f;
  }
  const HarmonicSet& set = sets[static_cast<std::size_t>(piece.set)];
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  for (std::size_t h = 0; h < set.f.size(); ++h)
    out += harmonic_basis(static_cast<int>(h), psi) * set.f[h];
  return out;
}

Eigen::MatrixXd PeriodicSystem::A_mean(double a, double b) const {
  // The interval lies inside one piece by contract; its midpoint decides which (robust to an
  // endpoint sitting exactly on a piece edge).
  const SystemPiece& piece = pieces[static_cast<std::size_t>(piece_at(0.5 * (a + b)))];
  if (piece.set < 0) {
    Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n), x;
    Eigen::VectorXd f;
    for (int i = 0; i < 8; ++i) {
      piece.evaluator(0.5 * (a + b) + 0.5 * (b - a) * kX8[i], x, f);
      out += (0.5 * kW8[i]) * x;
    }
    return out;
  }
  const HarmonicSet& set = sets[static_cast<std::size_t>(piece.set)];
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t h = 0; h < set.A.size(); ++h)
    out += harmonic_mean(static_cast<int>(h), a, b) * set.A[h];
  return out;
}

std::vector<double> PeriodicSystem::breakpoints() const {
  std::vector<double> out;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (i > 0) out.push_back(pieces[i].begin);
    for (double b : pieces[i].breaks) out.push_back(b);
  }
  return out;
}

double PeriodicSystem::trace_integral() const {
  // int_0^{2pi} phi_h = 2 pi for h = 0 and 0 otherwise.  A piece [b, e) of another set
  // replaces the base harmonics B_h there:
  //   int tr A = sum_h tr(B_h) (int_0^{2pi} phi_h - int_b^e phi_h) + int_b^e tr A(piece).
  const HarmonicSet& base = sets.at(0);
  double total = kTwoPi * base.A.at(0).trace();
  std::vector<double> means;  // harmonic_mean(h, p.begin, p.end), computed once per piece
  for (const SystemPiece& p : pieces) {
    if (p.set == 0) continue;
    const HarmonicSet* set = p.set > 0 ? &sets[static_cast<std::size_t>(p.set)] : nullptr;
    means.resize(std::max(base.A.size(), set != nullptr ? set->A.size() : 0));
    for (std::size_t h = 0; h < means.size(); ++h)
      means[h] = harmonic_mean(static_cast<int>(h), p.begin, p.end);
    const double width = p.end - p.begin;
    for (std::size_t h = 0; h < base.A.size(); ++h) total -= base.A[h].trace() * means[h] * width;
    if (set != nullptr) {
      for (std::size_t h = 0; h < set->A.size(); ++h) total += set->A[h].trace() * means[h] * width;
      continue;
    }
    // An evaluator piece: composite Gauss-Legendre, 8 points on panels of at most pi/16 on each
    // smooth part (between breaks), where the integrand is analytic (checked against closed
    // forms in tests/periodic_system_test.cpp, and through the rotor's Liouville residual below
    // 1e-10 in tests/analysis_test.cpp).
    std::vector<double> cuts = {p.begin};
    for (double b : p.breaks) cuts.push_back(b);
    cuts.push_back(p.end);
    Eigen::MatrixXd x;
    Eigen::VectorXd f;
    for (std::size_t k = 1; k < cuts.size(); ++k) {
      const double lo = cuts[k - 1], hi = cuts[k];
      const int panels = std::max(2, static_cast<int>(std::ceil((hi - lo) / (kPi / 16.0))));
      gauss::composite_gauss8(lo, hi, panels, [&](double psi, double weight) {
        p.evaluator(psi, x, f);
        total += weight * x.trace();
      });
    }
  }
  return total;
}

}  // namespace flaplag
