#!/usr/bin/python3
"""Compute grids against the fixed grid (examples/compute-grids/README.md): the stress of every MPI
block (compute_grid_stress.csv) set against the fixed grid's cells covering the same region
(grid_stress/*.h5), at one evaluation (the last by default), as the paper's Table 6 does:

  compare_blocks.py FOLDER [--time T] [--formula bagi] [--out DIR] [--check]

The fixed grid's value for a block's box is sum_c w_c V_c sigma_c / V_b, w_c the share of cell c's
volume inside the block: exact where the block's planes fall on cell faces (Bagi's stress is a
sum over grains, so V sigma adds over regions), otherwise it spreads each cell's sum uniformly over
the cell. Over the whole box the two must agree to rounding: sum_b V_b sigma_b = sum_c V_c sigma_c
(every grain is in one block and in one cell; docs/stress.md, "Stress in parallel").

blocks_s_zz.png   sigma_zz per block: the block's own against the fixed grid's over its box

Prints one row per block: its box, grains, sigma_zz, the fixed grid's over the same box, RAI.

--check exits non-zero unless: one block per rank of the run and every grain in one block; the
whole-box identity above holds to 1e-9 of the largest entry for all nine components; every block
holding grains at rest has RAI below --rai (1e-4 = 0.01 %; the paper's Table 6: 3e-5 % to 3e-2 %);
and in every column of blocks the lower block carries more compression than the one above it
(sigma_zz grows with depth)."""
import argparse
import csv
import json
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

AXES = [a + b for a in "xyz" for b in "xyz"]


def read_blocks(folder, formula, time=None):
    """(rows of the evaluation nearest to `time`, or the last, for `formula`; its step)."""
    with open(os.path.join(folder, "compute_grid_stress.csv")) as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#")) if r["formula"] == formula]
    steps = sorted({(float(r["time"]), int(r["step"])) for r in rows})
    t, step = steps[-1] if time is None else min(steps, key=lambda s: abs(s[0] - time))
    return [r for r in rows if int(r["step"]) == step], t, step


def fixed_grid(folder, step, formula):
    """(lo, hi, n, cell volume, tensors[c, 9], particles[c]) of the fixed grid at `step`."""
    with h5py.File(os.path.join(folder, "grid_stress", f"grid_stress_{step:09d}.h5")) as h:
        lo, hi, n = h["grid/lo"][()], h["grid/hi"][()], h["grid/n"][()].astype(int)
        return lo, hi, n, float(h["grid"].attrs["cell_volume"]), h[f"stress/{formula}/tensor"][()], h["cells/particles"][()]


def overlap(a0, a1, b0, b1):
    return max(0.0, min(a1, b1) - max(a0, b0))


