#!/usr/bin/python3
"""Checks an upgrain output folder: every XDMF data item points at an HDF5 dataset of the
stated shape, snapshots hold particles sorted by id, the time series parses and its
columns match its header, and summary.json is complete; the grid stress and strain files
are consistent, the objective stress rates recompute from the files' own data, and
report.md has a sane Strain section (check_strain_report.py)."""
import csv
import json
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))  # before any chdir


def check_cell_xdmf(xdmf):
    """Every HDF data item of a grid XDMF file resolves to a dataset of the stated size;
    returns the number of items."""
    count = 0
    for item in ET.parse(xdmf).iter("DataItem"):
        if item.get("Format") != "HDF":
            continue
        name, path = item.text.split(":")
        dims = [int(x) for x in item.get("Dimensions").split()]
        with h5py.File(name, "r") as h:
            shape = list(h[path].shape)
            assert int(np.prod(shape)) == int(np.prod(dims)), (name, path, shape, dims)
        count += 1
    return count


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
# walls.csv: one row per wall and time-series row, at the series' times; the normal and shear
# columns are the parts of the force columns along the wall's normal and across it.
with open("walls.csv") as f:
    wrows = [r for r in csv.reader(l for l in f if not l.startswith("#"))]
wheader, wdata = wrows[0], wrows[1:]
walls = sorted({r[wheader.index("wall")] for r in wdata})
assert walls and len(wdata) == len(walls) * len(data), ("walls.csv rows", len(wdata), len(walls), len(data))
assert sorted({r[0] for r in wdata}) == sorted({r[0] for r in data}), "walls.csv times are not the series'"
with h5py.File("snapshots/" + sorted(os.listdir("snapshots"))[-1], "r") as h:
    names = h["/walls"].attrs["names"]
    normals = h["/walls/normal"][:]
names = (names.decode() if isinstance(names, bytes) else str(names)).split(",")
for r in wdata:
    n = normals[names.index(r[wheader.index("wall")])]
    force = np.array([float(r[wheader.index(c)]) for c in ("force_x", "force_y", "force_z")])
    fn = force.dot(n)
    assert float(r[wheader.index("normal_force")]) == -fn + 0.0, r
    assert abs(float(r[wheader.index("shear_force")]) - np.linalg.norm(force - fn * n)) <= 1e-12 * (
        1 + np.linalg.norm(force)), r
summary = json.load(open("summary.json"), parse_constant=lambda c: sys.exit(f"summary.json: {c} is not JSON"))
for key in ("particles", "steps", "energy_balance_error", "bed_solid_fraction", "particle_steps_per_second"):
    assert key in summary, key
assert summary["particles"] == expected
# Grid stress: every XDMF item resolves to a dataset of the stated shape; the CSV holds
# one row per evaluation, cell and formula and agrees with the HDF5 tensors; the modified
# forms are symmetric in every cell (an exact property in any state, docs/stress.md).
grid_items = check_cell_xdmf("grid_stress.xdmf")
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
# Grid strain (tiny_scene.prm enables it, Lagrangian, t0 = 0, both definitions): every XDMF
# item resolves; no NaN anywhere; one file per grid-stress evaluation plus the reference
# state; every valid cell of the first evaluation (t0) has F = 1, J = 1 to round-off;
# invalid cells are zero and carry a reason code; the CSV agrees with the HDF5 files.
strain_items = check_cell_xdmf("grid_strain.xdmf")
strain_files = sorted(os.listdir("grid_strain"))
assert len(strain_files) == len(files) + 1, (len(strain_files), len(files))
definitions = ("best_fit", "tessellation")
for k, f in enumerate(strain_files):
    with h5py.File(os.path.join("grid_strain", f), "r") as h:
        assert h.attrs["set"] in (b"lagrangian", "lagrangian"), h.attrs["set"]
        assert h.attrs["reference_time"] == 0.0
        names = [n.decode() if isinstance(n, bytes) else n for n in h.attrs["reason_names"]]
        assert names[0] == "valid" and "too few particles" in names, names
        cells = int(np.prod(h["/grid/n"][:]))
        assert h["/cells/particles"].shape == (cells,)
        for d in definitions:
            g = h[d]
            for key in g:
                data = g[key][:]
                assert np.all(np.isfinite(data)), (f, d, key)
                assert data.shape[0] == cells, (f, d, key, data.shape)
            for prefix in ("F", "L", "increment"):
                valid, reason = g[prefix + "_valid"][:], g[prefix + "_reason"][:]
                assert np.array_equal(valid == 1, reason == 0), (f, d, prefix)
                assert np.all((reason >= 0) & (reason < len(names)))
            valid = g["F_valid"][:] == 1
            F = g["F"][:]
            assert np.all(F[~valid] == 0.0) and np.all(g["J"][:][~valid] == 0.0), (f, d)
            too_few = h["/cells/particles"][:] < 4
            assert np.all(g["F_reason"][:][too_few] == names.index("too few particles")), (f, d)
            if k == 0:
                assert h.attrs["time"] == 0.0 and valid.sum() > 0, (f, d, valid.sum())
                err = np.abs(F[valid] - np.eye(3).reshape(9)).max()
                assert err <= 1e-12, (f, d, err)
                assert np.abs(g["J"][:][valid] - 1.0).max() <= 1e-12, (f, d)
                assert np.abs(g["ln_J"][:][valid]).max() <= 1e-12, (f, d)
