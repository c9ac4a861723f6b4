#!/usr/bin/python3
"""Pouring at a rate (examples/pour/README.md; docs/insertion.md): from a run's output folder,

  plot_pour.py FOLDER [--rate 3000] [--start 0] [--interval 0.005] [--out DIR] [--check]

pour.png   the grains in the container over time against the rate's line (rate x elapsed time,
           batch by batch), and the height of the bed (the surface below which 95 % of the
           settled grains' tops lie, settled: slower than 5 cm/s) and of the highest grain

and prints the count at each snapshot and the final bed. The rate, start and interval are the
scene's Insertion entries (the defaults are smoke_pour.prm's). --check exits non-zero unless
every grain asked for is in (summary.json: inserted_particles = insertion_target = particles),
none left the container, the count at every snapshot is the count the rate asked for by then
(every batch placed whole: the inlet had room), and the run ended at rest."""
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


# A grain slower than this is part of the bed, not of the rain falling onto it.
SETTLED_SPEED = 0.05  # m/s


def snapshots(folder):
    """(time, count, bed height, highest grain top, step) of each snapshot; the bed's height is the
    surface below which 95 % of the settled grains' tops lie."""
    out = []
    for f in sorted(glob.glob(os.path.join(folder, "snapshots", "*.h5"))):
        with h5py.File(f) as h:
            r = h["particles/radius"][:]
            top = h["particles/position"][:, 2] + r if len(r) else np.zeros(0)
            speed = np.linalg.norm(h["particles/velocity"][:], axis=1) if len(r) else np.zeros(0)
            settled = np.sort(top[speed < SETTLED_SPEED])
            bed = settled[int(0.95 * (len(settled) - 1))] if len(settled) else 0.0
            out.append((h.attrs["time"], len(r), bed, top.max() if len(top) else 0.0, h.attrs["step"]))
    return np.array(out)


def due(rate, start, interval, dt, step, target):
    """Grains the rate has asked for by the end of `step`: batch b goes in before the step after
    round((start + b interval) / dt) and brings those due by the end of its interval
    (dem/engine/pour.cc, dem/scene/insertion.cc grains_due)."""
    batches = 0
    while round((start + batches * interval) / dt) < step:
        batches += 1
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
    last = s[-1]
    dt = last[0] / last[4] if last[4] > 0 else 1.0
    asked = np.array([due(a.rate, a.start, a.interval, dt, step, target) for step in s[:, 4]])
    fine = np.arange(0, int(last[4]) + 1, max(1, int(a.interval / dt / 10)))
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
    ax.plot(fine * dt, [due(a.rate, a.start, a.interval, dt, k, target) for k in fine], color="gray", ls="--",
            label="asked: rate x time, batch by batch")
    ax.plot(s[:, 0], poured, "o-", ms=3, label="in the container")
    ax.set_ylabel("grains poured")
    ax.legend(fontsize=8)
    bx.plot(s[:, 0], 100 * s[:, 2], "o-", ms=3, label="bed (95 % of settled grain tops below)")
    bx.plot(s[:, 0], 100 * s[:, 3], "s-", ms=3, label="highest grain")
    bx.set_ylabel("height (cm)")
    bx.set_xlabel("t (s)")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "pour.png"), dpi=120)
    plt.close(fig)
    for t, n, bed, top, _ in s:
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
        wrong = poured != asked
        if wrong.any():
            k = np.argmax(wrong)
            problems.append(f"{int(poured[k])} grains poured at t = {s[k, 0]:.4f} s, {int(asked[k])} asked")
        if summary["stopped_at_rest"] is not True:
            problems.append("the run did not end at rest")
        if problems:
            sys.exit("check failed: " + "; ".join(problems))
        print("check passed: every grain in, none lost, the count the rate asked for at every snapshot, the bed at rest")


if __name__ == "__main__":
    main()
