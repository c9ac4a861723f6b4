#!/usr/bin/python3
"""Maps and histories of the grid stress a run wrote (grid_stress.csv, docs/output.md), for any
formula and any column of the table:

  plot_grid_stress.py OUTPUT_FOLDER [--formula bagi] [--field s_zz] [--time T] [--cells "i,j,k;..."]
                      [--mark T] [--out DIR]

<field>_<formula>_slices.png    horizontal slices: one map per layer k of the grid (x right, y up)
<field>_<formula>_sections.png  vertical sections through the middle row (x-z) and column (y-z)
<field>_<formula>_history.png   the field over time in chosen cells (default: the centre column)

--time picks the evaluation nearest to T (default: the last); --mark T (repeatable) draws a line at
T in the history (a gate's opening). --field is a column of
grid_stress.csv: s_xx ... s_zz, rai, solid_fraction, particles, ... (compression is negative).
The functions are used by the examples' own scripts (examples/*/plot_*.py)."""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_table(folder):
    """The rows of grid_stress.csv as dicts of strings."""
    with open(os.path.join(folder, "grid_stress.csv")) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def formulas(rows):
    return sorted({r["formula"] for r in rows})


def times(rows):
    return sorted({float(r["time"]) for r in rows})


def field_grid(rows, formula, field, time=None):
    """(values[k, j, i], x[i], y[j], z[k], t): the field of one formula at the evaluation nearest
    to `time` (the last when None), as a 3-D array in grid order."""
    ts = times(rows)
    t = ts[-1] if time is None else min(ts, key=lambda v: abs(v - time))
    sel = [r for r in rows if r["formula"] == formula and float(r["time"]) == t]
    if not sel:
        sys.exit(f"no rows for formula '{formula}' (the run wrote: {', '.join(formulas(rows))})")
    if field not in sel[0]:
        sys.exit(f"no column '{field}' in grid_stress.csv (columns: {', '.join(sel[0].keys())})")
    n = [1 + max(int(r[a]) for r in sel) for a in "ijk"]
    v = np.full((n[2], n[1], n[0]), np.nan)
    x, y, z = np.zeros(n[0]), np.zeros(n[1]), np.zeros(n[2])
    for r in sel:
        i, j, k = int(r["i"]), int(r["j"]), int(r["k"])
        v[k, j, i] = float(r[field])
        x[i], y[j], z[k] = float(r["x"]), float(r["y"]), float(r["z"])
    return v, x, y, z, t


def history(rows, formula, field, cell):
    """(t, value) of one cell (i, j, k) over the run."""
    i, j, k = cell
    pts = [(float(r["time"]), float(r[field])) for r in rows
           if r["formula"] == formula and (int(r["i"]), int(r["j"]), int(r["k"])) == (i, j, k)]
    pts.sort()
    return np.array([p[0] for p in pts]), np.array([p[1] for p in pts])


