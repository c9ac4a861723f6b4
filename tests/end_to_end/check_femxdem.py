#!/usr/bin/python3
"""Runs the FEM x DEM study (docs/femxdem.md) of a scene on 1 and 2 ranks and checks:
- the files: load_displacement.csv, points.csv, femxdem-NNNN.pvtu of every step with its pieces
  (one per rank), femxdem.pvd listing them, load_displacement.png, points.png, summary.json;
- the load-displacement path: step 0 at zero strain, then the axial strain k eps / N; the platen's
  sigma_1 at step 0 within 5 % of the confining pressure (the DEM cell is prepared within 2 % of
  it on every axis, and the step balances the specimen), growing at every step (the specimen is
  compressed well before its peak), no step cut, and q = sigma_1 - sigma_3;
- points.csv: one row per Gauss point (4 per Q1 element) at the last step, each cell's mean
  stress compressive and finite, its measures physical (solid fraction in (0.5, 0.75), a
  coordination above 2, q/p = q / p, a relaxed cell); point_history.csv: the same columns for every
  step, its last step's rows those of points.csv, step 0's solid fractions within 1 % of each
  other (one prepared cell copied, strained by step 0's balance only);
- summary.json: the Gauss points, grains per cell and Newton iterations of the tables;
- the log: the checkpoints' schedule (after converged load steps; none in so short a run); not the
  scene's particle count and effects, but the DEM cell's effects (no gravity, walls or energy);
- the ranks' balance: every step's imbalance at least 1 (exactly 1 on one rank, where nothing is
  repartitioned), summary.json's repartitions and its cost-weighted imbalance those of the table;
- 1 and 2 ranks give the same path and points to 1e-6: not bitwise, since the matrix entries of
  the nodes two ranks share are summed in another order (docs/femxdem.md), and a DEM cell
  answers a displacement gradient that differs in its last bits with stresses that differ a
  little more (measured: the same 9 digits on this scene).

Usage: check_femxdem.py UPGRAIN SCENE WORK [MPIEXEC]
"""
import json
import math
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from femxdem_run import run_femxdem, table  # noqa: E402

upgrain, scene, work = sys.argv[1:4]
mpiexec = sys.argv[4] if len(sys.argv) > 4 else 'mpiexec'
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)


folders = {}
for ranks in (1, 2):
    out = os.path.join(work, f'ranks_{ranks}')
    stdout = run_femxdem(upgrain, scene, out, ranks, mpiexec)
    # Its checkpoints come after converged load steps, by the wall clock or when it is asked to
    # stop (check_femxdem_restart.py); this run is shorter than the scene's interval: none.
    assert 'checkpoints: every 600 s of wall clock and when asked to stop, after a converged load step, ' \
        'the last 2 kept' in stdout, stdout
    kept = os.path.join(out, 'checkpoints')
    assert not os.path.isdir(kept) or not os.listdir(kept), os.listdir(kept)
    # Nor the scene's deposition: the cells' effects instead, without gravity, walls or energy.
    assert "the scene's particle count, end time and effects are not used" in stdout, stdout
    assert 'effects (Effects section' not in stdout, stdout
    cell = next(l for l in stdout.splitlines() if 'femxdem: the DEM cell:' in l)
    assert 'effects: tangential friction, damping, rotation' in cell, cell
    for off in ('gravity', 'wall friction', 'energy tracking'):
        assert off not in cell, cell
    folders[ranks] = os.path.join(out, 'femxdem')

