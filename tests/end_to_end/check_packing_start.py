#!/usr/bin/env python3
"""A run started from a packing (docs/input.md, "Starting from a packing").

usage: check_packing_start.py BENCH_DENSE_BED UPGRAIN WORK MPIEXEC...   (e.g. mpiexec -n 2)

1. `bench_dense_bed settle 300` writes a settled bed as a LAMMPS data file.
2. upgrain runs 5 ms from it (Particles/initial packing = the data file): the first snapshot
   holds the file's grains bit for bit (ids from 0 in the order of the file's ids), and the bed
   stays where it lay: no grain moves more than 2 % of its radius, the kinetic energy stays
   below 1e-6 of the potential energy measured from the floor.
3. upgrain runs again from the last snapshot of that run (HDF5): its first snapshot holds
   the same positions, velocities and angular velocities bit for bit.
4. The force network (Output/force network, docs/output.md): the last network file of step 2
   holds every contact once, normals from the lower id to the higher with r_a + r_b - d as the
   overlap, tangential forces normal to them, and its floor contacts carry what the snapshot's
   floor force says; on 2 ranks (MPIEXEC) the snapshots and network files hold the same values as
   on one.
"""
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

bench, upgrain, work = sys.argv[1:4]
mpiexec = sys.argv[4:]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
data = os.path.join(work, "bed.data")
subprocess.run([bench, "settle", "300", data], check=True, capture_output=True)

# The bed file: its box side and its atoms (id type diameter density x y z).
side = None
atoms = []
with open(data) as f:
    lines = f.read().splitlines()
for k, line in enumerate(lines):
    if line.endswith("xlo xhi"):
        side = float(line.split()[1])
    if line == "Atoms":
        atoms = [l.split() for l in lines[k + 2:] if l.strip()]
assert side and len(atoms) == 300, (side, len(atoms))
file_ids = np.array([int(a[0]) for a in atoms])
file_x = np.array([[float(v) for v in a[4:7]] for a in atoms])[np.argsort(file_ids, kind="stable")]
file_r = np.array([0.5 * float(a[2]) for a in atoms])[np.argsort(file_ids, kind="stable")]

# The benchmark's material (bench/dense_bed_scene.h) in the bed's box.
scene = f"""# written by check_packing_start.py
subsection Particles
  set initial packing = bed.data
  set youngs modulus = 29e9
  set poisson ratio = 0.25
end
subsection Container
  set length x = {side!r}
  set length y = {side!r}
end
subsection Simulation
  set time step = 2e-7
  set end time = 0.005
  set stop at rest ratio = 0
end
subsection Output
  set snapshot interval = 0.0025
  set time series interval = 0.0005
  set force network = true
end
subsection Study
  set compare with continuum = false
  set relax at end = false
end
"""
prm = os.path.join(work, "from_data.prm")
with open(prm, "w") as f:
    f.write(scene)


def run(prm_file, out, launcher=()):
    r = subprocess.run(list(launcher) + [upgrain, prm_file, "--output", out], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"upgrain failed on {prm_file}:\n{r.stdout}\n{r.stderr}")
    return r.stdout


def snapshots(out):
    names = sorted(os.listdir(os.path.join(out, "snapshots")), key=lambda n: int(n.split("_")[1][:-3]))
    return [os.path.join(out, "snapshots", n) for n in names]


out1 = os.path.join(work, "from_data")
log = run(prm, out1)
assert "initial packing: " in log and "LAMMPS data file (atom_style sphere), 300 grains" in log, log
snaps = snapshots(out1)
with h5py.File(snaps[0]) as first, h5py.File(snaps[-1]) as last:
    assert list(first["particles/id"][:]) == list(range(300))
    assert np.array_equal(first["particles/position"][:], file_x), "first snapshot is not the file's bed"
    assert np.array_equal(first["particles/radius"][:], file_r)
    moved = np.linalg.norm(last["particles/position"][:] - file_x, axis=1) / file_r
    end_state = {k: last["particles/" + k][:] for k in ("position", "velocity", "angular_velocity")}
assert moved.max() < 0.02, f"a grain moved {moved.max():.3g} radii: the bed did not stay where it lay"
with open(os.path.join(out1, "summary.json")) as f:
    summary = json.load(f)
