#!/usr/bin/env python3
"""The figures of `upgrain --study femxdem` (docs/femxdem.md), from the tables in the folder given:
- load_displacement.png: the deviator stress q = sigma_1 - sigma_3 and the Newton iterations per
  step against the axial strain (load_displacement.csv);
- column.png, for a column under its own weight instead: sigma_yy and sigma_xx by depth beside
  the weight's sigma_yy, and K0 = sigma_xx / sigma_yy (column.csv);
- points.png: the Gauss points at the last step over the specimen (points.csv): the shear strain
  sqrt(((eps_xx - eps_yy) / 2)^2 + eps_xy^2), q/p, the cells' solid fraction and their grains'
  mean rotation, where a shear band shows as a line of high shear strain and rotation."""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402


def table(path: Path) -> list[dict[str, str]]:
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def points_figure(folder: Path) -> None:
    rows = table(folder / "points.csv")
    x = [1e3 * float(r["x"]) for r in rows]
    y = [1e3 * float(r["y"]) for r in rows]
    shear = [
        100.0 * ((0.5 * (float(r["eps_xx"]) - float(r["eps_yy"]))) ** 2 + float(r["eps_xy"]) ** 2) ** 0.5
        for r in rows
    ]
    fields = [
        ("shear strain (%)", shear, "viridis"),
        ("q / p", [float(r["q_over_p"]) for r in rows], "magma"),
        ("solid fraction", [float(r["solid_fraction"]) for r in rows], "cividis"),
        ("grain rotation (mrad)", [1e3 * float(r["grain_rotation"]) for r in rows], "coolwarm"),
    ]
    width, height = max(x) + min(x), max(y) + min(y)
    fig, axes = plt.subplots(1, 4, figsize=(11, 5.2), sharey=True)
    for ax, (name, values, cmap) in zip(axes, fields):
        kw = {}
        if cmap == "coolwarm":
            bound = max(abs(v) for v in values) or 1.0
            kw = {"vmin": -bound, "vmax": bound}
        if len(rows) >= 3:
            art = ax.tripcolor(x, y, values, shading="gouraud", cmap=cmap, **kw)
        else:
            art = ax.scatter(x, y, c=values, cmap=cmap, **kw)
        ax.plot(x, y, ".", color="k", ms=1.5)
        ax.set_xlim(0, width)
        ax.set_ylim(0, height)
        ax.set_aspect("equal")
        ax.set_title(name, fontsize=9)
        ax.set_xlabel("x (mm)")
        bar = fig.colorbar(art, ax=ax, orientation="horizontal", pad=0.12)
        bar.ax.xaxis.set_major_locator(MaxNLocator(4))
    axes[0].set_ylabel("y (mm)")
    fig.suptitle(f"FEM × DEM: the Gauss points at the last step ({len(rows)} DEM cells)")
    fig.tight_layout()
    fig.savefig(folder / "points.png", dpi=120)


def column_figure(folder: Path) -> None:
    rows = table(folder / "column.csv")
    depth = [1e3 * float(r["depth"]) for r in rows]
    fig, (left, right) = plt.subplots(1, 2, figsize=(8, 5), sharey=True)
    left.plot([-float(r["weight_sigma_yy"]) for r in rows], depth, "k--", label="weight: −σ_yy")
    left.plot([-float(r["sigma_yy"]) for r in rows], depth, "o-", ms=4, label="−σ_yy")
    left.plot([-float(r["sigma_xx"]) for r in rows], depth, "s-", ms=4, label="−σ_xx")
    left.set_xlabel("stress (Pa)")
    left.set_ylabel("depth (mm)")
    left.invert_yaxis()
    left.grid(alpha=0.3)
    left.legend(fontsize=8)
    right.plot([float(r["K0"]) for r in rows], depth, "o-", ms=4)
    right.set_xlabel("K0 = σ_xx / σ_yy")
    right.grid(alpha=0.3)
    fig.suptitle("FEM × DEM column under its own weight")
    fig.tight_layout()
    fig.savefig(folder / "column.png", dpi=120)


def main(folder: Path) -> None:
    if (folder / "column.csv").exists():
        column_figure(folder)
        points_figure(folder)
        return
    rows = table(folder / "load_displacement.csv")
    strain = [100.0 * float(r["axial_strain"]) for r in rows]
    q = [float(r["q"]) / 1e3 for r in rows]
    newton = [int(r["newton_iterations"]) for r in rows]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(5.5, 6), sharex=True, height_ratios=[3, 1])
    top.plot(strain, q, "o-", ms=3)
    top.set_ylabel("q = σ1 − σ3 (kPa)")
    top.set_title("FEM × DEM biaxial compression")
    top.grid(alpha=0.3)
    bottom.bar(strain[1:], newton[1:], width=0.6 * (strain[1] - strain[0]) if len(strain) > 1 else 0.1)
    bottom.set_xlabel("axial strain (%)")
    bottom.set_ylabel("Newton its")
    fig.tight_layout()
    fig.savefig(folder / "load_displacement.png", dpi=120)
    points_figure(folder)


if __name__ == "__main__":
    main(Path(sys.argv[1]))
