#!/usr/bin/env python3
"""Your own blade: a blade property table against the uniform blade of the same groups.

Reads the model-rotor blade of examples/model-rotor-blade.csv (SI units: mass, stiffness,
chord and twist along the span, a tip weight, the rotor speed), prints the nondimensional
groups flaplag derived from it, and draws the lag damping ratio against the advance ratio for
that blade and for the paper's uniform blade with the same gamma, sigma, e1, l/R and first
rotating frequencies: what the taper, the tip weight and the twist change.  Run:

    PYTHONPATH=build/python /usr/bin/python3 examples/python/your_blade.py -o your_blade.png
"""

import argparse
import os

import matplotlib.pyplot as plt
import numpy as np

import flaplag

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="your_blade.png", help="image file")
    ap.add_argument("--table", default=os.path.join(HERE, "..", "model-rotor-blade.csv"),
                    help="blade property table (CSV)")
    ap.add_argument("--theta", type=float, default=0.12, help="collective pitch at zero twist [rad]")
    args = ap.parse_args()

    blade = flaplag.Analysis(blade=args.table, theta=args.theta)
    p = blade.parameters
    same = {k: p[k] for k in ("gamma", "sigma", "root_offset", "length_ratio", "omega_flap",
                              "omega_lag", "theta")}
    uniform = flaplag.Analysis(modes="exact", **same)
    print("groups of the table:", ", ".join(f"{k} = {v:.6g}" for k, v in same.items()))

    mu = np.round(np.arange(0.0, 1.61, 0.05), 2)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for an, name in ((blade, "blade table"), (uniform, "uniform blade, same groups")):
        s = an.sweep(list(mu))
        lag = [l for l in s.labels if l.startswith("lag")][0]
        ratio = 100.0 * np.array(s.damping_ratio[lag])
        c = an.critical()
        mu_c = f"mu_c = {c.mu_c:.4f} ({c.mode})" if c.mu_c is not None else "stable to 2"
        print(f"{name}: least lag damping ratio {ratio.min():.3f} %, {mu_c}, status {c.status}")
        ax.plot(s.mu, ratio, marker="o", ms=3, label=f"{name}: {mu_c}")
    ax.axhline(1.0, color="0.5", ls="--", lw=1, label="1 % damping ratio")
    ax.set_xlabel("advance ratio mu")
    ax.set_ylabel("lag damping ratio [%]")
    ax.set_title("Lag damping of the model-rotor blade (theta = %.3g rad at zero twist)" % args.theta)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