steps = 4
eps, confining = 0.004, 1e5
for ranks, folder in folders.items():
    rows = table(os.path.join(folder, 'load_displacement.csv'))
    assert len(rows) == steps + 1, len(rows)
    for k, row in enumerate(rows):
        assert int(row['step']) == k
        assert abs(float(row['axial_strain']) - k * eps / steps) < 1e-12, row
        assert int(row['cuts']) == 0, row
        assert int(row['newton_iterations']) >= 1, row
        assert abs(float(row['q']) - (float(row['sigma_1']) - float(row['sigma_3']))) < 1e-6 * confining, row
    s1 = [float(r['sigma_1']) for r in rows]
    assert abs(s1[0] / confining - 1) < 0.05, s1[0]
    assert all(b > a for a, b in zip(s1, s1[1:])), s1
    pvd = open(os.path.join(folder, 'femxdem.pvd')).read()
    for k in range(steps + 1):
        name = f'femxdem-{k:04d}'
        assert f'file="{name}.pvtu"' in pvd, name
        assert os.path.exists(os.path.join(folder, name + '.pvtu')), name
        for r in range(ranks):
            assert os.path.exists(os.path.join(folder, f'{name}.proc{r:04d}.vtu')), (name, r)
    for png in ('load_displacement.png', 'points.png'):
        assert os.path.exists(os.path.join(folder, png)), png
    points = table(os.path.join(folder, 'points.csv'))
    assert len(points) == 2 * 4, len(points)
    for p in points:
        assert math.isfinite(float(p['p'])) and float(p['p']) > 0, p
        assert 0.5 < float(p['solid_fraction']) < 0.75, p
        assert float(p['coordination']) > 2, p
        assert abs(float(p['q_over_p']) - float(p['q']) / float(p['p'])) < 1e-8, p
        assert float(p['unbalanced_force']) <= 1e-4, p
    history = table(os.path.join(folder, 'point_history.csv'))
    assert len(history) == (steps + 1) * len(points), len(history)
    assert history[-len(points):] == points
    phi0 = [float(h['solid_fraction']) for h in history if h['step'] == '0']
    assert max(phi0) < 1.01 * min(phi0), phi0
    assert all(math.isfinite(float(h['grain_rotation'])) for h in history)
    summary = json.load(open(os.path.join(folder, '..', 'summary.json')))
    assert summary['gauss_points'] == len(points) and summary['ranks'] == ranks
    assert summary['grains_per_cell'] == 60
    assert summary['newton_iterations'] == sum(int(r['newton_iterations']) for r in rows)
    assert summary['line_search_halvings'] == sum(int(r['halvings']) for r in rows)
    # The ranks' balance: 1 on one rank; on two, each rank's share of every step's grain-steps
    # at least the mean, and the run's busiest share the steps' weighted by their grain-steps.
    imbalance = [float(r['imbalance']) for r in rows]
    cost = [float(r['grain_steps']) for r in rows]
    assert all(x >= 1 - 1e-12 for x in imbalance), imbalance
    if ranks == 1:
        assert imbalance == [1.0] * len(rows) and all(r['repartitioned'] == '0' for r in rows), rows
    assert summary['repartitions'] == sum(int(r['repartitioned']) for r in rows)
    weighted = sum(x * c for x, c in zip(imbalance, cost)) / sum(cost)
    assert abs(summary['imbalance'] - weighted) < 1e-6 * weighted, (summary['imbalance'], weighted)

a = table(os.path.join(folders[1], 'load_displacement.csv'))
b = table(os.path.join(folders[2], 'load_displacement.csv'))
for x, y in zip(a, b):
    assert abs(float(x['sigma_1']) - float(y['sigma_1'])) <= 1e-6 * float(x['sigma_1']), (x, y)
pa = table(os.path.join(folders[1], 'points.csv'))
pb = table(os.path.join(folders[2], 'points.csv'))
for x, y in zip(pa, pb):
    assert (x['cell'], x['point']) == (y['cell'], y['point'])
    for c in ('sigma_xx', 'sigma_yy', 'sigma_xy'):
        assert abs(float(x[c]) - float(y[c])) <= 1e-6 * confining, (c, x, y)
print(f'femxdem: {steps} load steps, sigma_1 {s1[0]:.6g} -> {s1[-1]:.6g} Pa on 1 and 2 ranks')
