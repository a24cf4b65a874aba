#!/usr/bin/env python3
"""A stability map: the largest damping exponent zeta [per rev] over advance ratio mu and lag
frequency omega_L1 (typical case otherwise), with the stability boundary zeta = 0.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/stability_map.py -o map.png

On a Dask cluster (see the README), pass the scheduler's address:

    ... stability_map.py --scheduler tcp://scheduler-host:8786
"""

import argparse

import matplotlib.pyplot as plt
from matplotlib.colors import TwoSlopeNorm
import numpy as np

import flaplag


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="stability_map.png", help="image file")
    ap.add_argument("--mu", type=int, default=61, help="advance ratios in 0..1.5")
    ap.add_argument("--omega-lag", type=int, default=31, help="lag frequencies in 0.5..2")
    ap.add_argument("--scheduler", help="address of a Dask scheduler to run the map on")
    args = ap.parse_args()

    client = None
    if args.scheduler:
        from distributed import Client

        client = Client(args.scheduler)
    mu = np.linspace(0.0, 1.5, args.mu)
    omega_lag = np.linspace(0.5, 2.0, args.omega_lag)
    m = flaplag.map(x=("mu", mu), y=("omega_lag", omega_lag), client=client)
    print(m)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    # white at zeta = 0, blue (stable) and red (unstable) each over their own range
    norm = TwoSlopeNorm(vcenter=0.0, vmin=min(np.nanmin(m.max_zeta), -1e-6),
                        vmax=max(np.nanmax(m.max_zeta), 1e-6))
    mesh = ax.pcolormesh(m.x_values, m.y_values, m.max_zeta, cmap="RdBu_r", shading="nearest",
                         norm=norm)
    ax.contour(m.x_values, m.y_values, m.max_zeta, levels=[0.0], colors="k", linewidths=1.2)
    fig.colorbar(mesh, ax=ax, label=r"largest $\zeta$ [per rev]")
    ax.set_xlabel(r"advance ratio $\mu$")
    ax.set_ylabel(r"lag frequency $\bar\omega_{L1}$ [per rev]")
    ax.set_title(r"Stability map (black: $\zeta$ = 0; red: unstable)")
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
