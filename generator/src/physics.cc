// The physics of the derivation: kinematics (eqs 2.13-2.15, 2.22-2.23), aerodynamic loads
// (2.18-2.21), structural and inertial loads (2.2-2.10, 2.16-2.17), and the ordering truncation
// (Appendix C.1) applied after every product.
#include <algorithm>

#include "deriver.h"

namespace flaplag::derive::detail {

using GiNaC::ex;
using GiNaC::exvector;
using GiNaC::numeric;
using GiNaC::symbol;

ex Deriver::trunc(const ex& e, int max_eps) const {
  // The nonlinear pass (nonlinear.cc) expands about q = 0 and keeps every degree.
  const ex x = (nonlinear_ ? e.subs(hover_zero_) : e).expand();
  exvector keep;
  auto consider = [&](const ex& t) {
    if ((nonlinear_ || t.degree(dlt_) <= 1) && t.degree(eps_) <= max_eps) keep.push_back(t);
  };
  if (GiNaC::is_a<GiNaC::add>(x)) {
    for (const auto& t : x) consider(t);
  } else {
    consider(x);
  }
  return ex(GiNaC::add(keep));
}

// Generalized aerodynamic loads, eqs 2.18-2.23, nondimensionalised so that
//   A_Fi = (gamma/2)(l/R)^2 int u_T (u_T theta - u_P) eta_i dx0
//   A_Li = (gamma/2)(l/R)^2 int [u_P (u_T theta - u_P) + (C_Do/a) u_T^2] gamma_i dx0
// with u_T = U_T/(Omega R), u_P = U_P/(Omega R) and the section pitch theta (below: collective,
// built-in twist theta_tw(x0) and cyclic pitch).  A_Li carries the sign of eq 2.19 (v_e = -l
// gamma h, so the lag coordinate is positive against the rotation).
void Deriver::aerodynamic_loads() {
  const ex c = (z_ + 1 / z_) / 2;               // cos psi
  const ex s = (z_ - 1 / z_) / (2 * GiNaC::I);  // sin psi
  const ex theta = eps_pow("theta") * scalar(theta_);
  // Cyclic pitch (spec switch cyclic_pitch): theta(psi) = theta + theta1c cos psi + theta1s
  // sin psi in the pitch angle of the blade section, eqs 2.20-2.21, of the same eps order as
  // theta.  Only the aerodynamic pitch varies with psi: the droop geometry (the -beta_D theta
  // slope of v, eq 2.13) and the elastic coupling (Appendix E) keep the collective theta, since
  // a pitch that varies with psi there would add inertial terms in theta' and theta'' that the
  // paper's hover-based ordering has no place for.  The cyclic parts carry their own origin
  // tags so that the audit report lists them apart.
  const ex cyclic =
      spec_.cyclic_pitch ? eps_pow("theta") * (scalar(theta1c_) * c + scalar(theta1s_) * s) : ex(0);
  // Built-in twist theta_tw(x0): the section pitch is theta + theta_tw(x0) (+ cyclic), the
  // twist of the same eps order as theta and, like the cyclic pitch, in the aerodynamic pitch
  // only (the droop slope and the elastic coupling keep the collective theta).  The spanwise
  // symbol tw becomes a factor of the integral (model::Factor::Twist); its terms carry their own
  // origin tags.
  const ex twist = eps_pow("theta") * tw_;
  const ex lambda = eps_pow("inflow") * scalar(inflow_);
  const ex beta = eps_pow("precone") * scalar(precone_) + eps_pow("droop") * scalar(droop_);
  const ex beta_d = eps_pow("droop") * scalar(droop_);
  const ex cdo = eps_pow("cdo_a") * scalar(cdo_);
  // mu is O(1) in the paper ([orders] mu = 0); a spec may make it a small quantity.
  const ex mu = eps_pow("mu") * scalar(mu_), lr = scalar(lr_);
  const int kf = spec_.kept_flap, kl = spec_.kept_lag;
  const int kmax = std::max(kf, kl);

  // Slopes and rates of the displacement field (2.13-2.15), linearized about hover (2.26):
  // g = g0 + dg, h = h0 + dh.
  ex w_slope = beta, v_slope = -beta_d * theta, w_rate = 0, v_rate = 0;
  for (int k = 0; k < M_; ++k) {
    w_slope += etap_[k] * eps_pow("g") * (scalar(g0_[k]) + dlt_ * dg_[k]);
    w_rate += eta_[k] * eps_pow("g_dot") * dlt_ * dgd_[k];
  }
  for (int m = 0; m < N_; ++m) {
    v_slope -= gamp_[m] * eps_pow("h") * (scalar(h0_[m]) + dlt_ * dh_[m]);
    v_rate -= gam_[m] * eps_pow("h_dot") * dlt_ * dhd_[m];
  }
  // Eq 2.23; the last term is the radial-flow term, tagged rf.
  const ex radial = spec_.radial_flow ? ex(radial_) : ex(0);
  const ex uT = trunc(x_ + mu * s + radial * mu * c * v_slope + lr * v_rate, kmax);
  // Eq 2.22.
  const ex uP = trunc(lambda + mu * c * w_slope + lr * w_rate, kmax);

  const ex uT2 = mul(uT, uT, kmax);
  const ex uTuP = mul(uT, uP, kmax);
  const ex uP2 = mul(uP, uP, kmax);

  // Eq 2.20 as u_T (u_T theta - u_P), by load product.
  ex lz = tag("L_z: theta U_T^2") * theta * uT2 + tag("L_z: theta_tw U_T^2") * twist * uT2 -
          tag("L_z: -U_T U_P") * uTuP;
  // Eq 2.21 as -(L_y) = u_P (u_T theta - u_P) + (C_Do/a) u_T^2.
  ex ly = tag("L_y: theta U_P U_T") * theta * uTuP + tag("L_y: theta_tw U_P U_T") * twist * uTuP -
          tag("L_y: -U_P^2") * uP2 + tag("L_y: (C_Do/a) U_T^2") * cdo * uT2;
  if (spec_.cyclic_pitch) {
    lz += tag("L_z: theta_cyclic U_T^2") * cyclic * uT2;
    ly += tag("L_y: theta_cyclic U_P U_T") * cyclic * uTuP;
  }
  lz = trunc(lz, kf);
  ly = trunc(ly, kl);
  const ex scale = scalar(lock_) / 2 * GiNaC::pow(lr, 2);
  for (int i = 0; i < M_; ++i) place(scale * lz * eta_[i], true, i);
  for (int i = 0; i < N_; ++i) place(scale * ly * gam_[i], true, model::lag_equation_index(i, M_));
  // Rotor thrust of one blade (cyclic-pitch models, for the trim): the same flap load L_z,
  // integrated over the aerodynamic span with dr/R = (l/R) dx0 instead of Galerkin-weighted.
  if (spec_.cyclic_pitch) place(lr * lz, true, model_.thrust_equation());
}

// Structural and inertial generalized forces from eqs 2.2-2.10, Galerkin-weighted (2.16-2.17)
// and divided by Omega^2 I_b.  Loads (2.4-2.6) with the terms the paper marks small (u'' and
// u in P_x) neglected:
//   P_x = m (x0 + e1 + 2 v'),  P_y = L_y - m (v'' - v + 2 u'),  P_z = L_z - m w''
//   T(x) = int_x^1 P_x dx1 (free tip).
// Flap residual i:  int eta_i P_z dx0 - int eta_i' T w_x dx0      (tension by parts)
// Lag residual i:   int (-gamma_i) P_y dx0 + int gamma_i' T v_x dx0 (weight -gamma_i: v_e = -l
// gamma h)
void Deriver::structural_loads() {
  const ex theta = eps_pow("theta") * scalar(theta_);
  const ex beta = eps_pow("precone") * scalar(precone_) + eps_pow("droop") * scalar(droop_);
  const ex beta_d = eps_pow("droop") * scalar(droop_);

  ex w_slope = beta, w_acc = 0, v = -x0_ * beta_d * theta, v_slope = -beta_d * theta, v_acc = 0;
  ex u_rate = 0;                // u' (eq 2.8 differentiated; beta and theta constant)
  ex inner_v_rate = 0;          // v'(x1) inside the tension integral
  ex head_ww = 0, head_vv = 0;  // int_0^x w_e'^2 and v_e'^2 products, differentiated
  std::vector<ex> G, Gd, H, Hd;
  for (int k = 0; k < M_; ++k) {
    G.push_back(eps_pow("g") * (scalar(g0_[k]) + dlt_ * dg_[k]));
    Gd.push_back(eps_pow("g_dot") * dlt_ * dgd_[k]);
    w_slope += etap_[k] * G[k];
    w_acc += eta_[k] * eps_pow("g_dot") * dlt_ * dgdd_[k];
    u_rate -= beta * eta_[k] * Gd[k];  // -(beta_P + beta_D) w_e'
  }
  for (int m = 0; m < N_; ++m) {
    H.push_back(eps_pow("h") * (scalar(h0_[m]) + dlt_ * dh_[m]));
    Hd.push_back(eps_pow("h_dot") * dlt_ * dhd_[m]);
    v -= gam_[m] * H[m];
    v_slope -= gamp_[m] * H[m];
    v_acc -= gam_[m] * eps_pow("h_dot") * dlt_ * dhdd_[m];
    inner_v_rate -= igam_[m] * Hd[m];
  }
  // d/dpsi of -1/2 int_0^x (w_e'^2 + v_e'^2) dx1 = -int_0^x (w_e' w_e'' + v_e' v_e'') dx1
  for (int k = 0; k < M_; ++k)
    for (int l = 0; l < M_; ++l) head_ww += ietap_[k] * ietap_[l] * G[k] * Gd[l];
  for (int m = 0; m < N_; ++m)
    for (int r = 0; r < N_; ++r) head_vv += igamp_[m] * igamp_[r] * H[m] * Hd[r];
  u_rate = trunc(u_rate - head_ * (head_ww + head_vv), kUntruncated);

  // Tension: centrifugal part and the Coriolis part 2 v' of P_x.
  const ex tension = tail_ * mi_ *
                     (tag("tension, centrifugal (2.4)") * iarm_ +
                      tag("tension, Coriolis 2v' (2.4)") * 2 * inner_v_rate);
  absorbed_origins_ = {"tension, centrifugal (2.4)", "in-plane centrifugal -v (2.5)"};

  for (int i = 0; i < M_; ++i) {
    ex r = -tag("flap inertia w'' (2.6)") * mo_ * eta_[i] * w_acc;
    r -= mul(etap_[i] * w_slope, tension, kUntruncated);
    place(trunc(r, kUntruncated), false, i);
  }
  for (int i = 0; i < N_; ++i) {
    ex r = mo_ * gam_[i] *
           (tag("lag inertia v'' (2.5)") * v_acc - tag("in-plane centrifugal -v (2.5)") * v +
            tag("Coriolis 2u' (2.5)") * 2 * u_rate);
    r += mul(gamp_[i] * v_slope, tension, kUntruncated);
    place(trunc(r, kUntruncated), false, model::lag_equation_index(i, M_));
  }

  // Modal stiffness and damping (orthogonality, A.2 and A.4; damping as in 2.16-2.17) and the
  // elastic coupling of Appendix E (E.5-E.8), which enter as inputs.
  const ex es_w = GiNaC::pow(eps_, 2 * spec_.order("theta"));  // sin^2 theta
  const ex ecs_w = eps_pow("theta");                           // sin theta cos theta
  for (int i = 0; i < M_; ++i) {
    const ex mass = mo_ * eta_[i] * eta_[i];
    ex r = -tag("modal stiffness (A.2)") * GiNaC::pow(scalar(wf_[i]), 2) * mass * G[i] -
           tag("structural damping (2.16)") * 2 * scalar(wf_[i]) * scalar(zf_[i]) * mass * Gd[i];
    for (int k = 0; k < M_; ++k)
      r -= tag("elastic coupling E^s (E.5)") * es_w * scalar(esf_[i][k]) * G[k];
    for (int m = 0; m < N_; ++m)
      r += tag("elastic coupling E^cs (E.6)") * ecs_w * scalar(ecsfl_[i][m]) * H[m];
    place(trunc(r, kUntruncated), false, i);
  }
  for (int i = 0; i < N_; ++i) {
    const ex mass = mo_ * gam_[i] * gam_[i];
    ex r = -tag("modal stiffness (A.4)") * GiNaC::pow(scalar(wl_[i]), 2) * mass * H[i] -
           tag("structural damping (2.17)") * 2 * scalar(wl_[i]) * scalar(zl_[i]) * mass * Hd[i];
    for (int m = 0; m < N_; ++m)
      r += tag("elastic coupling E^s (E.7)") * es_w * scalar(esl_[i][m]) * H[m];
    for (int k = 0; k < M_; ++k)
      r += tag("elastic coupling E^cs (E.8)") * ecs_w * scalar(ecslf_[i][k]) * G[k];
    place(trunc(r, kUntruncated), false, model::lag_equation_index(i, M_));
  }
}

}  // namespace flaplag::derive::detail
