#!/usr/bin/env python3
"""Fig 15 of NASA CR-132431: the critical advance ratio mu_c versus the lag frequency
omega_L1 (typical case otherwise: theta = 0.15, gamma = 10, omega_F1 = 1.175, assumed modes).

Flutter (a complex multiplier pair leaves the unit circle) and periodic instabilities (omega
locked to 0, 1/2 or 1 per rev) are marked differently; blades stable up to the scan limit are
drawn at the top.  Run:

    PYTHONPATH=build/python /usr/bin/python3 examples/python/fig15.py -o fig15.png
"""

import argparse

import matplotlib.pyplot as plt
import numpy as np

import flaplag


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="fig15.png", help="image file (png, pdf, svg)")
    ap.add_argument("--mu-max", type=float, default=2.0, help="scan limit of the search")
    ap.add_argument("--points", type=int, default=47, help="omega_L1 values in 0.2..2.5")
    args = ap.parse_args()

    omega_lag = np.linspace(0.2, 2.5, args.points)
    st = flaplag.study("omega_lag", omega_lag, mu_max=args.mu_max)
    print(st)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    found = ~np.isnan(st.mu_c)
    for kind, marker, label in (("flutter", "o", "flutter"),
                                ("periodic", "s", "periodic (omega locked to 0, 1/2, 1 per rev)")):
        sel = found & (st.kind == kind)
        ax.plot(omega_lag[sel], st.mu_c[sel], marker, mfc="none" if kind == "periodic" else None,
                ls="none", label=label)
    stable = ~found & ~st.hover_unstable & (st.row_status != "failed")
    ax.plot(omega_lag[stable], np.full(stable.sum(), args.mu_max), "^", color="0.5", ls="none",
            label=f"stable up to mu = {args.mu_max:g}")
    ax.plot(omega_lag[found], st.mu_c[found], "-", color="0.8", zorder=0)
    ax.axvline(1.28303, color="0.7", ls=":", lw=1)
    ax.set_xlabel(r"lag frequency $\bar\omega_{L1}$ [per rev]")
    ax.set_ylabel(r"critical advance ratio $\mu_c$")
    ax.set_title(r"Fig 15: $\mu_c$ versus $\bar\omega_{L1}$ (assumed modes, $\theta$ = 0.15)")
    ax.set_ylim(0, args.mu_max * 1.05)
    ax.legend(loc="lower right", fontsize="small")
    ax.text(0.01, 0.01, f"flaplag {flaplag.__version__} {flaplag.git_commit[:10]}",
            transform=fig.transFigure, fontsize="x-small", color="0.5")
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
