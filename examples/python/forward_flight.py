#!/usr/bin/env python3
"""Forward flight about the periodic equilibrium: the periodic equilibrium q°(psi)
of the nonlinear equations, a nonlinear time-domain simulation from it, and a thrust trim.

Left: the tip flap and lag deflections of q°(psi) over one revolution at mu (the typical
case).  Right: the nonlinear simulation from q°(0)
plus a small perturbation; the lag deviation from q°(psi) decays like exp(zeta psi) with zeta
the largest Floquet exponent of the linearization about q° (dashed).  Run:

    PYTHONPATH=build/python /usr/bin/python3 examples/python/forward_flight.py -o forward.png
"""

import argparse

import matplotlib.pyplot as plt
import numpy as np

import flaplag


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="forward_flight.png", help="image file")
    ap.add_argument("--mu", type=float, default=0.5, help="advance ratio")
    ap.add_argument("--revs", type=float, default=40.0, help="revolutions simulated")
    args = ap.parse_args()

    an = flaplag.Analysis()
    eq = an.periodic_equilibrium(args.mu, samples=180)
    print(eq)
    sim = an.simulate(args.mu, nonlinear=True, y0=1e-3, revolutions=args.revs,
                      samples_per_rev=90)
    print(sim)
    print(f"largest zeta about q°: {eq.max_zeta:.6g} per rev; "
          f"simulated lag envelope rate: {sim.lag_growth_rate:.6g} per rev")
    # The same blade trimmed to C_T = 0.005 at mu = 0.3 (moment trim: with cyclic pitch).
    print(an.trim(0.3, kind="moment", thrust_coefficient=0.005))

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    deg = np.degrees(eq.psi)
    a1.plot(deg, eq.flap_tip, label="flap w/l")
    a1.plot(deg, eq.lag_tip, label="lag v/l")
    a1.set_xlabel(r"azimuth $\psi$ [deg]")
    a1.set_ylabel("tip deflection")
    a1.set_title(rf"periodic equilibrium at $\mu$ = {args.mu:g} (K = {eq.harmonics})")
    a1.legend(fontsize="small")
    a2.plot(sim.revolutions, sim.lag_tip, lw=0.6, label="lag dv/l (nonlinear)")
    start = np.max(np.abs(sim.lag_tip[sim.revolutions < 1.0]))
    env = start * np.exp(eq.max_zeta * sim.psi)
    a2.plot(sim.revolutions, env, "k--", lw=0.8, label=rf"$\exp(\zeta\psi)$, $\zeta$ = {eq.max_zeta:.4f}")
    a2.plot(sim.revolutions, -env, "k--", lw=0.8)
    a2.set_xlabel("revolutions")
    a2.set_ylabel(r"deviation from $q^\circ(\psi)$")
    a2.set_title("nonlinear simulation from the perturbed equilibrium")
    a2.legend(fontsize="small")
    fig.text(0.01, 0.01, f"flaplag {flaplag.__version__} {flaplag.git_commit[:10]}",
             fontsize="x-small", color="0.5")
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
