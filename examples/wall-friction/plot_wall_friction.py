#!/usr/bin/python3
"""Wall friction on and off (examples/wall-friction/README.md): from the two output folders,

  plot_wall_friction.py ON_FOLDER OFF_FOLDER [--out DIR] [--check]

s_zz_slices_on.png, s_zz_slices_off.png  Bagi's sigma_zz in horizontal slices at rest
s_zz_sections.png                        vertical sections through the middle row, both runs
wall_share.png                           share of the weight the side walls carry

and prints, for each run, the side walls' share of the weight (from the last snapshot's wall
forces: their vertical force over that of every wall, which is the weight at rest) and the
centre-to-wall ratio of sigma_zz in each layer (plot_grid_stress.centre_to_wall). --check exits
non-zero unless the pattern the paper reports holds: the side walls carry more of the weight with
friction than without, and sigma_zz is higher in the centre than along the walls in the layer at
or just below mid-height ((layers - 1) // 2 from the bottom) with wall friction."""
import argparse
import glob
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import plot_grid_stress as pgs  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402


def wall_share(folder):
    """Share of the weight carried by the side walls at the last snapshot."""
    last = sorted(glob.glob(os.path.join(folder, "snapshots", "*.h5")))[-1]
    with h5py.File(last) as h:
        fz = h["walls/force"][:, 2]
        names = bytes(h["walls"].attrs["names"]).decode() if "names" in h["walls"].attrs else ""
    # Wall 0 is the floor (dem/boundary/container.h: floor, x-, x+, y-, y+).
    return fz[1:].sum() / fz.sum(), names


def main():
    p = argparse.ArgumentParser()
    p.add_argument("on")
    p.add_argument("off")
    p.add_argument("--out", default=".")
    p.add_argument("--formula", default="bagi")
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    result = {}
    for label, folder in (("on", a.on), ("off", a.off)):
        rows = pgs.read_table(folder)
        v, x, y, z, t = pgs.field_grid(rows, a.formula, "s_zz")
        pgs.plot_slices(v, x, y, z, f"sigma_zz ({a.formula}), wall friction {label}, t = {t:.3g} s",
                        os.path.join(a.out, f"s_zz_slices_{label}.png"))
        share, _ = wall_share(folder)
        ratios = [pgs.centre_to_wall(v, k) for k in range(v.shape[0])]
        result[label] = (v, x, z, share, ratios)
        print(f"wall friction {label}: side walls carry {100 * share:.1f} % of the weight; centre-to-wall "
              f"sigma_zz ratio by layer (bottom first): " + ", ".join(f"{r:.2f}" for r in ratios))
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
    lo = min(np.nanmin(result[k][0]) for k in result)
    hi = max(np.nanmax(result[k][0]) for k in result)
    for ax, label in zip(axes, ("on", "off")):
        v, x, z = result[label][:3]
        im = ax.pcolormesh(100 * x, 100 * z, v[:, v.shape[1] // 2, :], vmin=lo, vmax=hi, shading="nearest")
        ax.set_title(f"wall friction {label}", fontsize=9)
        ax.set_xlabel("x (cm)")
        ax.set_ylabel("z (cm)")
    fig.colorbar(im, ax=list(axes), label="sigma_zz (Pa)")
    fig.savefig(os.path.join(a.out, "s_zz_sections.png"), dpi=120)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(4, 3))
    ax.bar(["on", "off"], [100 * result[k][3] for k in ("on", "off")])
    ax.set_ylabel("side walls' share of the weight (%)")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "wall_share.png"), dpi=120)
    plt.close(fig)
    if a.check:
        mid = (result["on"][0].shape[0] - 1) // 2  # the layer at or just below mid-height
        problems = []
        if not result["on"][3] > result["off"][3]:
            problems.append("the side walls do not carry more of the weight with friction")
        if not result["on"][4][mid] > 1.0:
            problems.append(f"with wall friction, sigma_zz at mid-height (layer {mid}) is not higher in the centre")
        if problems:
            sys.exit("check failed: " + "; ".join(problems))
        print("check passed: wall share on > off, centre-to-wall ratio at mid-height > 1 with wall friction")


if __name__ == "__main__":
    main()
