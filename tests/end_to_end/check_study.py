#!/usr/bin/python3
"""Checks a DEM-vs-continuum study folder by physical invariants, not stored numbers
(docs/study.md):
- the continuum (Q2) equals the analytic column to solver tolerance;
- the floor carries the bed's weight minus what the side walls carry (equilibrium);
- Bagi's stress summed over the grid balances the weight's moment about the floor:
  sum_cells V sigma_zz = -M g z_mean exactly at equilibrium when the side walls are
  frictionless (the floor's contacts have zero lever arm);
- DEM sigma_zz, averaged over each level of cells, grows in magnitude with depth;
- the continuum's sigma_zz is uniform across each level, its lateral ratio is K0;
- with frictionless side walls every continuum (elastic on rollers, the frictional FEM
  variants, Janssen) is the hydrostatic column, and none carries weight on its walls;
- the coarse-grained fields on the mesh satisfy the momentum balance to round-off, the bed's
  d(rho v)/dt is that of a bed at rest, and their stress is compared with the continuum's;
- the continua's material is where study.json says it came from: with the study's own
  calibration (Continuum/material from, tiny_study.prm), the values of calibration/material.prm,
  its paths beside it, K0 = nu / (1 - nu) of that nu, and the report's material section naming
  them; with the Continuum entries (tiny_study_lucy.prm), the entries' values;
- the side walls' shear against height (wall_shear.csv, study.json): a value per level for the DEM
  and every continuum, whose levels sum to what the walls carry (the DEM's from its wall
  contacts against its wall forces, each continuum's against its wall share);
- report, plots, tables and meshes are there, and no temporary file is left."""
import csv
import glob
import json
import os
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))  # before any chdir

folder = sys.argv[1]
os.chdir(folder)
s = json.load(open("study.json"), parse_constant=lambda c: sys.exit(f"study.json: {c} is not JSON"))
assert s["fem_relative_l2_error_stress"] < 1e-8, s["fem_relative_l2_error_stress"]
assert abs(s["fem_mean_lateral_ratio"] - s["k0"]) < 1e-8, (s["fem_mean_lateral_ratio"], s["k0"])

weight = s["weight_N"]
carried = -s["floor_force_z_N"] - s["side_wall_force_z_N"]
assert abs(carried - weight) <= 0.05 * weight, (carried, weight)
floor_share = -s["floor_force_z_N"] / weight

# Bagi's stress of the final (relaxed) state against the weight's moment.
last = sorted(glob.glob("grid_stress/*.h5"))[-1]
snap = sorted(glob.glob("snapshots/*.h5"))[-1]
with h5py.File(last, "r") as g, h5py.File(snap, "r") as p:
    assert g.attrs["step"] == p.attrs["step"], "grid stress and snapshot of different steps"
    bagi = g["/stress/bagi/tensor"][:].reshape(-1, 3, 3)
    volume = g["/grid"].attrs["cell_volume"]
    r = p["/particles/radius"][:]
    z = p["/particles/position"][:, 2]
mass = s["grain_mass_kg"] * r**3 / np.sum(r**3)
moment = -np.sum(mass * 9.81 * z)
total = volume * bagi[:, 2, 2].sum()
assert abs(total - moment) <= 1e-6 * abs(moment), (total, moment)

with open("profiles.csv") as f:
    prof = list(csv.DictReader(l for l in f if not l.startswith("#")))
centre = sorted((row for row in prof if row["column"] == "centre"), key=lambda row: float(row["z"]))
# Each level's mean sigma_zz carries the weight above it (single columns of a small bed
# may arch, so the invariant is on whole levels).
nx, ny, nz = s["grid_cells"]
level = bagi[:, 2, 2].reshape(nz, ny * nx).mean(axis=1)
szz = list(level)
assert all(a < b for a, b in zip(szz, szz[1:])), f"Bagi sigma_zz does not grow with depth: {szz}"
exact = [float(row["analytic_s_zz"]) for row in centre]
# tiny_study.prm's side walls are frictionless: then no continuum has a Janssen effect, and
# each (the frictional FEM variants, the Janssen line) is the hydrostatic column with the
# ratio K0: the floor's friction does not act on a column that settles straight down, and
# the at-rest state K0 = 0.43 lies inside the Drucker-Prager cone (phi = 30 degrees).
assert set(s["continua"]) == {"fem", "fem_elastic_friction", "fem_drucker_prager", "janssen"}, s["continua"].keys()
for key, continuum in s["continua"].items():
    assert abs(continuum["wall_share"]) < 1e-12, (key, continuum["wall_share"])
    assert abs(continuum["mean_lateral_ratio"] - s["k0"]) < 1e-8, (key, continuum["mean_lateral_ratio"])
    values = [float(row[key + "_s_zz"]) for row in centre]
    assert np.allclose(values, exact, rtol=1e-8, atol=1e-9 * abs(exact[0])), (key, values, exact)
for name, formula in s["formulas"].items():
    assert formula["closest_continuum"] in s["continua"], (name, formula["closest_continuum"])