def centre_to_wall(values, k):
    """sigma in the centre cell(s) of layer k over the mean of the cells along the side walls: > 1
    when the centre carries more (the dome the paper reports with wall friction)."""
    layer = values[k]
    nj, ni = layer.shape
    ci = [ni // 2] if ni % 2 else [ni // 2 - 1, ni // 2]
    cj = [nj // 2] if nj % 2 else [nj // 2 - 1, nj // 2]
    centre = np.mean([layer[j, i] for j in cj for i in ci])
    edge = np.concatenate([layer[0, :], layer[-1, :], layer[1:-1, 0], layer[1:-1, -1]])
    return centre / np.mean(edge)


def plot_slices(values, x, y, z, title, path, unit="Pa"):
    nk = values.shape[0]
    fig, axes = plt.subplots(1, nk, figsize=(2.6 * nk + 1.0, 2.8), squeeze=False)
    finite = values[np.isfinite(values)]
    lo, hi = (finite.min(), finite.max()) if finite.size else (0, 1)
    for k in range(nk):
        ax = axes[0, k]
        im = ax.imshow(values[k], origin="lower", vmin=lo, vmax=hi, cmap="viridis",
                       extent=[x[0] - (x[1] - x[0]) / 2 if len(x) > 1 else 0, x[-1] + (x[1] - x[0]) / 2 if len(x) > 1 else 1,
                               y[0] - (y[1] - y[0]) / 2 if len(y) > 1 else 0, y[-1] + (y[1] - y[0]) / 2 if len(y) > 1 else 1])
        ax.set_title(f"z = {100 * z[k]:.1f} cm", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
        for j in range(values.shape[1]):
            for i in range(values.shape[2]):
                if np.isfinite(values[k, j, i]):
                    ax.text(x[i], y[j], f"{values[k, j, i]:.0f}", ha="center", va="center", fontsize=6, color="w")
    fig.colorbar(im, ax=axes.ravel().tolist(), label=unit)
    fig.suptitle(title, fontsize=10)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_sections(values, x, y, z, title, path, unit="Pa"):
    nk, nj, ni = values.shape
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.8), constrained_layout=True)
    finite = values[np.isfinite(values)]
    lo, hi = (finite.min(), finite.max()) if finite.size else (0, 1)
    for ax, cut, coord, name in ((axes[0], values[:, nj // 2, :], x, "x"), (axes[1], values[:, :, ni // 2], y, "y")):
        im = ax.pcolormesh(100 * coord, 100 * z, cut, vmin=lo, vmax=hi, cmap="viridis", shading="nearest")
        ax.set_xlabel(f"{name} (cm)")
        ax.set_ylabel("z (cm)")
        ax.set_title(f"section through the middle {'row' if name == 'x' else 'column'}", fontsize=9)
    fig.colorbar(im, ax=list(axes), label=unit)
    fig.suptitle(title, fontsize=10)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_histories(rows, formula, field, cells, title, path, unit="Pa", marks=()):
    fig, ax = plt.subplots(figsize=(6, 3.6))
    for cell in cells:
        t, v = history(rows, formula, field, cell)
        ax.plot(t, v, ".-", label=f"cell {cell}")
    for m in marks:
        ax.axvline(m, color="k", lw=0.8, ls="--")
    ax.set_xlabel("t (s)")
    ax.set_ylabel(f"{field} ({unit})")
    ax.legend(fontsize=7)
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("folder")
    p.add_argument("--formula", default="bagi")
    p.add_argument("--field", default="s_zz")
    p.add_argument("--time", type=float, default=None)
    p.add_argument("--cells", default=None, help='"i,j,k;i,j,k" (default: the centre column)')
    p.add_argument("--out", default=None, help="folder for the figures (default: the output folder)")
    p.add_argument("--mark", type=float, action="append", default=[], help="a time to mark in the history (s)")
    a = p.parse_args()
    rows = read_table(a.folder)
    out = a.out or a.folder
    os.makedirs(out, exist_ok=True)
    v, x, y, z, t = field_grid(rows, a.formula, a.field, a.time)
    unit = "Pa" if a.field.startswith("s_") else "-"
    stem = os.path.join(out, f"{a.field}_{a.formula}")
    plot_slices(v, x, y, z, f"{a.field}, {a.formula}, t = {t:g} s", stem + "_slices.png", unit)
    plot_sections(v, x, y, z, f"{a.field}, {a.formula}, t = {t:g} s", stem + "_sections.png", unit)
    if a.cells:
        cells = [tuple(int(c) for c in s.split(",")) for s in a.cells.split(";")]
    else:
        cells = [(v.shape[2] // 2, v.shape[1] // 2, k) for k in range(v.shape[0])]
    plot_histories(rows, a.formula, a.field, cells, f"{a.field}, {a.formula}", stem + "_history.png", unit,
                   a.mark)
    print(f"{a.field} ({a.formula}) at t = {t:g} s, by layer (bottom first): "
          + "; ".join(f"z = {100 * z[k]:.1f} cm: centre {v[k, v.shape[1] // 2, v.shape[2] // 2]:.0f}, "
                      f"mean {np.nanmean(v[k]):.0f}" for k in range(v.shape[0])))
    for suffix in ("slices", "sections", "history"):
        print(f"  wrote {stem}_{suffix}.png")


if __name__ == "__main__":
    main()
