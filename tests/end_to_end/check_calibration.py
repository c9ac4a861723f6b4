#!/usr/bin/python3
"""Runs the calibration study (docs/calibration.md) of a scene on 1 and 2 ranks and checks:
- oedometer.csv and material.prm are the same bytes on both rank counts;
- the path: state 0 unloaded, then one state per target; the lid's stress grows from state to
  state and ends within 50 % of the last target (the servo converges over the compliance of
  this loose tiny bed, not within one hold: measured 575 Pa for 735 Pa), and the strain grows; K0 and nu = K0 / (1 + K0) in the columns agree; the M, nu and E columns satisfy
  E = M (1 + nu)(1 - 2 nu) / (1 - nu);
- material.prm holds a Continuum section whose E and nu are those of summary.json, and which the
  driver reads as a scene file (upgrain --check); a scene naming it as Continuum/material file
  takes its E (the driver says so), and one naming a missing file is refused.

Usage: check_calibration.py UPGRAIN SCENE WORK [MPIEXEC]
"""
import csv
import json
import os
import shutil
import subprocess
import sys

upgrain, scene, work = sys.argv[1:4]
mpiexec = sys.argv[4] if len(sys.argv) > 4 else 'mpiexec'
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
folders = {}
for ranks in (1, 2):
    out = os.path.join(work, f'ranks_{ranks}')
    cmd = [upgrain, '--study', 'calibration', '--output', out, scene]
    if ranks > 1:
        cmd = [mpiexec, '-n', str(ranks)] + cmd
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f'{ranks} rank(s): exit {r.returncode}\n{r.stdout}\n{r.stderr}')
    folders[ranks] = os.path.join(out, 'calibration')
for name in ('oedometer.csv', 'material.prm'):
    a = open(os.path.join(folders[1], name), 'rb').read()
    b = open(os.path.join(folders[2], name), 'rb').read()
    assert a == b, f'{name} differs between 1 and 2 ranks'

rows = list(csv.DictReader(l for l in open(os.path.join(folders[1], 'oedometer.csv')) if not l.startswith('#')))
assert len(rows) == 5, len(rows)
assert float(rows[0]['target']) == 0 and float(rows[0]['vertical_strain']) == 0
strain = [float(r['vertical_strain']) for r in rows]
assert all(b > a for a, b in zip(strain, strain[1:])), strain
held = [r for r in rows if r['held'] == '1']
assert len(held) >= 2, 'fewer than two held states: no modulus'
for r in rows:
    t, s = float(r['target']), float(r['lid_stress'])
    assert (r['held'] == '1') == (t > 0 and abs(s - t) <= 0.05 * t), r
lid = [float(r['lid_stress']) for r in rows[1:]]
assert all(b > a for a, b in zip(lid, lid[1:])), lid
assert abs(lid[-1] - float(rows[-1]['target'])) < 0.5 * float(rows[-1]['target']), (lid, rows[-1]['target'])
for r in rows:
    k0 = float(r['sigma_h']) / float(r['sigma_v'])
    assert abs(k0 - float(r['K0'])) < 1e-8 * abs(k0), r
for r in rows[2:]:
    m, nu, e = float(r['M']), float(r['nu']), float(r['E'])
    assert abs(nu - float(r['K0']) / (1 + float(r['K0']))) < 1e-8, r
    assert abs(e - m * (1 + nu) * (1 - 2 * nu) / (1 - nu)) < 1e-7 * abs(e), r

summary = json.load(open(os.path.join(work, 'ranks_1', 'summary.json')))
material = open(os.path.join(folders[1], 'material.prm')).read()
values = {}
for line in material.splitlines():
    if line.strip().startswith('set '):
        key, value = line.strip()[4:].split('=')
        values[key.strip()] = float(value)
assert abs(values['youngs modulus'] - summary['youngs_modulus_Pa']) < 1e-8 * summary['youngs_modulus_Pa']
assert abs(values['poisson ratio'] - summary['poisson_ratio']) < 1e-8
r = subprocess.run([upgrain, '--check', os.path.abspath(os.path.join(folders[1], 'material.prm'))],
                   capture_output=True, text=True, cwd=work)
assert r.returncode == 0, r.stderr
# A study's scene takes E and nu from the material file (Continuum/material file, a path
# relative to the scene file's folder), and names the file; a missing file is refused.
scene_with_material = os.path.join(work, 'study_with_material.prm')
with open(scene_with_material, 'w') as f:
    f.write('subsection Continuum\n  set material file = ranks_1/calibration/material.prm\nend\n')
r = subprocess.run([upgrain, '--check', scene_with_material], capture_output=True, text=True, cwd=work)
assert r.returncode == 0, r.stderr
line = [l for l in r.stdout.splitlines() if 'continuum material:' in l]
assert line and 'material.prm' in line[0], r.stdout
e_read = float(line[0].split('E ')[1].split(' Pa')[0])
assert e_read == values['youngs modulus'], (e_read, values)
with open(scene_with_material, 'w') as f:
    f.write('subsection Continuum\n  set material file = no_such_material.prm\nend\n')
r = subprocess.run([upgrain, '--check', scene_with_material], capture_output=True, text=True, cwd=work)
assert r.returncode != 0 and 'Continuum/material file' in r.stderr and 'no_such_material.prm' in r.stderr, r.stderr
print(f"calibration: E {summary['youngs_modulus_Pa']:.4g} Pa, nu {summary['poisson_ratio']:.3f}, "
      f"wall time {summary['deposition_wall_time_s']:.1f} + {summary['oedometer_wall_time_s']:.1f} s")