# Coarse-grained fields (docs/coarse-graining.md), on by default.
cg = s["coarse_graining"]
assert cg["momentum_residual"] < 1e-12, cg
assert cg["momentum_rate"] < 1e-6, cg
assert cg["points"] > 1000 and 0.0 < cg["relative_l2_zz"] < 1.0, cg
assert abs(cg["width_m"] - 2 * 1.5e-3) < 1e-12, cg  # w = 1 d, monodisperse r = 1.5 mm
if cg["momentum_residual_by_differences"] is not None:
    # A bed at rest: the balance by differences over a few steps is as small as the bed's own
    # d(rho v)/dt (tiny_study_lucy.prm: Lucy's kernel, no cut-off jump).
    assert cg["momentum_residual_by_differences"] <= 10 * cg["momentum_rate"] + 1e-12, cg
for name in ("report.md", "comparison_cells.csv", "relative_l2.csv", "stress_summary.csv", "wall_shear.csv",
             "wall_shear.png", "profiles_szz.png",
             "lateral_ratio.png", "wall_share.png", "level_spread.png", "mesh/dem_fem.pvtu", "fem/column.pvtu",
             "fem_elastic_friction/column.pvtu", "fem_drucker_prager/column.pvtu", "mesh/cg_fields.pvtu"):
    assert os.path.exists(name), name
report = open("report.md").read()
shear = s["wall_shear_Pa"]
area = s["wall_shear_level_height_m"] * s["box_perimeter_m"]
assert len(shear["dem"]) == nz, shear
assert abs(sum(shear["dem"]) * area + s["side_wall_force_z_N"]) <= 1e-9 * weight, (shear["dem"], s["side_wall_force_z_N"])
for key, continuum in s["continua"].items():
    assert len(shear[key]) == nz, (key, shear[key])
    assert abs(sum(shear[key]) * area - continuum["wall_share"] * weight) <= 1e-8 * weight, (key, shear[key])
assert "## Wall shear stress (Pa) against height" in report
material = s["continuum_material"]
assert "## The continua's material" in report
nu = material["poisson_ratio"]
assert abs(s["k0"] - nu / (1 - nu)) < 1e-12, (s["k0"], nu)
expected_source = sys.argv[2] if len(sys.argv) > 2 else "calibration"
assert material["source"] == expected_source, (material["source"], expected_source)
if material["source"] == "calibration":
    for name in ("calibration/oedometer.csv", "calibration/triaxial.csv", "calibration/material.prm"):
        assert os.path.exists(name), name
    assert os.path.samefile(material["file"], "calibration/material.prm"), material["file"]
    written = {}
    for line in open("calibration/material.prm"):
        if line.strip().startswith("set "):
            key, value = line.strip()[4:].split("=")
            written[key.strip()] = float(value)
    for key, entry in (("youngs_modulus_Pa", "youngs modulus"), ("poisson_ratio", "poisson ratio"),
                       ("friction_angle_deg", "friction angle"), ("dilatancy_angle_deg", "dilatancy angle")):
        assert abs(material[key] - written[entry]) <= 1e-8 * abs(written[entry]), (key, material[key], written)
        assert abs(material[key] - material["calibration"][key]) <= 1e-12 * abs(material[key]), key
    assert 0 <= material["dilatancy_angle_deg"] <= material["friction_angle_deg"], material
    assert report.count("calibration of this bed") >= 4, "the report names the calibration as each value's source"
    print(f"continuum material from the bed's calibration: E {material['youngs_modulus_Pa']:.4g} Pa, nu {nu:.3f}, "
          f"phi {material['friction_angle_deg']:.2f} deg, psi {material['dilatancy_angle_deg']:.2f} deg")
else:
    assert not os.path.exists("calibration"), "a study with the Continuum entries measures nothing"
    assert report.count("Continuum entry") >= 4, "the report names the entries as each value's source"
for needle in ("Headline figures", "Timings", "profiles_szz.png", "bagi", "Closest to the DEM", "Janssen",
               "Coarse-grained fields on the mesh", f"coarse-grained field ({cg['kernel']}"):
    assert needle in report, needle
# tiny_study.prm enables the strain: the report has its section and plots.
sys.path.insert(0, HERE)
from check_strain_report import check_strain_report  # noqa: E402

strain_outputs = check_strain_report()
leftovers = [f for root, _, files in os.walk(".") for f in files if ".tmp" in f]
assert not leftovers, f"temporary files left: {leftovers}"
print(f"strain report ok: {strain_outputs} outputs")
print(f"coarse-grained fields ok: residual {cg['momentum_residual']:.2e} of rho g, ||d s_zz|| "
      f"{cg['relative_l2_zz']:.3f} over {cg['points']} points")
print(f"study ok: floor carries {100 * floor_share:.2f} % of the weight, sum V s_zz = {total:.6g} vs "
      f"-M g z_mean = {moment:.6g}, level means of s_zz {['%.4g' % v for v in szz]}")
