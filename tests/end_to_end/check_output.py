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
leftovers = [f for root, _, files in os.walk(".") for f in files if ".tmp." in f]
assert not leftovers, f"temporary files left: {leftovers}"
print(f"output ok: {items} XDMF items, {len(data)} time-series rows")
