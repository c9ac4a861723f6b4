#!/usr/bin/python3
"""Plots of a DEM-vs-continuum study (docs/study.md), from the CSV tables the driver wrote:

  plot_study.py OUTPUT_FOLDER

profiles_szz.png   sigma_zz against height, centre and edge columns: each DEM formula, each
                   continuum (elastic on rollers, with wall friction, Drucker-Prager, Janssen),
                   the hydrostatic column;
lateral_ratio.png  (s_xx + s_yy) / (2 s_zz) against height, DEM and continua, beside K0;
wall_share.png     share of the weight the side walls carry, DEM and continua;
wall_shear.png     the side walls' mean upward shear against height, DEM (from its wall
                   contacts) and continua (wall_shear.csv);
level_spread.png   spread of sigma_zz across each level, DEM formulas and continua.

The DEM formulas and continua, with their labels, come from stress_summary.csv."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DEM_STYLES = ("o-", "s--", "^:", "v-.", "d-", "x--", "+:")
CONTINUUM_STYLES = ("k-", "b-", "r-", "g--", "m-", "c-")


def table(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def column_rows(prof, column):
    return sorted((r for r in prof if r["column"] == column), key=lambda r: float(r["z"]))


def main():
    folder = sys.argv[1]
    prof = table(os.path.join(folder, "profiles.csv"))
    summary = table(os.path.join(folder, "stress_summary.csv"))
    formulas = [(r["source"], r["label"]) for r in summary if r["kind"] == "dem"]
    continua = [(r["source"], r["label"]) for r in summary if r["kind"] == "continuum"]

    fig, axes = plt.subplots(1, 2, figsize=(11, 5), sharey=True)
    for ax, column in zip(axes, ("centre", "edge")):
        rows = column_rows(prof, column)
        z = [float(r["z"]) for r in rows]
        for (key, label), style in zip(formulas, DEM_STYLES):
            ax.plot([float(r[key + "_s_zz"]) for r in rows], z, style, label=label)
        for (key, label), style in zip(continua, CONTINUUM_STYLES):
            ax.plot([float(r[key + "_s_zz"]) for r in rows], z, style, lw=2 if key == "fem" else 1.5, label=label)
        ax.plot([float(r["analytic_s_zz"]) for r in rows], z, "k:", label="hydrostatic")
        ax.set_title(f"{column} column (i={rows[0]['i']}, j={rows[0]['j']})")
        ax.set_xlabel("sigma_zz (Pa)")
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("z (m)")
    axes[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "profiles_szz.png"), dpi=120)

    fig, axes = plt.subplots(1, 2, figsize=(11, 5), sharey=True)
    for ax, column in zip(axes, ("centre", "edge")):
        rows = column_rows(prof, column)
        z = [float(r["z"]) for r in rows]
        for (key, label), style in zip(formulas, DEM_STYLES):
            ax.plot([float(r[key + "_ratio"]) for r in rows], z, style, label=label)
        for (key, label), style in zip(continua, CONTINUUM_STYLES):
            ax.plot([float(r[key + "_ratio"]) for r in rows], z, style, label=label)
        ax.axvline(float(prof[0]["k0"]), color="k", lw=0.8, ls=":", label="K0 = nu/(1-nu)")
        ax.set_title(f"{column} column")
        ax.set_xlabel("(sigma_xx + sigma_yy) / (2 sigma_zz)")
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("z (m)")
    axes[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "lateral_ratio.png"), dpi=120)

    # The DEM's share comes from its wall forces, the same for every formula: one bar.
    dem_row = next(r for r in summary if r["kind"] == "dem")
    bars = [("DEM", float(dem_row["wall_share"]))] + [
        (r["label"], float(r["wall_share"])) for r in summary if r["kind"] == "continuum"
    ]
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.bar(range(len(bars)), [100.0 * v for _, v in bars], color=["0.4"] + ["C%d" % k for k in range(len(bars) - 1)])
    ax.set_xticks(range(len(bars)))
    ax.set_xticklabels([name for name, _ in bars], rotation=20, ha="right", fontsize=8)
    ax.set_ylabel("share of the weight on the side walls (%)")
    ax.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "wall_share.png"), dpi=120)

    shear_path = os.path.join(folder, "wall_shear.csv")
    if os.path.exists(shear_path):
        shear = table(shear_path)
        z = [0.5 * (float(r["z_lo"]) + float(r["z_hi"])) for r in shear]
        fig, ax = plt.subplots(figsize=(5, 5))
        if all(r["dem"] for r in shear):
            ax.plot([float(r["dem"]) for r in shear], z, "ko-", lw=2, label="DEM (wall contacts)")
        continua = [(r["source"], r["label"]) for r in summary if r["kind"] == "continuum"]
        for k, (key, label) in enumerate(continua):
            if key in shear[0] and all(r[key] for r in shear):
                ax.plot([float(r[key]) for r in shear], z, CONTINUUM_STYLES[k % len(CONTINUUM_STYLES)], label=label)
        ax.set_xlabel("side walls' upward shear on the fill (Pa)")
        ax.set_ylabel("z (m)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(folder, "wall_shear.png"), dpi=120)

    fig, ax = plt.subplots(figsize=(6, 4.5))
    for r in summary:
        levels = sorted((k for k in r if k.startswith("level_spread_")), key=lambda k: int(k.split("_")[-1]))
        style = "o-" if r["kind"] == "dem" else "s--"
        ax.plot(range(len(levels)), [float(r[k]) for k in levels], style, label=r["label"])
    ax.set_xlabel("level k (0 = floor)")
    ax.set_ylabel("(max - min) / |mean| of sigma_zz")
    ax.legend(fontsize=7)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "level_spread.png"), dpi=120)


if __name__ == "__main__":
    main()
