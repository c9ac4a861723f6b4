#!/usr/bin/python3
"""The paper's four shapes (examples/shapes/README.md): from one output folder per shape,

  plot_shapes.py FOLDER [FOLDER ...] [--out DIR] [--formula bagi] [--check]

s_zz_shapes.png  Bagi's sigma_zz at rest in the horizontal slices of every run, one row per shape
                 (bottom layer left), all on one colour scale, each cell's value written in it

and prints, per run, the shape (the median b/a and c/a of its grains' semi-axes in the last
snapshot), the bed (surface, solid fraction), the side walls' share of the weight and, per layer,
sigma_zz in the centre cell, along the walls (the mean of the eight cells next to the side walls)
and their ratio (plot_grid_stress.centre_to_wall): below 1 when the centre carries less than the
cells along the walls, the paper's "river plate" of the flatter shapes.

--check exits non-zero unless every run is at rest with every grain in the box; with
--river-plate M also unless the two lower layers' centre-to-wall ratio (their mean) is lower for
the last folder (the flattest shape) than for the first (the roundest) by at least M: the flatter
grains carry less of the weight in the centre. The README says at which size this holds."""
import argparse
import glob
import json
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import plot_grid_stress as pgs  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402


def shape_of(folder):
    """'1:b:c' from the median aspect ratios of the grains in the last snapshot (1:1:1 for spheres)."""
    last = sorted(glob.glob(os.path.join(folder, "snapshots", "*.h5")))[-1]
    with h5py.File(last) as h:
        if "semi_axes" not in h["particles"]:
            return "1:1:1", h["walls/force"][:, 2]
        s = h["particles/semi_axes"][()]
        fz = h["walls/force"][:, 2]
    s = np.sort(s, axis=1)[:, ::-1]
    return f"1:{np.median(s[:, 1] / s[:, 0]):.2g}:{np.median(s[:, 2] / s[:, 0]):.2g}", fz


def lower_ratio(ratios):
    """The mean centre-to-wall ratio of the two lower layers (where the bed's weight has built up)."""
    return float(np.mean(ratios[:2]))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("folders", nargs="+", help="one run per shape, roundest first")
    p.add_argument("--out", default=".")
    p.add_argument("--formula", default="bagi")
    p.add_argument("--river-plate", type=float, default=None, metavar="M",
                   help="--check: the flattest shape's lower centre-to-wall ratio is below the roundest's by M")
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    runs = []
    for folder in a.folders:
        v, x, y, z, t = pgs.field_grid(pgs.read_table(folder), a.formula, "s_zz")
        shape, fz = shape_of(folder)
        with open(os.path.join(folder, "summary.json")) as f:
            summary = json.load(f)
        # Wall 0 is the floor (dem/boundary/container.h: floor, x-, x+, y-, y+).
        share = fz[1:].sum() / fz.sum()
        ratios = [pgs.centre_to_wall(v, k) for k in range(v.shape[0])]
        runs.append(dict(folder=folder, shape=shape, v=v, x=x, y=y, z=z, t=t, summary=summary, share=share,
                         ratios=ratios))
        print(f"{shape} ({folder}): bed surface {100 * summary['bed_surface_height_m']:.2f} cm, solid fraction "
              f"{summary['bed_solid_fraction']:.3f}, side walls carry {100 * share:.1f} % of the weight")
        for k in range(v.shape[0]):
            layer = v[k]
            edge = np.concatenate([layer[0, :], layer[-1, :], layer[1:-1, 0], layer[1:-1, -1]])
            print(f"  z = {100 * z[k]:.2f} cm: centre {layer[layer.shape[0] // 2, layer.shape[1] // 2]:8.1f} Pa, "
                  f"walls {np.mean(edge):8.1f} Pa, centre/walls {ratios[k]:.2f}")
        print(f"  two lower layers: centre/walls {lower_ratio(ratios):.3f}")

    finite = np.concatenate([r["v"][np.isfinite(r["v"])] for r in runs])
    lo, hi = finite.min(), finite.max()
    nk = max(r["v"].shape[0] for r in runs)
    fig, axes = plt.subplots(len(runs), nk, figsize=(2.2 * nk + 1.2, 2.2 * len(runs) + 0.4), squeeze=False,
                             constrained_layout=True)
    for row, r in enumerate(runs):
        v, x, y, z = r["v"], r["x"], r["y"], r["z"]
        dx, dy = x[1] - x[0], y[1] - y[0]
        for k in range(nk):
            ax = axes[row, k]
            ax.set_xticks([])
            ax.set_yticks([])
            if k >= v.shape[0]:
                continue
            im = ax.imshow(v[k], origin="lower", vmin=lo, vmax=hi, cmap="viridis",
                           extent=[x[0] - dx / 2, x[-1] + dx / 2, y[0] - dy / 2, y[-1] + dy / 2])
            for j in range(v.shape[1]):
                for i in range(v.shape[2]):
                    ax.text(x[i], y[j], f"{v[k, j, i]:.0f}", ha="center", va="center", fontsize=6, color="w")
            ax.set_title(f"z = {100 * z[k]:.1f} cm, c/w {r['ratios'][k]:.2f}", fontsize=8)
            if k == 0:
                ax.set_ylabel(r["shape"], fontsize=9)
    fig.colorbar(im, ax=axes.ravel().tolist(), label=f"sigma_zz ({a.formula}, Pa)", shrink=0.8)
    fig.suptitle("sigma_zz at rest by shape (c/w: centre cell over the cells along the walls)", fontsize=9)
    fig.savefig(os.path.join(a.out, "s_zz_shapes.png"), dpi=100)
    plt.close(fig)

    if a.check:
        problems = []
        for r in runs:
            s = r["summary"]
            if not s["stopped_at_rest"] and not s["relaxed"]:
                problems.append(f"{r['folder']}: not at rest")
            if s["particles_outside_container"] != 0:
                problems.append(f"{r['folder']}: {s['particles_outside_container']} grains outside the box")
        first, last = lower_ratio(runs[0]["ratios"]), lower_ratio(runs[-1]["ratios"])
        if a.river_plate is not None and not last < first - a.river_plate:
            problems.append(f"the flattest shape's lower centre-to-wall ratio {last:.3f} is not below the roundest's "
                            f"{first:.3f} by {a.river_plate}")
        if problems:
            sys.exit("check failed: " + "; ".join(problems))
        print("check passed: every bed at rest and in the box" +
              ("" if a.river_plate is None else f"; lower centre-to-wall ratio {last:.3f} ({runs[-1]['shape']}) < "
               f"{first:.3f} ({runs[0]['shape']}) - {a.river_plate}"))


if __name__ == "__main__":
    main()
