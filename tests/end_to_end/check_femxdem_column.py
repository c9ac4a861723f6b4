#!/usr/bin/python3
"""Runs the FEM x DEM column under its own weight (docs/femxdem.md, "The column under its own
weight") on 1 and 2 ranks and checks:
- the files: column.csv, point_history.csv, points.csv, column.png, points.png, summary.json;
- the DEM cell prepared at the confining pressure although its servo would hunt there: the log's
  cell pressure within 2 % of it;
- step 0 applies nothing: every point at the prepared stress; the 4 load steps converged;
- equilibrium: each element's mean sigma_yy (Q1 on rollers: the stress is constant along y in an
  element) within 2 % of the weight's at the element's mid-depth, -(top + rho g depth), where the
  top pressure is the prepared cell's sigma_yy and rho g = rho_s phi_0 g from the cells' own solid
  fraction at step 0;
- K0 = sigma_xx / sigma_yy of every level between 0.3 and 1.2 and falling with depth from the
  isotropic start (the weight's increments are carried more vertically);
- summary.json: loading, the deepest level's sigma_yy and K0 those of column.csv;
- 1 and 2 ranks give the same stresses to 1e-6 (docs/femxdem.md: not bitwise).

Usage: check_femxdem_column.py UPGRAIN SCENE WORK [MPIEXEC]
"""
import json
import os
import re
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from femxdem_run import run_femxdem, table  # noqa: E402

upgrain, scene, work = sys.argv[1:4]
mpiexec = sys.argv[4] if len(sys.argv) > 4 else 'mpiexec'
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)

top, steps, height, density, gravity = 1000.0, 4, 0.1, 2650.0, 9.81


columns = {}
for ranks in (1, 2):
    out = os.path.join(work, f'ranks_{ranks}')
    stdout = run_femxdem(upgrain, scene, out, ranks, mpiexec)
    cell = next(l for l in stdout.splitlines() if 'femxdem: the DEM cell:' in l)
    p = float(re.search(r' p ([0-9.e+-]+) Pa', cell).group(1))
    assert abs(p / top - 1) < 0.02, cell
    folder = os.path.join(out, 'femxdem')
    for name in ('column.csv', 'points.csv', 'point_history.csv', 'column.png', 'points.png'):
        assert os.path.exists(os.path.join(folder, name)), name
    assert not os.path.exists(os.path.join(folder, 'load_displacement.csv'))
    history = table(os.path.join(folder, 'point_history.csv'))
    start = [h for h in history if h['step'] == '0']
    assert len(start) == 8, len(start)
    sigma_yy0 = float(start[0]['sigma_yy'])
    for h in start:
        assert abs(float(h['sigma_yy']) - sigma_yy0) < 1e-9 * top, h
    phi0 = float(start[0]['solid_fraction'])
    assert {h['step'] for h in history} == {str(k) for k in range(steps + 1)}
    rows = table(os.path.join(folder, 'column.csv'))
    assert len(rows) == 4 and all(int(row['points']) == 2 for row in rows), rows
    unit_weight = density * phi0 * gravity
    for row in rows:
        expected = -(-sigma_yy0 + unit_weight * float(row['depth']))
        assert abs(float(row['weight_sigma_yy']) - expected) < 0.01 * abs(expected), (row, expected)
    for element in (rows[0:2], rows[2:4]):
        mean = sum(float(row['sigma_yy']) for row in element) / 2
        mid = sum(float(row['depth']) for row in element) / 2
        weight = -(-sigma_yy0 + unit_weight * mid)
        assert abs(mean / weight - 1) < 0.02, (mean, weight, element)
    k0 = [float(row['K0']) for row in rows]
    assert all(0.3 < k < 1.2 for k in k0), k0
    assert k0[-1] < k0[0], k0
    summary = json.load(open(os.path.join(out, 'summary.json')))
    assert summary['loading'] == 'gravity column' and summary['load_steps'] == steps, summary
    assert abs(summary['deepest_K0'] - k0[-1]) < 1e-6, (summary, k0)
    assert abs(summary['deepest_sigma_yy_Pa'] - float(rows[-1]['sigma_yy'])) < 1e-6 * top, summary
    columns[ranks] = rows

for a, b in zip(columns[1], columns[2]):
    for c in ('sigma_xx', 'sigma_yy'):
        assert abs(float(a[c]) - float(b[c])) <= 1e-6 * top, (c, a, b)
print('femxdem column: K0 ' + ', '.join(f'{float(r["K0"]):.3f}' for r in columns[1]) +
      f' from the top; deepest sigma_yy {float(columns[1][-1]["sigma_yy"]):.6g} Pa on 1 and 2 ranks')
