#!/usr/bin/python3
"""Checks a tiny unconstrained collapse run through the driver (tiny_unconstrained_collapse.prm,
docs/scenes.md) by what must hold physically and in the files:
- every grain is inside the box while the walls stand, and the pile has spread past every
  former wall by the end, with its top lower, no grain below the floor, nothing lost;
- the removed walls carry no force after the release; the floor carries the weight at the end
  within 5 %;
- the strain is relative to the state at the release (reference time 0.3 s, Eulerian sets),
  with one output per grid-stress evaluation from there on, and some cell has valid stress
  rates;
- report.md names the collapse and has a sane Strain section (check_strain_report.py)."""
import json
import os
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))  # before the chdir
sys.path.insert(0, HERE)
from check_strain_report import check_strain_report  # noqa: E402

folder, expected = sys.argv[1], int(sys.argv[2])
os.chdir(folder)
open_time, lx, ly, g = 0.3, 0.015, 0.015, 9.81
snaps = []
for f in sorted(os.listdir("snapshots")):
    with h5py.File(os.path.join("snapshots", f), "r") as h:
        snaps.append({"time": float(h.attrs["time"]), "x": h["/particles/position"][:],
                      "r": h["/particles/radius"][:], "id": h["/particles/id"][:],
                      "mass": (4 / 3 * np.pi * h["/particles/radius"][:] ** 3 * 2650).sum(),
                      "walls": [n for n in range(h["/walls/force"].shape[0])],
                      "wall_force": h["/walls/force"][:], "wall_normal": h["/walls/normal"][:]})
before = [s for s in snaps if s["time"] <= open_time + 1e-9][-1]
last = snaps[-1]
assert abs(before["time"] - open_time) < 1e-9, before["time"]
overlap = 0.02 * before["r"].max()
x, r = before["x"], before["r"]
assert (x[:, 0] - r).min() >= -overlap and (x[:, 0] + r).max() <= lx + overlap, "walls did not hold (x)"
assert (x[:, 1] - r).min() >= -overlap and (x[:, 1] + r).max() <= ly + overlap, "walls did not hold (y)"
x, r = last["x"], last["r"]
assert len(last["id"]) == expected and np.array_equal(np.sort(last["id"]), np.sort(before["id"])), "grains lost"
assert np.all(np.isfinite(x))
assert (x[:, 0] - r).min() < -r.max() and (x[:, 0] + r).max() > lx + r.max(), "no spreading along x"
assert (x[:, 1] - r).min() < -r.max() and (x[:, 1] + r).max() > ly + r.max(), "no spreading along y"
top_before = (before["x"][:, 2] + before["r"]).max()
top_after = (x[:, 2] + r).max()
assert top_after < 0.75 * top_before, (top_before, top_after)
assert (x[:, 2] - r).min() > -0.05 * r.max(), "a grain sank into the floor"
# Walls: the floor has normal +z; the four side walls carry nothing after the release.
for s in snaps:
    if s["time"] <= open_time + 1e-9:
        continue
    side = [k for k in s["walls"] if abs(s["wall_normal"][k][2]) < 0.5]
    assert len(side) == 4 and np.all(s["wall_force"][side] == 0.0), (s["time"], s["wall_force"])
floor = [k for k in last["walls"] if last["wall_normal"][k][2] > 0.5][0]
weight = last["mass"] * g
assert abs(-last["wall_force"][floor][2] - weight) < 0.05 * weight, (last["wall_force"][floor], weight)
summary = json.load(open("summary.json"), parse_constant=lambda c: sys.exit(f"summary.json: {c} is not JSON"))
assert summary["particles_outside_container"] > 0
# Strain from the release on; rates from its second output.
files = sorted(os.listdir("grid_strain"))
stress_files = sorted(os.listdir("grid_stress"))
valid_rates = 0
for k, f in enumerate(files):
    with h5py.File(os.path.join("grid_strain", f), "r") as h:
        assert abs(h.attrs["reference_time"] - open_time) < 1e-9, h.attrs["reference_time"]
        assert h.attrs["set"] in (b"eulerian", "eulerian")
        assert h["rates"].attrs["outputs_used"] == min(k + 1, 3)
        for d in ("best_fit", "tessellation"):
            for key in h[d]:
                assert np.all(np.isfinite(h[d][key][:])), (f, d, key)
            valid_rates += int(h[d]["rate_valid"][:].sum())
            if k == 0:
                valid = h[d]["F_valid"][:] == 1
                assert valid.any() and np.abs(h[d]["ln_J"][:][valid]).max() <= 1e-12, (d, "F = 1 at t0")
with h5py.File(os.path.join("grid_strain", files[0]), "r") as h:
    t_first = float(h.attrs["time"])
assert abs(t_first - open_time) < 1e-9, t_first
n_after = sum(1 for f in stress_files if int(f.split("_")[-1].split(".")[0]) >= round(open_time / 1e-5))
assert len(files) == n_after, (len(files), n_after)
assert valid_rates > 0, "no valid stress rate in any cell"
report = open("report.md").read()
assert "unconstrained collapse: all side walls removed at t = 0.3 s" in report, report[:600]
outputs = check_strain_report()
print(f"collapse ok: top {top_before:.4f} -> {top_after:.4f} m, extent x [{(x[:, 0] - r).min():.4f}, "
      f"{(x[:, 0] + r).max():.4f}] m, {outputs} strain outputs, {valid_rates} valid cell rates")