assert summary["particles"] == 300, summary
series = np.genfromtxt(os.path.join(out1, "time_series.csv"), delimiter=",", names=True, skip_header=1)
kinetic = series["kinetic_translational"] + series["kinetic_rotational"]
potential = 2650 * 9.81 * np.sum(4 / 3 * np.pi * file_r**3 * file_x[:, 2])
assert kinetic.max() < 1e-6 * potential, f"kinetic energy {kinetic.max():.3g} J of {potential:.3g} J"

# Again from the last snapshot of that run.
shutil.copy(snaps[-1], os.path.join(work, "last.h5"))
prm2 = os.path.join(work, "from_snapshot.prm")
with open(prm2, "w") as f:
    f.write(scene.replace("bed.data", "last.h5"))
out2 = os.path.join(work, "from_snapshot")
log = run(prm2, out2)
assert "Upgrain snapshot, 300 grains" in log, log
with h5py.File(snapshots(out2)[0]) as first:
    for k, v in end_state.items():
        assert np.array_equal(first["particles/" + k][:], v), f"{k} of the snapshot not read back bit for bit"
# The force network of the last snapshot (step 2's run starts from the end of step 1's).
nets = sorted(os.listdir(os.path.join(out1, "force_network")))
assert len(nets) == len(snaps) - 1, (nets, snaps)  # every snapshot after the first
with h5py.File(os.path.join(out1, "force_network", nets[-1])) as net, h5py.File(snaps[-1]) as last:
    x = net["particles/position"][:]
    assert np.array_equal(x, last["particles/position"][:])
    ids = net["contacts/ids"][:]
    n = net["contacts/normal"][:]
    fn = net["contacts/normal_force"][:]
    ft = net["contacts/tangential_force"][:]
    a, b = ids[:, 0], ids[:, 1]
    assert len(ids) > 300 and np.all(a < b), "pairs once each, lower id first"
    assert len({(i, j) for i, j in ids}) == len(ids)
    d = x[b] - x[a]
    dist = np.linalg.norm(d, axis=1)
    assert np.allclose(n, d / dist[:, None], rtol=0, atol=1e-12), "normals from a to b"
    assert np.allclose(net["contacts/overlap"][:], file_r[a] + file_r[b] - dist, rtol=0, atol=1e-15)
    assert np.all(np.abs(np.sum(ft * n, axis=1)) <= 1e-9 * np.linalg.norm(fn, axis=1) + 1e-300)
    assert np.all(np.sum(fn * n, axis=1) < 0), "the force on a pushes it away from b"
    # The floor (wall 0): the sum of its contacts' forces is the snapshot's floor force.
    wall = net["wall_contacts/wall"][:]
    on_floor = -(net["wall_contacts/normal_force"][:] + net["wall_contacts/tangential_force"][:])[wall == 0]
    floor = last["walls/force"][0]
    assert np.allclose(on_floor.sum(axis=0), floor, rtol=1e-9, atol=1e-12), (on_floor.sum(axis=0), floor)
    pairs = len(ids)

# force_network.xdmf: every data item names a dataset of its stated shape.
for item in ET.parse(os.path.join(out1, "force_network.xdmf")).iter("DataItem"):
    name, path = item.text.split(":")
    with h5py.File(os.path.join(out1, name)) as h:
        assert list(h[path].shape) == [int(v) for v in item.get("Dimensions").split()], (name, path)

# On two ranks: the same values in every snapshot and network file.
if mpiexec:
    out2r = os.path.join(work, "from_data_2_ranks")
    run(prm, out2r, mpiexec)
    for sub in ("snapshots", "force_network"):
        names = sorted(os.listdir(os.path.join(out1, sub)))
        assert names == sorted(os.listdir(os.path.join(out2r, sub))), sub
        for name in names:
            with h5py.File(os.path.join(out1, sub, name)) as one, h5py.File(os.path.join(out2r, sub, name)) as two:
                def same(path, obj):
                    if isinstance(obj, h5py.Dataset):
                        assert np.array_equal(obj[:], two[path][:]), f"{sub}/{name}:{path} differs on 2 ranks"
                one.visititems(same)

print(f"from a settled bed of 300: largest displacement {moved.max():.3g} radii in 5 ms, "
      f"largest kinetic energy {kinetic.max() / potential:.3g} of the potential; snapshot read back bitwise; {pairs} pairs in the force network"
      f"{', the same on 2 ranks' if mpiexec else ''}")
