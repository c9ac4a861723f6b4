#!/usr/bin/python3
"""Energies and wall forces over a run (the paper's Fig. 8; examples/energies/README.md):

  plot_energies.py OUTPUT_FOLDER [--density 2650] [--gravity 9.81] [--out DIR] [--check]

energies.png     kinetic (translational + rotational), potential released, elastic (normal +
                 tangential), dissipated (damping, friction) and the balance error, from
                 time_series.csv (docs/output.md)
wall_forces.png  the vertical force the grains exert on the floor and on the side walls at each
                 snapshot (/walls/force), against the grains' weight

--check exits non-zero unless the run's energy balance closes to 1 % and, at the last snapshot,
the walls together carry the weight (density x volume x g of the grains) to 1 %: true of a bed
at rest, which is how the examples end."""
import argparse
import glob
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    p = argparse.ArgumentParser()
    p.add_argument("folder")
    p.add_argument("--density", type=float, default=2650.0)
    p.add_argument("--gravity", type=float, default=9.81)
    p.add_argument("--out", default=None)
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    out = a.out or a.folder
    os.makedirs(out, exist_ok=True)
    s = np.genfromtxt(os.path.join(a.folder, "time_series.csv"), delimiter=",", names=True, skip_header=1)
    t = s["time"]
    kinetic = s["kinetic_translational"] + s["kinetic_rotational"]
    released = s["potential"][0] - s["potential"]
    elastic = s["elastic_normal"] + s["elastic_tangential"]
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    for y, label in ((released, "potential released"), (kinetic, "kinetic"), (elastic, "elastic"),
                     (s["dissipated_damping"], "dissipated, damping"), (s["dissipated_friction"], "dissipated, friction")):
        ax.plot(t, y, label=label)
    ax.set_ylabel("energy (J)")
    ax.legend(fontsize=8)
    bx.plot(t, 100 * s["balance_error"], "k-")
    bx.set_ylabel("balance error (%)")
    bx.set_xlabel("t (s)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "energies.png"), dpi=120)
    plt.close(fig)

    times, floor, sides, weight = [], [], [], None
    for f in sorted(glob.glob(os.path.join(a.folder, "snapshots", "*.h5"))):
        with h5py.File(f) as h:
            fz = -h["walls/force"][:, 2]  # the force on the walls points down: its negative is what they carry
            times.append(h.attrs["time"])
            floor.append(fz[0])
            sides.append(fz[1:].sum())
            if "semi_axes" in h["particles"]:
                volume = np.prod(h["particles/semi_axes"][:], axis=1).sum() * 4 / 3 * np.pi
            else:
                volume = (h["particles/radius"][:] ** 3).sum() * 4 / 3 * np.pi
            weight = a.density * volume * a.gravity
    fig, ax = plt.subplots(figsize=(6.5, 3.4))
    ax.plot(times, floor, "o-", label="floor")
    ax.plot(times, sides, "s-", label="side walls")
    ax.plot(times, np.array(floor) + np.array(sides), "k.-", label="all walls")
    ax.axhline(weight, color="gray", ls="--", label="weight of the grains")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("vertical force carried (N)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "wall_forces.png"), dpi=120)
    plt.close(fig)
    total = floor[-1] + sides[-1]
    worst = np.abs(s["balance_error"]).max()
    print(f"largest |balance error| {100 * worst:.3g} %; at t = {times[-1]:.3g} s the walls carry {total:.5g} N "
          f"of a weight of {weight:.5g} N ({100 * total / weight:.2f} %), the side walls {100 * sides[-1] / total:.2f} %;"
          f" dissipated by damping {s['dissipated_damping'][-1]:.4g} J, by friction {s['dissipated_friction'][-1]:.4g} J "
          f"of {released[-1]:.4g} J released")
    if a.check:
        problems = []
        if worst > 0.01:
            problems.append(f"the energy balance is off by {100 * worst:.3g} %")
        if abs(total / weight - 1) > 0.01:
            problems.append(f"the walls carry {100 * total / weight:.2f} % of the weight at the end")
        if problems:
            sys.exit("check failed: " + "; ".join(problems))
        print("check passed: balance within 1 %, walls carry the weight within 1 %")


if __name__ == "__main__":
    main()
