#!/usr/bin/env python3
"""The load-displacement curve of `upgrain --study femxdem` (docs/femxdem.md): the deviator
stress q = sigma_1 - sigma_3 and the Newton iterations per step against the axial strain, from
load_displacement.csv in the folder given."""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(folder: Path) -> None:
    with open(folder / "load_displacement.csv") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
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


if __name__ == "__main__":
    main(Path(sys.argv[1]))
