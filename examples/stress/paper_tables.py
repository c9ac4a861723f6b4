#!/usr/bin/python3
"""Runs the stress examples (stress_examples) and turns their CSV tables into the paper's
tables and plots (docs/stress.md, "Examples"):

  paper_tables.py STRESS_EXAMPLES OUT [--quick] [--plot-only]

Table 2/4: symmetry against particle count, every formula on the largest bed.
Table 3: the same on the paper's polydisperse ellipsoid beds.
Table 6/7: per-grid Bagi stress of one relaxed bed on 3x3x4, 3x3x5, 5x5x9 and 7x7x13 grids.
--quick uses small beds (a few minutes); the full set takes about an hour on one core
(the ellipsoid beds are most of it).
--plot-only redraws the plots from the CSV tables already in OUT.
Plots: OUT/symmetry.png and OUT/symmetry_ellipsoids.png (RAI against count), OUT/grids.png
(sigma_zz against depth)."""
import csv
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    exe, out = sys.argv[1], sys.argv[2]
    quick = "--quick" in sys.argv
    os.makedirs(out, exist_ok=True)
    counts = ["68", "153", "500"] if quick else ["68", "153", "500", "1536", "3456"]
    bed = "1000" if quick else "7200"
    grids = ["3,3,4", "3,3,5"] if quick else ["3,3,4", "3,3,5", "5,5,9", "7,7,13"]
    ellipsoid_counts = ["69", "200"] if quick else ["69", "200", "500", "1000"]
    if "--plot-only" not in sys.argv:
        subprocess.run([exe, "symmetry", out] + counts, check=True)
        subprocess.run([exe, "ellipsoids", out] + ellipsoid_counts, check=True)
        subprocess.run([exe, "grids", out, bed] + grids, check=True)

    for table, grains, png in [("symmetry.csv", "spheres", "symmetry.png"),
                               ("symmetry_ellipsoids.csv", "ellipsoids", "symmetry_ellipsoids.png")]:
        sym = rows(os.path.join(out, table))
        fig, ax = plt.subplots(figsize=(6, 4))
        for formula, style in [("weber", "o-"), ("drescher", "s-"), ("bagi", "^-"), ("modified_nicot", "v--")]:
            pts = [(int(r["count"]), 100 * max(float(r["rai"]), 1e-16)) for r in sym if r["formula"] == formula]
            ax.loglog(*zip(*pts), style, label=formula.replace("_", " "))
        settled = sorted({(int(r["count"]), 100 * float(r["settled_bagi_rai"])) for r in sym})
        ax.loglog(*zip(*settled), "k:", label="bagi, settled (not relaxed)")
        ax.set_xlabel(f"number of {grains}")
        ax.set_ylabel("relative asymmetry index (%)")
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(out, png), dpi=120)

    fig, ax = plt.subplots(figsize=(6, 4))
    for spec in grids:
        nx, ny, nz = (int(v) for v in spec.split(","))
        g = rows(os.path.join(out, f"grid_{nx}x{ny}x{nz}.csv"))
        centre = [r for r in g if int(r["i"]) == nx // 2 and int(r["j"]) == ny // 2]
        centre.sort(key=lambda r: float(r["z"]))
        ax.plot([float(r["bagi_s_zz"]) for r in centre], [float(r["z"]) for r in centre], "o-",
                label=f"{nx}x{ny}x{nz}, centre column")
    ax.set_xlabel("Bagi sigma_zz (Pa)")
    ax.set_ylabel("z (m)")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "grids.png"), dpi=120)
    print(f"\nplots: {out}/symmetry.png, {out}/symmetry_ellipsoids.png, {out}/grids.png")


if __name__ == "__main__":
    main()
