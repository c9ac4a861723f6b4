#!/usr/bin/python3
"""Plots of a DEM-vs-continuum study (docs/study.md), from the CSV tables the driver wrote:

  plot_study.py OUTPUT_FOLDER

profiles_szz.png   sigma_zz against height, centre and edge columns: each DEM formula, FEM,
                   analytic;
lateral_ratio.png  (s_xx + s_yy) / (2 s_zz) against height beside K0;
level_spread.png   spread of sigma_zz across each level, DEM formulas and FEM."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def table(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def main():
    folder = sys.argv[1]
    prof = table(os.path.join(folder, "profiles.csv"))
    formulas = [k[: -len("_s_zz")] for k in prof[0] if k.endswith("_s_zz") and k not in ("fem_s_zz", "analytic_s_zz")]

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.5), sharey=True)
    for ax, column in zip(axes, ("centre", "edge")):
        rows = sorted((r for r in prof if r["column"] == column), key=lambda r: float(r["z"]))
        z = [float(r["z"]) for r in rows]
        for f, style in zip(formulas, ("o-", "s--", "^:", "v-.", "d-", "x--", "+:")):
            ax.plot([float(r[f + "_s_zz"]) for r in rows], z, style, label=f"DEM {f.replace('_', ' ')}")
        ax.plot([float(r["fem_s_zz"]) for r in rows], z, "k-", lw=2, label="FEM (cell mean)")
        ax.plot([float(r["analytic_s_zz"]) for r in rows], z, "k:", label="analytic")
        ax.set_title(f"{column} column (i={rows[0]['i']}, j={rows[0]['j']})")
        ax.set_xlabel("sigma_zz (Pa)")
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("z (m)")
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "profiles_szz.png"), dpi=120)

    fig, ax = plt.subplots(figsize=(5.5, 4.5))
    for column, style in (("centre", "-"), ("edge", "--")):
        rows = sorted((r for r in prof if r["column"] == column), key=lambda r: float(r["z"]))
        z = [float(r["z"]) for r in rows]
        for f in formulas:
            ax.plot([float(r[f + "_ratio"]) for r in rows], z, "o" + style, label=f"{f.replace('_', ' ')}, {column}")
        ax.plot([float(r["fem_ratio"]) for r in rows], z, "k" + style, label=f"FEM, {column}")
    ax.axvline(float(prof[0]["k0"]), color="r", lw=1, label="K0 = nu/(1-nu)")
    ax.set_xlabel("(sigma_xx + sigma_yy) / (2 sigma_zz)")
    ax.set_ylabel("z (m)")
    ax.legend(fontsize=7)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "lateral_ratio.png"), dpi=120)

    l2 = table(os.path.join(folder, "relative_l2.csv"))
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for r in l2:
        levels = sorted((k for k in r if k.startswith("level_spread_")), key=lambda k: int(k.split("_")[-1]))
        ax.plot(range(len(levels)), [float(r[k]) for k in levels], "o-", label=r["formula"].replace("_", " "))
    ax.set_xlabel("level k (0 = floor)")
    ax.set_ylabel("(max - min) / |mean| of sigma_zz")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "level_spread.png"), dpi=120)


if __name__ == "__main__":
    main()
