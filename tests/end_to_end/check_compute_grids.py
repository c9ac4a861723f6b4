#!/usr/bin/env python3
"""Checks compute_grid_stress.csv of an MPI run against its fixed-grid stress.

Usage: check_compute_grids.py FOLDER RANKS PARTICLES

At every evaluation: one block per rank, every grain in exactly one block, and for Bagi
(a sum over grains, valid in any state) sum_b V_b sigma_b equals sum_c V_c sigma_c of the
fixed grid to 1e-9 of its largest entry, when the fixed grid holds every grain.
"""
import csv
import glob
import os
import sys

import h5py
import numpy as np

folder, ranks, particles = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
rows = [r for r in csv.DictReader(l for l in open(os.path.join(folder, 'compute_grid_stress.csv'))
                                  if not l.startswith('#'))]
steps = sorted({int(r['step']) for r in rows})
checked = 0
for step in steps:
    bagi = [r for r in rows if int(r['step']) == step and r['formula'] == 'bagi']
    assert len(bagi) == ranks, f'step {step}: {len(bagi)} blocks for {ranks} ranks'
    assert sum(int(r['particles']) for r in bagi) == particles, f'step {step}: grains not counted once'
    blocks = sum(float(r['volume']) * np.array([float(r['s_' + a + b]) for a in 'xyz' for b in 'xyz'])
                 for r in bagi)
    h5 = os.path.join(folder, 'grid_stress', f'grid_stress_{step:09d}.h5')
    f = h5py.File(h5, 'r')
    if int(f['cells/particles'][()].sum()) != particles:
        continue  # grains outside the fixed grid: the sums cover different grains
    cells = f['grid'].attrs['cell_volume'] * f['stress/bagi/tensor'][()].sum(axis=0)
    scale = max(np.abs(cells).max(), 1e-300)
    assert np.abs(blocks - cells).max() <= 1e-9 * scale, \
        f'step {step}: sum V_b sigma_b {blocks} vs sum V_c sigma_c {cells}'
    checked += 1
assert checked > 0, 'no evaluation with every grain inside the fixed grid'
print(f'compute grids ok: {len(steps)} evaluations, {ranks} blocks each, Bagi sums equal the fixed '
      f'grid\'s at {checked} of them')
