#!/usr/bin/python3
"""Pouring at a rate (examples/pour/README.md; docs/insertion.md): from a run's output folder,

  plot_pour.py FOLDER [--rate 3000] [--start 0] [--interval 0.005] [--out DIR] [--check]

pour.png   the grains in the container over time against the rate's line (rate x elapsed time,
           batch by batch), and the height of the bed (the grain surface below which 95 % of
           the grains lie) and of the highest grain

and prints the count at each snapshot and the final bed. The rate, start and interval are the
scene's Insertion entries (the defaults are smoke_pour.prm's). --check exits non-zero unless
every grain asked for is in (summary.json: inserted_particles = insertion_target = particles),
none left the container, the count never ran ahead of the rate nor fell more than one batch
behind it while the inlet was free, and the run ended at rest."""
import argparse
import glob
import json
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def snapshots(folder):
    """(time, count, bed height, highest grain top) of each snapshot."""
    out = []
    for f in sorted(glob.glob(os.path.join(folder, "snapshots", "*.h5"))):
        with h5py.File(f) as h:
            r = h["particles/radius"][:]
            top = h["particles/position"][:, 2] + r if len(r) else np.zeros(0)
            bed = np.sort(top)[int(0.95 * (len(top) - 1))] if len(top) else 0.0
            out.append((h.attrs["time"], len(r), bed, top.max() if len(top) else 0.0))
    return np.array(out)


def due(rate, start, interval, t, target):
    """Grains the rate has asked for by time t: batch b (at start + b interval) brings those due by
    the end of its interval (dem/scene/insertion.cc, grains_due)."""
    if t < start - 1e-12:
        return 0
    batches = math.floor((t - start) / interval + 1e-9) + 1
    return min(target, math.floor(rate * batches * interval + 0.5))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("folder")
    p.add_argument("--rate", type=float, default=3000.0)
    p.add_argument("--start", type=float, default=0.0)
    p.add_argument("--interval", type=float, default=0.005)
    p.add_argument("--out", default=".")
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.folder, "summary.json")) as f:
        summary = json.load(f)
    target = int(summary["insertion_target"])
    s = snapshots(a.folder)
    first = int(s[0, 1])  # the initial fill
    poured = s[:, 1] - first
    asked = np.array([due(a.rate, a.start, a.interval, t, target) for t in s[:, 0]])
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
    ax.step(s[:, 0], asked, where="post", color="gray", ls="--", label="asked: rate x time, by batch")
    ax.plot(s[:, 0], poured, "o-", ms=3, label="in the container")
    ax.set_ylabel("grains poured")
    ax.legend(fontsize=8)
    bx.plot(s[:, 0], 100 * s[:, 2], "o-", ms=3, label="bed (95 % of grain tops below)")
    bx.plot(s[:, 0], 100 * s[:, 3], "s-", ms=3, label="highest grain")
    bx.set_ylabel("height (cm)")
    bx.set_xlabel("t (s)")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "pour.png"), dpi=120)
    plt.close(fig)
    for t, n, bed, top in s:
        print(f"t = {t:.3f} s: {int(n)} grains, bed {100 * bed:.2f} cm, highest {100 * top:.2f} cm")
    print(f"inserted {summary['inserted_particles']} of {target}; {summary['particles']} grains at the end, "
          f"{summary['particles_outside_container']} outside; stopped at rest: {summary['stopped_at_rest']} "
          f"(kinetic / released {float(summary['kinetic_to_released']):.3g}) at t = "
          f"{float(summary['simulated_time_s']):.3f} s; solid fraction {float(summary['bed_solid_fraction']):.3f}")
    if a.check:
        problems = []
        if int(summary["inserted_particles"]) != target or int(summary["particles"]) != first + target:
            problems.append(f"{summary['inserted_particles']} of {target} inserted, {summary['particles']} at the end")
        if int(summary["particles_outside_container"]) != 0:
            problems.append(f"{summary['particles_outside_container']} grains outside the container")
        per_batch = math.floor(a.rate * a.interval + 0.5)
        ahead = poured > asked
        behind = poured < asked - per_batch
        if ahead.any():
            problems.append(f"ahead of the rate at t = {s[ahead, 0][0]:.3f} s")
        if behind.any():
            problems.append(f"more than a batch behind the rate at t = {s[behind, 0][0]:.3f} s")
        if summary["stopped_at_rest"] is not True:
            problems.append("the run did not end at rest")
        if problems:
            sys.exit("check failed: " + "; ".join(problems))
        print("check passed: every grain in, none lost, the count followed the rate, the bed at rest")


if __name__ == "__main__":
    main()
