#!/usr/bin/python3
"""Plots of the grid strain of a run (docs/strain.md), from the HDF5 files under grid_strain/:

  plot_strain.py OUTPUT_FOLDER

strain_ln_J.png      ln J of every grid cell against time, one line per cell with a valid F
                     at some output, per definition (best fit, tessellation);
strain_shear.png     the equivalent shear strain gamma_eq of every cell against time, likewise;
strain_final_map.png ln J and gamma_eq at the last output on the x-z slice through the
                     middle row of cells (j = ny / 2), per definition; invalid cells blank.

Invalid cells (F_valid = 0) are left out of the lines (a gap) and blank in the map: their
stored values are zeros with a reason code, not strains."""
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DEFINITIONS = ("best_fit", "tessellation")


def load(folder):
    files = sorted(os.listdir(os.path.join(folder, "grid_strain")))
    out = []
    for f in files:
        with h5py.File(os.path.join(folder, "grid_strain", f), "r") as h:
            o = {"time": float(h.attrs["time"]), "n": h["/grid/n"][:].astype(int), "lo": h["/grid/lo"][:],
                 "hi": h["/grid/hi"][:], "set": h.attrs["set"]}
            for d in DEFINITIONS:
                if d in h:
                    valid = h[d]["F_valid"][:].reshape(-1) == 1
                    o[d] = {"valid": valid, "ln_J": h[d]["ln_J"][:].reshape(-1),
                            "shear": h[d]["equivalent_shear_strain"][:].reshape(-1)}
            out.append(o)
    return out


def time_plot(outputs, definitions, key, label, path):
    fig, axes = plt.subplots(1, len(definitions), figsize=(5.5 * len(definitions), 4.2), squeeze=False)
    t = np.array([o["time"] for o in outputs])
    for ax, d in zip(axes[0], definitions):
        values = np.array([o[d][key] for o in outputs], dtype=float)
        valid = np.array([o[d]["valid"] for o in outputs])
        values[~valid] = np.nan  # a gap, not a zero strain
        cells = np.flatnonzero(valid.any(axis=0))
        for c in cells:
            ax.plot(t, values[:, c], "-", lw=0.8, alpha=0.6)
        if len(cells):
            ax.plot(t, np.nanmedian(values[:, cells], axis=1), "k-", lw=2, label="median over cells")
            ax.legend(loc="best", fontsize=8)
        ax.set_title(f"{d.replace('_', ' ')}: {len(cells)} cells")
        ax.set_xlabel("t (s)")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def final_map(outputs, definitions, path):
    o = outputs[-1]
    nx, ny, nz = o["n"]
    j = ny // 2
    x = np.linspace(o["lo"][0], o["hi"][0], nx + 1)
    z = np.linspace(o["lo"][2], o["hi"][2], nz + 1)
    fig, axes = plt.subplots(len(definitions), 2, figsize=(11, 3.6 * len(definitions)), squeeze=False)
    for row, d in zip(axes, definitions):
        for ax, key, label, cmap in ((row[0], "ln_J", "ln J", "RdBu_r"),
                                     (row[1], "shear", "equivalent shear strain", "viridis")):
            v = np.where(o[d]["valid"], o[d][key], np.nan).reshape(nz, ny, nx)[:, j, :]
            m = np.ma.masked_invalid(v)
            kw = {}
            if key == "ln_J":
                a = float(np.nanmax(np.abs(v))) if np.isfinite(v).any() else 1.0
                kw = {"vmin": -a, "vmax": a}
            im = ax.pcolormesh(x, z, m, cmap=cmap, shading="flat", **kw)
            fig.colorbar(im, ax=ax, label=label)
            ax.set_aspect("equal")
            ax.set_title(f"{d.replace('_', ' ')}: {label}, t = {o['time']:.3g} s, j = {j}")
            ax.set_xlabel("x (m)")
            ax.set_ylabel("z (m)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    folder = sys.argv[1]
    outputs = load(folder)
    if not outputs:
        raise SystemExit("no grid_strain/*.h5 files")
    definitions = [d for d in DEFINITIONS if d in outputs[0]]
    made = []
    time_plot(outputs, definitions, "ln_J", "ln J (< 0 compaction, > 0 dilation)",
              os.path.join(folder, "strain_ln_J.png"))
    made.append("strain_ln_J.png")
    time_plot(outputs, definitions, "shear", "equivalent shear strain", os.path.join(folder, "strain_shear.png"))
    made.append("strain_shear.png")
    final_map(outputs, definitions, os.path.join(folder, "strain_final_map.png"))
    made.append("strain_final_map.png")
    print("plots:", ", ".join(made))


if __name__ == "__main__":
    main()