with open("grid_strain.csv") as f:
    rows = [r for r in csv.reader(l for l in f if not l.startswith("#"))]
sheader, sdata = rows[0], rows[1:]
assert all(len(r) == len(sheader) for r in sdata), "grid strain CSV malformed"
with h5py.File(os.path.join("grid_strain", strain_files[-1]), "r") as h:
    step = int(h.attrs["step"])
    F = h["/tessellation/F"][:]
    last = [r for r in sdata if int(r[1]) == step and r[sheader.index("definition")] == "tessellation"]
    assert len(last) == F.shape[0], (len(last), F.shape)
    for r in last:
        c = int(r[sheader.index("cell")])
        csv_f = np.array([float(v) for v in r[sheader.index("F_xx"):sheader.index("F_zz") + 1]])
        assert np.array_equal(csv_f, F[c]), (c, csv_f, F[c])
leftovers = [f for root, _, files in os.walk(".") for f in files if ".tmp." in f]
assert not leftovers, f"temporary files left: {leftovers}"
print(f"strain ok: {strain_items} grid-strain items, {len(strain_files)} grid-strain evaluations")
# Objective stress rates (docs/strain.md "Stress rates over time"): every strain output with
# a grid stress has them (the t0 = 0 reference has no stress yet); the differences use 1,
# 2, then 3 outputs; the rates recomputed here from the files' own times, stresses, L and R
# by the backward difference (eq. (10), last output) and eq. (9) match the written ones; the
# validity flags match the codes; the CSV columns match the HDF5 files.
def read(f):
    with h5py.File(os.path.join("grid_strain", f), "r") as h:
        if "rates" not in h:
            return None
        out = {"time": float(h.attrs["time"]), "step": int(h.attrs["step"]),
               "used": int(h["rates"].attrs["outputs_used"]),
               "formula": h["rates"].attrs["formula"],
               "stress": h["/rates/stress"][:].reshape(-1, 3, 3)}
        for d in definitions:
            for key in ("L", "R", "F_reason", "L_reason", "stress_rate", "jaumann_rate", "green_naghdi_rate",
                        "truesdell_rate", "oldroyd_rate", "rate_valid", "rate_reason", "green_naghdi_valid",
                        "green_naghdi_reason"):
                v = h[d][key][:]
                out[d + "/" + key] = v.reshape(-1, 3, 3) if v.ndim == 2 and v.shape[1] == 9 else v.reshape(-1)
        return out


def backward(t, f):
    """d/dt at the last of 2 or 3 outputs (eq. (10), last output; two-point for 2)."""
    if len(t) == 2:
        return (f[1] - f[0]) / (t[1] - t[0])
    h1, h2 = t[1] - t[0], t[2] - t[1]
    return (h2 / (h1 * (h1 + h2))) * f[0] - ((h1 + h2) / (h1 * h2)) * f[1] + \
        ((h1 + 2 * h2) / (h2 * (h1 + h2))) * f[2]


