#!/usr/bin/python3
"""Mono- against polydisperse order (examples/crystallisation/README.md): the Steinhardt bond
order parameter q6 of every grain in the last snapshot of each run,

  plot_q6.py MONO_FOLDER POLY_FOLDER [--out DIR] [--check]

Definition (Steinhardt, Nelson and Ronchetti, Phys. Rev. B 28, 784, 1983): the neighbours of
grain i are the grains j whose centres lie within 1.2 (r_i + r_j) (the first shell of a packing
of touching spheres), and with the unit bond vectors b_ij,

  q_6m(i) = (1 / N_i) sum_j Y_6m(b_ij),   q_6(i) = sqrt(4 pi / 13 sum_{m=-6..6} |q_6m(i)|^2),

and the global Q6 the same with q_6m averaged over every bond of the interior grains: near 0 for
randomly oriented neighbourhoods, high when crystalline domains share their orientation.

A perfect FCC crystal has q6 = 0.575, HCP 0.485; a random close packing about 0.37 (the value
depends on the neighbour rule). Grains within --margin (2) largest diameters of a wall or of the bed's top
are left out (walls order the grains next to them), as are grains with fewer than 4 neighbours.

q6_histogram.png   the distribution of q6 in both beds, with the FCC and HCP values marked

--check exits non-zero unless the monodisperse bed's mean q6 exceeds the polydisperse one's by
--min-difference (0 by default; the CI smoke asks 0.015 of its measured 0.036 and 0.044) (the paper: monodisperse assemblies crystallise, polydisperse ones do not)."""
import argparse
import glob
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy.spatial import cKDTree  # noqa: E402
from scipy.special import sph_harm  # noqa: E402


def q6_values(x, r, interior=None):
    """(q6, neighbour count) of every grain at x with radii r, and the global Q6 of the bonds of the
    grains `interior` (a mask; all when None)."""
    reach = 1.2 * 2 * r.max()
    pairs = cKDTree(x).query_pairs(reach, output_type="ndarray")
    d = x[pairs[:, 1]] - x[pairs[:, 0]]
    dist = np.linalg.norm(d, axis=1)
    keep = dist < 1.2 * (r[pairs[:, 0]] + r[pairs[:, 1]])
    pairs, d, dist = pairs[keep], d[keep], dist[keep]
    b = d / dist[:, None]
    theta = np.arccos(np.clip(b[:, 2], -1, 1))  # polar
    phi = np.arctan2(b[:, 1], b[:, 0])  # azimuth
    n = len(x)
    count = np.bincount(pairs[:, 0], minlength=n) + np.bincount(pairs[:, 1], minlength=n)
    total = np.zeros(n)
    inner = np.ones(n, bool) if interior is None else interior
    bonds = inner[pairs[:, 0]] & inner[pairs[:, 1]]
    global_sum = 0.0
    for m in range(-6, 7):
        y = sph_harm(m, 6, phi, theta)  # scipy: sph_harm(m, l, azimuth, polar)
        # Y_lm(-b) = (-1)^l Y_lm(b) = Y_lm(b) for l = 6: both ends of a bond add the same value.
        s = np.zeros(n, complex)
        np.add.at(s, pairs[:, 0], y)
        np.add.at(s, pairs[:, 1], y)
        total += np.abs(s / np.maximum(count, 1)) ** 2
        global_sum += np.abs(y[bonds].mean()) ** 2 if bonds.any() else 0.0
    return np.sqrt(4 * np.pi / 13 * total), count, np.sqrt(4 * np.pi / 13 * global_sum)


def q6_of(folder, diameters=2.0):
    """q6 of the interior grains of the last snapshot (farther than `diameters` largest diameters
    from every wall and from the bed's top), the count left out, the mean neighbours."""
    last = sorted(glob.glob(os.path.join(folder, "snapshots", "*.h5")))[-1]
    with h5py.File(last) as h:
        x = h["particles/position"][:]
        r = h["particles/radius"][:]
        walls = h["walls/point"][:], h["walls/normal"][:]
    # Interior: away from every wall and from the top of the bed.
    margin = diameters * 2 * r.max()
    inside = np.ones(len(x), bool)
    for p, nrm in zip(*walls):
        inside &= (x - p) @ nrm > margin
    inside &= x[:, 2] < (x[:, 2] + r).max() - margin
    q6, count, big_q6 = q6_values(x, r, inside)
    inside &= count >= 4
    return q6[inside], len(x) - inside.sum(), count[inside].mean(), big_q6


def main():
    p = argparse.ArgumentParser()
    p.add_argument("mono")
    p.add_argument("poly")
    p.add_argument("--out", default=".")
    p.add_argument("--margin", type=float, default=2.0,
                   help="grains closer than this many largest diameters to a wall or the top are left out")
    p.add_argument("--min-difference", type=float, default=0.0,
                   help="--check: the monodisperse mean q6 must exceed the polydisperse one by this much")
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    res = {}
    fig, ax = plt.subplots(figsize=(5.5, 3.6))
    for label, folder in (("monodisperse", a.mono), ("polydisperse", a.poly)):
        q6, left, neighbours, big_q6 = q6_of(folder, a.margin)
        res[label] = q6
        ax.hist(q6, bins=40, range=(0, 0.7), histtype="step", density=True, label=f"{label} ({len(q6)} grains)")
        print(f"{label}: {len(q6)} interior grains ({left} left out), {neighbours:.2f} neighbours each, mean q6 "
              f"{q6.mean():.3f}, median {np.median(q6):.3f}, share with q6 > 0.45: {100 * np.mean(q6 > 0.45):.1f} %; global Q6 of their bonds {big_q6:.3f}")
    for v, name in ((0.575, "FCC"), (0.485, "HCP")):
        ax.axvline(v, color="gray", ls="--", lw=0.8)
        ax.text(v, ax.get_ylim()[1] * 0.95, name, fontsize=7, ha="center")
    ax.set_xlabel("q6")
    ax.set_ylabel("density")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "q6_histogram.png"), dpi=120)
    plt.close(fig)
    if a.check:
        mono, poly = res["monodisperse"].mean(), res["polydisperse"].mean()
        if not mono > poly + a.min_difference:
            sys.exit(f"check failed: the monodisperse bed's mean q6 {mono:.3f} does not exceed the polydisperse "
                     f"one's {poly:.3f} by {a.min_difference}")
        print(f"check passed: mean q6 monodisperse {mono:.3f} > polydisperse {poly:.3f} + {a.min_difference}")


if __name__ == "__main__":
    main()
