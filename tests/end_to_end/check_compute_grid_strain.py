#!/usr/bin/env python3
"""Checks the strain per compute grid of an MPI run against a recomputation from the snapshots.

Usage: check_compute_grid_strain.py FOLDER RANKS PARTICLES

At every evaluation (compute_grid_strain/*.h5 and compute_grid_strain.csv):
- one block per rank, every particle of a Lagrangian set in exactly one block (the sets come
  with the file: /sets/id, /sets/block), the block counts equal /blocks/particles;
- where a snapshot of the same step exists, the best-fit F and L of every valid block, taken
  again here with numpy (least squares on centred positions from the t0 and current
  snapshots, matched by id), equal the file's to 1e-10 of their scale (for L: the larger of
  |L| and the velocities over the set's extent);
- the tessellation's F of a valid block has J = det F > 0 and ln J = log J;
- invalid blocks are all zero, nothing is NaN, and the CSV holds the files' F, L and reasons.
"""
import csv
import glob
import os
import sys

import h5py
import numpy as np

folder, ranks, particles = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
files = sorted(glob.glob(os.path.join(folder, 'compute_grid_strain', 'compute_grid_strain_*.h5')))
assert files, 'no compute_grid_strain files'
rows = [r for r in csv.DictReader(l for l in open(os.path.join(folder, 'compute_grid_strain.csv'))
                                  if not l.startswith('#'))]


def snapshot(step):
    path = os.path.join(folder, 'snapshots', f'particles_{step:09d}.h5')
    if not os.path.exists(path):
        return None
    with h5py.File(path, 'r') as f:
        p = f['particles']
        return {int(i): (x, v) for i, x, v in zip(p['id'][()], p['position'][()], p['velocity'][()])}


def best_fit(a, b):
    """G with b - mean(b) ~ G (a - mean(a)) in least squares."""
    da, db = a - a.mean(axis=0), b - b.mean(axis=0)
    g, *_ = np.linalg.lstsq(da, db, rcond=None)
    return g.T


compared = 0
reference = None
for path in files:
    with h5py.File(path, 'r') as f:
        step, set_kind = int(f.attrs['step']), f.attrs['set'].decode()
        ref_step = int(f.attrs['reference_step'])
        ids, member = f['sets/id'][()], f['sets/block'][()]
        counts = f['blocks/particles'][()]
        assert len(counts) == ranks, f'{path}: {len(counts)} blocks for {ranks} ranks'
        assert np.all(np.diff(ids) > 0), f'{path}: set ids not ascending'
        assert np.array_equal(np.bincount(member[member >= 0], minlength=ranks), counts), path
        if set_kind == 'lagrangian':
            assert counts.sum() == particles, f'{path}: {counts.sum()} of {particles} particles in the sets'
        fields = {d: {k: f[d][k][()] for k in f[d]} for d in ('best_fit', 'tessellation') if d in f}
    for d, g in fields.items():
        for k, v in g.items():
            assert np.all(np.isfinite(v)), f'{path}: {d}/{k} not finite'
        bad = g['F_valid'] == 0
        assert np.all(g['F'][bad] == 0) and np.all(g['J'][bad] == 0), f'{path}: {d} invalid blocks not zero'
        good = ~bad
        assert np.all(g['J'][good] > 0), path
        assert np.allclose(g['ln_J'][good], np.log(g['J'][good]), rtol=0, atol=1e-12), path
        csv_rows = [r for r in rows if int(r['step']) == step and r['definition'] == d]
        assert len(csv_rows) == ranks, f'step {step} {d}: {len(csv_rows)} CSV rows'
        for r in csv_rows:
            b = int(r['block'])
            assert int(r['particles']) == counts[b] and int(r['F_reason']) == g['F_reason'][b], (step, d, b)
            for k, name in enumerate(f'{i}{j}' for i in 'xyz' for j in 'xyz'):
                assert float(r['F_' + name]) == g['F'][b, k] and float(r['L_' + name]) == g['L'][b, k], \
                    (step, d, b, name)
    if reference is None or reference[0] != ref_step:
        reference = (ref_step, snapshot(ref_step))
    now = snapshot(step)
    if reference[1] is None or now is None:
        continue
    g = fields['best_fit']
    for b in range(ranks):
        if g['F_valid'][b] == 0:
            continue
        set_ids = ids[member == b]
        X = np.array([reference[1][int(i)][0] for i in set_ids])
        x = np.array([now[int(i)][0] for i in set_ids])
        v = np.array([now[int(i)][1] for i in set_ids])
        F, L = best_fit(X, x), best_fit(x, v)
        assert np.abs(F - g['F'][b].reshape(3, 3)).max() <= 1e-10 * np.abs(F).max(), (step, b, F, g['F'][b])
        if g['L_valid'][b]:
            # L's scale: the velocities over the set's extent (a falling set has L = 0 to round-off)
            scale = max(np.abs(L).max(), np.abs(v).max() / np.ptp(x, axis=0).max())
            assert np.abs(L - g['L'][b].reshape(3, 3)).max() <= 1e-10 * scale, (step, b, L, g['L'][b])
        compared += 1
assert compared > 0, 'no evaluation with both snapshots to compare'
print(f'compute-grid strain ok: {len(files)} evaluations, {ranks} blocks, best fit recomputed for '
      f'{compared} blocks')