def fixed_over_box(grid, box_lo, box_hi):
    """sum_c w_c V_c sigma_c over the cells of `grid`, w_c the share of cell c inside the box."""
    lo, hi, n, vol, tensor, _ = grid
    h = (hi - lo) / n
    total = np.zeros(9)
    # Cells in grid order: i fastest, then j, then k (docs/output.md, grid_stress.csv).
    for k in range(n[2]):
        for j in range(n[1]):
            for i in range(n[0]):
                c0 = lo + h * np.array([i, j, k])
                w = np.prod([overlap(c0[d], c0[d] + h[d], box_lo[d], box_hi[d]) / h[d] for d in range(3)])
                if w > 0:
                    total += w * vol * tensor[i + n[0] * (j + n[1] * k)]
    return total


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("folder")
    p.add_argument("--time", type=float, default=None)
    p.add_argument("--formula", default="bagi")
    p.add_argument("--out", default=None)
    p.add_argument("--rai", type=float, default=1e-4)
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    out = a.out or a.folder
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(a.folder, "summary.json")) as f:
        summary = json.load(f)
    blocks, t, step = read_blocks(a.folder, a.formula, a.time)
    grid = fixed_grid(a.folder, step, a.formula)
    print(f"{len(blocks)} blocks at t = {t:.4g} s (step {step}); fixed grid {' x '.join(map(str, grid[2]))} "
          f"cells up to z = {100 * grid[1][2]:.2f} cm")
    print(" block | box x, y, z (cm)                          | grains | s_zz block | s_zz fixed grid | RAI")
    table = []
    for r in sorted(blocks, key=lambda r: int(r["block"])):
        b_lo = np.array([float(r[c]) for c in ("x0", "y0", "z0")])
        b_hi = np.array([float(r[c]) for c in ("x1", "y1", "z1")])
        vol = float(r["volume"])
        own = np.array([float(r["s_" + c]) for c in AXES])
        fixed = fixed_over_box(grid, b_lo, b_hi) / vol
        table.append(dict(block=int(r["block"]), lo=b_lo, hi=b_hi, vol=vol, own=own, fixed=fixed,
                          particles=int(r["particles"]), rai=float(r["rai"])))
        box = ", ".join(f"{100 * b_lo[d]:.2f}-{100 * b_hi[d]:.2f}" for d in range(3))
        print(f" {r['block']:>5} | {box:41} | {r['particles']:>6} | {own[8]:10.1f} | {fixed[8]:15.1f} | "
              f"{100 * float(r['rai']):.1e} %")
    blocks_sum = sum(b["vol"] * b["own"] for b in table)
    cells_sum = grid[3] * grid[4].sum(axis=0)
    scale = max(np.abs(cells_sum).max(), 1e-300)
    identity = np.abs(blocks_sum - cells_sum).max() / scale
    print(f"whole box: sum V_b s_zz,b = {blocks_sum[8]:.9e} N m, sum V_c s_zz,c = {cells_sum[8]:.9e} N m; "
          f"largest difference over the nine components {identity:.1e} of the largest entry")

    fig, ax = plt.subplots(figsize=(6.5, 3.4))
    idx = np.arange(len(table))
    ax.bar(idx - 0.2, [b["own"][8] for b in table], 0.4, label="block (compute grid)")
    ax.bar(idx + 0.2, [b["fixed"][8] for b in table], 0.4, label="fixed grid over the block's box")
    ax.set_xticks(idx)
    ax.set_xticklabels([f"{b['block']}\nz {100 * b['lo'][2]:.1f}-{100 * b['hi'][2]:.1f}" for b in table], fontsize=7)
    ax.set_xlabel("block (rank), z range in cm")
    ax.set_ylabel(f"sigma_zz ({a.formula}, Pa)")
    ax.legend(fontsize=7)
    ax.set_title(f"sigma_zz per MPI block against the fixed grid, t = {t:.3g} s", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "blocks_s_zz.png"), dpi=100)
    plt.close(fig)

    if a.check:
        problems = []
        if len(table) != summary["mpi_ranks"]:
            problems.append(f"{len(table)} blocks for {summary['mpi_ranks']} ranks")
        if sum(b["particles"] for b in table) != summary["particles"]:
            problems.append("the blocks do not hold every grain once")
        if int(grid[5].sum()) != summary["particles"]:
            problems.append("grains outside the fixed grid: its box must hold the bed for the identity")
        if not identity <= 1e-9:
            problems.append(f"sum V_b sigma_b differs from sum V_c sigma_c by {identity:.1e} of the largest entry")
        for b in table:
            if b["particles"] > 0 and not b["rai"] < a.rai:
                problems.append(f"block {b['block']}: RAI {b['rai']:.1e} at rest")
        for b in table:
            above = [c for c in table if np.allclose(c["lo"][:2], b["lo"][:2]) and np.isclose(c["lo"][2], b["hi"][2])]
            for c in above:
                if not b["own"][8] < c["own"][8]:
                    problems.append(f"block {b['block']} (sigma_zz {b['own'][8]:.1f} Pa) is not more compressed "
                                    f"than block {c['block']} above it ({c['own'][8]:.1f} Pa)")
        if problems:
            sys.exit("check failed: " + "; ".join(problems))
        print(f"check passed: {len(table)} blocks, every grain in one, whole-box identity to {identity:.1e}, "
              f"RAI < {a.rai:g}, sigma_zz grows with depth in every column of blocks")


if __name__ == "__main__":
    main()
