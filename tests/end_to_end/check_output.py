#!/usr/bin/python3
"""Checks an upgrain output folder: every XDMF data item points at an HDF5 dataset of the
stated shape, snapshots hold particles sorted by id, the time series parses and its
columns match its header, and summary.json is complete."""
import csv
import json
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

folder = sys.argv[1]
expected = int(sys.argv[2])
os.chdir(folder)
items = 0
for item in ET.parse("particles.xdmf").iter("DataItem"):
    name, path = item.text.split(":")
    dims = [int(x) for x in item.get("Dimensions").split()]
    with h5py.File(name, "r") as h:
        assert list(h[path].shape) == dims, (name, path, h[path].shape, dims)
        ids = h["/particles/id"][:]
        assert len(ids) == expected and np.all(np.diff(ids) > 0), "particles not sorted by id"
        assert np.all(np.isfinite(h["/particles/position"][:]))
    items += 1
assert items >= 6 * 3, f"too few XDMF items: {items}"
with open("time_series.csv") as f:
    rows = [r for r in csv.reader(l for l in f if not l.startswith("#"))]
header, data = rows[0], rows[1:]
assert len(data) >= 40 and all(len(r) == len(header) for r in data), "time series malformed"
summary = json.load(open("summary.json"))
for key in ("particles", "steps", "energy_balance_error", "bed_solid_fraction", "particle_steps_per_second"):
    assert key in summary, key
assert summary["particles"] == expected
# Grid stress: every XDMF item resolves to a dataset of the stated shape; the CSV holds
# one row per evaluation, cell and formula and agrees with the HDF5 tensors; the modified
# forms are symmetric in every cell (an exact property in any state, docs/stress.md).
grid_items = 0
for item in ET.parse("grid_stress.xdmf").iter("DataItem"):
    if item.get("Format") != "HDF":
        continue
    name, path = item.text.split(":")
    dims = [int(x) for x in item.get("Dimensions").split()]
    with h5py.File(name, "r") as h:
        shape = list(h[path].shape)
        assert int(np.prod(shape)) == int(np.prod(dims)), (name, path, shape, dims)
    grid_items += 1
with open("grid_stress.csv") as f:
    rows = [r for r in csv.reader(l for l in f if not l.startswith("#"))]
gheader, gdata = rows[0], rows[1:]
formulas = sorted({r[gheader.index("formula")] for r in gdata})
assert formulas == sorted(["weber", "drescher", "bagi", "de_saxce", "nicot", "modified_nicot",
                           "modified_de_saxce"]), formulas
files = sorted(os.listdir("grid_stress"))
assert len(gdata) == len(files) * 36 * 7, (len(gdata), len(files))
with h5py.File(os.path.join("grid_stress", files[-1]), "r") as h:
    step = int(h.attrs["step"])
    mn = h["/stress/modified_nicot/tensor"][:].reshape(-1, 3, 3)
    bagi = h["/stress/bagi/tensor"][:].reshape(-1, 3, 3)
    assert np.all(np.abs(mn - mn.transpose(0, 2, 1)) <= 1e-10 * np.abs(mn).max())
    last = [r for r in gdata if int(r[1]) == step and r[gheader.index("formula")] == "bagi"]
    for r in last:
        c = int(r[gheader.index("cell")])
        csv_t = np.array([float(v) for v in r[gheader.index("s_xx"):gheader.index("s_zz") + 1]])
        assert np.array_equal(csv_t, bagi[c].reshape(9)), (c, csv_t, bagi[c])
    assert int(h["/cells/particles"][:].sum()) <= expected
leftovers = [f for root, _, files in os.walk(".") for f in files if ".tmp." in f]
assert not leftovers, f"temporary files left: {leftovers}"
print(f"output ok: {items} XDMF items, {len(data)} time-series rows, {grid_items} grid-stress items, "
      f"{len(files)} grid-stress evaluations")
