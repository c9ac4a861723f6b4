#!/usr/bin/python3
"""Pluviation from a height (examples/pluviation/README.md): from the output folders of the
drops, e.g. 5, 10 and 20 cm,

  plot_pluviation.py FOLDER... [--formula bagi] [--out DIR] [--check]

stages.png       per drop (one column each), Bagi's sigma_zz of the centre column against
                 height at each evaluation during the deposition (a line per stage, lighter later;
                 the first four and the last labelled with their time)
max_zone.png     per drop, the height of the cell of largest compression in the centre column
                 over time, and the bed's top (the highest grain in the snapshots)

and prints, per drop, when the first grains reach the floor, the height of the largest
compression at each stage, and the final profile. --check exits non-zero unless, in every drop,
the zone of largest compression in the centre column is not at the same height at every stage
(it moves as the bed builds; the paper's Figs. 17-18). Where it ends is not checked: after drops
of 10 and 20 cm it ended in the second cell from the floor, not the first (README.md)."""
import argparse
import glob
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import plot_grid_stress as pgs  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402


def bed_top(folder):
    """(time, height of the highest grain surface) of each snapshot."""
    out = []
    for f in sorted(glob.glob(os.path.join(folder, "snapshots", "*.h5"))):
        with h5py.File(f) as h:
            z = h["particles/position"][:, 2] + h["particles/radius"][:]
            if len(z) == 0:  # an empty container, before a pour (examples/pour)
                continue
            out.append((h.attrs["time"], z.max(), np.sort(z)[len(z) // 10]))
    return np.array(out)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("folders", nargs="+")
    p.add_argument("--formula", default="bagi")
    p.add_argument("--out", default=".")
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    n = len(a.folders)
    fig, axes = plt.subplots(1, n, figsize=(3.6 * n, 4.2), squeeze=False, sharey=True)
    fig2, axes2 = plt.subplots(1, n, figsize=(3.6 * n, 3.4), squeeze=False, sharey=True)
    problems = []
    for c, folder in enumerate(a.folders):
        rows = pgs.read_table(folder)
        ts = pgs.times(rows)
        name = os.path.basename(os.path.normpath(folder))
        zmax, tz = [], []
        ax = axes[0, c]
        for s, t in enumerate(ts):
            v, x, y, z, _ = pgs.field_grid(rows, a.formula, "s_zz", t)
            col = v[:, v.shape[1] // 2, v.shape[2] // 2]
            if not np.any(col < 0):
                continue  # nothing has landed in the centre column yet
            shade = 0.9 * s / max(len(ts) - 1, 1)
            label = f"t = {t:.3f} s" if len(zmax) < 4 or t == ts[-1] else None
            ax.plot(col, 100 * z, "-", color=plt.cm.viridis(shade), lw=1, label=label)
            k = int(np.argmin(col))
            zmax.append(z[k])
            tz.append(t)
        ax.set_title(name, fontsize=9)
        ax.legend(fontsize=6)
        ax.set_xlabel(f"sigma_zz centre column ({a.formula}, Pa)")
        if c == 0:
            ax.set_ylabel("z (cm)")
        top = bed_top(folder)
        bx = axes2[0, c]
        bx.plot(tz, 100 * np.array(zmax), "o-", label="largest compression (cell centre)")
        bx.plot(top[:, 0], 100 * top[:, 1], "k--", label="highest grain")
        bx.set_title(name, fontsize=9)
        bx.set_xlabel("t (s)")
        if c == 0:
            bx.set_ylabel("z (cm)")
            bx.legend(fontsize=7)
        bx.set_ylim(0, 105 * max(top[:, 1].max(), z[-1]))
        print(f"{name}: first compression in the centre column at t = {tz[0]:.3g} s; largest compression at z = "
              + ", ".join(f"{100 * h:.2f}" for h in zmax) + " cm at t = " + ", ".join(f"{t:.3f}" for t in tz) + " s")
        final, _, _, _, _ = pgs.field_grid(rows, a.formula, "s_zz")
        print(f"  final centre column, bottom to top: " + ", ".join(f"{s:.0f}" for s in final[:, final.shape[1] // 2,
                                                                                           final.shape[2] // 2]) + " Pa")
        if len(set(zmax)) < 2:
            problems.append(f"{name}: the zone of largest compression never moves")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "stages.png"), dpi=120)
    fig2.tight_layout()
    fig2.savefig(os.path.join(a.out, "max_zone.png"), dpi=120)
    plt.close("all")
    if a.check:
        if problems:
            sys.exit("check failed: " + "; ".join(problems))
        print("check passed: the zone of largest compression moves during the deposition")


if __name__ == "__main__":
    main()