def skew(a):
    return 0.5 * (a - np.swapaxes(a, -1, -2))


outputs = [read(f) for f in strain_files]
assert outputs[0] is None, "the t0 = 0 reference has no grid stress, hence no rates"
with_rates = [o for o in outputs[1:] if o is not None]
assert len(with_rates) == len(strain_files) - 1 and len(with_rates) >= 3, len(with_rates)
assert [o["used"] for o in with_rates[:3]] == [1, 2, 3] and all(o["used"] == 3 for o in with_rates[3:])
assert all(o["formula"] in (b"bagi", "bagi") for o in with_rates)
checked = 0
for k, o in enumerate(with_rates):
    win = with_rates[max(0, k - 2):k + 1]
    t = [w["time"] for w in win]
    for d in definitions:
        reason, valid = o[d + "/rate_reason"], o[d + "/rate_valid"] == 1
        gn_reason, gn_valid = o[d + "/green_naghdi_reason"], o[d + "/green_naghdi_valid"] == 1
        assert np.array_equal(valid, reason == 0) and np.array_equal(gn_valid, gn_reason == 0), (k, d)
        for key in ("stress_rate", "jaumann_rate", "truesdell_rate", "oldroyd_rate"):
            assert np.all(o[d + "/" + key][~valid] == 0.0), (k, d, key)
        assert np.all(o[d + "/green_naghdi_rate"][~gn_valid] == 0.0), (k, d)
        if k == 0:
            assert not valid.any() and np.all(reason == names.index("no earlier output")), (d, reason)
            continue
        bad_l = o[d + "/L_reason"] != 0
        assert np.array_equal(reason[bad_l], o[d + "/L_reason"][bad_l]), (k, d)
        s = o["stress"]
        sd = backward(t, np.array([w["stress"] for w in win]))
        L = o[d + "/L"]
        W = skew(L)
        scale = np.abs(sd).max() + np.abs(L).max() * np.abs(s).max() + 1e-300
        expect = {"stress_rate": sd,
                  "jaumann_rate": sd - W @ s + s @ W,
                  "truesdell_rate": sd - L @ s - s @ np.swapaxes(L, 1, 2) + np.trace(L, axis1=1, axis2=2)[:, None,
                                                                                                        None] * s,
                  "oldroyd_rate": sd - L @ s - s @ np.swapaxes(L, 1, 2)}
        for key, e in expect.items():
            err = np.abs(o[d + "/" + key][valid] - e[valid]).max(initial=0.0)
            assert err <= 1e-9 * scale, (k, d, key, err, scale)
        R = np.array([w[d + "/R"] for w in win])
        omega = skew(backward(t, R) @ np.swapaxes(R[-1], 1, 2))
        gn = sd - omega @ s + s @ omega
        err = np.abs(o[d + "/green_naghdi_rate"][gn_valid] - gn[gn_valid]).max(initial=0.0)
        assert err <= 1e-9 * scale, (k, d, "green_naghdi_rate", err)
        checked += int(valid.sum())
assert checked > 0, "no valid rate anywhere"
last = with_rates[-1]
rows = [r for r in sdata if int(r[1]) == last["step"] and r[sheader.index("definition")] == "best_fit"]
for r in rows:
    c = int(r[sheader.index("cell")])
    assert int(r[sheader.index("rate_reason")]) == last["best_fit/rate_reason"][c]
    for key, col in (("jaumann_rate", "jaumann"), ("green_naghdi_rate", "green_naghdi"),
                     ("truesdell_rate", "truesdell"), ("oldroyd_rate", "oldroyd")):
        v = np.array([float(x) for x in r[sheader.index(col + "_xx"):sheader.index(col + "_zz") + 1]])
        assert np.array_equal(v, last["best_fit/" + key][c].reshape(9)), (c, key)
print(f"rates ok: {len(with_rates)} outputs with rates, {checked} valid cell rates recomputed")
# report.md: the run's account with the Strain section and its plots.
sys.path.insert(0, HERE)
from check_strain_report import check_strain_report  # noqa: E402

print(f"strain report ok: {check_strain_report()} outputs")
