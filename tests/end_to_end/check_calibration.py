#!/usr/bin/python3
"""Runs the calibration study (docs/calibration.md) of a scene on 1 and 2 ranks and checks:
- oedometer.csv, triaxial.csv and material.prm are the same bytes on both rank counts;
- the oedometric path, by whichever loading the scene sets (in a periodic cell: below): state 0 the bed under its own weight
  (by lid: before the lid touches it), then one state per gravity factor or lid target, the strain
  growing. By gravity: sigma_v = f W/(2A) of state 0's
  W/(2A) (the bed's mean vertical stress of summary.json), the strain 3/4 of the centre of mass's
  descent over its height. By lid: the at_rest column is the lid within 5 % of its target, the
  lid's stress grows from state to state and ends within 50 % of the last target (the servo
  converges over the compliance of this loose tiny bed, not within one hold: measured 575 Pa for
  735 Pa). In a periodic cell (Calibration/tests in): state 0 the deposited bed, then one state
  per target of the cell's servo, each held within 5 %, the strain that of the cell's height, no
  lid or wall columns. All: K0 and nu = K0 / (1 + K0) in the columns agree; M is the secant of the step from
  the state before, and E = M (1 + nu)(1 - 2 nu) / (1 - nu);
- material.prm holds a Continuum section whose E and nu are those of summary.json, and which the
  driver reads as a scene file (upgrain --check); a scene naming it as Continuum/material file
  takes its E (the driver says so), and one naming a missing file is refused;
- the friction-angle test's path (triaxial.csv): 101 records, the axial strain growing from 0
  to the final strain, the columns consistent (sigma_1, sigma_3 and phi from the Bagi stress,
  eps_v from the box), the servo side walls holding sigma_3 on average to 10 %; the peak or
  critical-state phi and psi in material.prm and summary.json agree, psi in [0, phi], Jaky's K0
  is 1 - sin phi_cs; a scene naming the material file takes its phi (the driver names the
  file), and a material file without phi leaves the scene's own (named as a Continuum entry).

Usage: check_calibration.py UPGRAIN SCENE WORK [MPIEXEC]
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys

from study_run import run_study

upgrain, scene, work = sys.argv[1:4]
mpiexec = sys.argv[4] if len(sys.argv) > 4 else 'mpiexec'
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
folders = {}
for ranks in (1, 2):
    out = os.path.join(work, f'ranks_{ranks}')
    run_study(upgrain, 'calibration', scene, out, ranks, mpiexec)
    folders[ranks] = os.path.join(out, 'calibration')
for name in ('oedometer.csv', 'triaxial.csv', 'material.prm'):
    a = open(os.path.join(folders[1], name), 'rb').read()
    b = open(os.path.join(folders[2], name), 'rb').read()
    assert a == b, f'{name} differs between 1 and 2 ranks'

rows = list(csv.DictReader(l for l in open(os.path.join(folders[1], 'oedometer.csv')) if not l.startswith('#')))
summary = json.load(open(os.path.join(work, 'ranks_1', 'summary.json')))
strain = [float(r['vertical_strain']) for r in rows]
assert strain[0] == 0 and all(b > a for a, b in zip(strain, strain[1:])), strain
at_rest = [r for r in rows[1:] if r['at_rest'] == '1']
assert len(at_rest) >= 1, 'no loaded state at rest: no modulus'
if 'gravity_factor' in rows[0]:
    # By gravity: state 0 the bed under its weight, then one state per factor; sigma_v = f W / (2 A)
    # by equilibrium, the mean strain 3/4 of the centre of mass's descent over its height.
    assert summary['oedometer_loading'] == 'gravity'
    factors = [float(r['gravity_factor']) for r in rows]
    assert factors[0] == 1 and all(b > a for a, b in zip(factors, factors[1:])), factors
    z0 = float(rows[0]['centroid'])
    half_weight = 0.5 * summary['weight_stress_Pa']  # W/(2A)
    assert abs(float(rows[0]['sigma_v']) - summary['bed_mean_vertical_stress_Pa']) < 1e-8 * half_weight
    for r in rows:
        # sigma_v = f W/(2A) less the side walls' share: their lift's moment over zc, at most
        # about 2.5 times the lift in size (their contacts lie below the top, about 2 zc); exactly
        # f W/(2A) without walls' friction. oedometer.csv has 9 significant digits: the centres of
        # mass to 1e-11 m of 7e-3 m.
        share, f = float(r['side_wall_share']), float(r['gravity_factor'])
        assert abs(share) < 1, r  # < 0: walls that hold grains down (measured -2.4 % on this bed at 1 g)
        if share == 0:
            assert abs(float(r['sigma_v']) - f * half_weight) < 2e-8 * f * half_weight, r
        else:
            assert abs(float(r['sigma_v']) - f * half_weight) < 2.5 * abs(share) * f * half_weight, (r, half_weight)
        assert abs(float(r['vertical_strain']) - 0.75 * (z0 - float(r['centroid'])) / z0) < 3e-9, r
    # tiny_calibration_gravity.prm gives the side walls friction: they carry part of the weight.
    assert max(abs(float(r['side_wall_share'])) for r in rows) > 0.01, rows
    first_step = 1
elif summary['oedometer_loading'] == 'periodic cell':
    # In the periodic cell: state 0 the deposited bed (its mean Bagi stress under its weight, the
    # cell's height its highest point), then one state per target of the cell's servo along z;
    # at_rest is sigma_v within 5 % of the target; no lid. The cell only shortens along z.
    assert len(rows) == 5, len(rows)
    assert float(rows[0]['target']) == 0 and rows[0]['at_rest'] == '0'
    assert abs(float(rows[0]['sigma_v']) - summary['bed_mean_vertical_stress_Pa']) < 1e-8 * summary['bed_mean_vertical_stress_Pa']
    assert all(r['lid_stress'] == '' for r in rows), rows
    for r in rows[1:]:
        t, s = float(r['target']), float(r['sigma_v'])
        assert (r['at_rest'] == '1') == (abs(s - t) <= 0.05 * t), r
    h = [float(r['height']) for r in rows]
    assert all(b < a for a, b in zip(h, h[1:])), h
    for r in rows:
        assert abs(float(r['vertical_strain']) - (1 - float(r['height']) / h[0])) < 1e-8, r
    # The cell's servo holds every target (measured: the first within 1.7 %, the others to 0.1 %).
    assert len(at_rest) == 4, rows
    first_step = 2
else:
    assert summary['oedometer_loading'] == 'lid'
    assert len(rows) == 5, len(rows)
    assert float(rows[0]['target']) == 0
    for r in rows[1:]:
        t, s = float(r['target']), float(r['lid_stress'])
        assert (r['at_rest'] == '1') == (t > 0 and abs(s - t) <= 0.05 * t), r
    lid = [float(r['lid_stress']) for r in rows[1:]]
    assert all(b > a for a, b in zip(lid, lid[1:])), lid
    assert abs(lid[-1] - float(rows[-1]['target'])) < 0.5 * float(rows[-1]['target']), (lid, rows[-1]['target'])
    assert len(at_rest) >= 2, 'fewer than two held states: no modulus'
    first_step = 2
for r in rows:
    k0 = float(r['sigma_h']) / float(r['sigma_v'])
    assert abs(k0 - float(r['K0'])) < 1e-8 * abs(k0), r
for k, r in enumerate(rows):
    if k < first_step:
        assert r['M'] == '', r
        continue
    m, nu, e = float(r['M']), float(r['nu']), float(r['E'])
    q = rows[k - 1]
    # oedometer.csv has 9 significant digits (a relative rounding of 5e-9 each): the secant of
    # small steps (the cell's: strain steps of 6e-4 at strains of 0.29) is known to that rounding
    # of its differences.
    sr, sq = float(r['sigma_v']), float(q['sigma_v'])
    er, eq_ = float(r['vertical_strain']), float(q['vertical_strain'])
    rounding = 5e-9 * ((abs(sr) + abs(sq)) / abs(sr - sq) + (abs(er) + abs(eq_)) / abs(er - eq_) + 1)
    assert abs(m - (sr - sq) / (er - eq_)) <= 1.01 * rounding * abs(m), (r, rounding)
    assert abs(nu - float(r['K0']) / (1 + float(r['K0']))) < 1e-8, r
    assert abs(e - m * (1 + nu) * (1 - 2 * nu) / (1 - nu)) < 1e-7 * abs(e), r

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
# The friction-angle test.
tri = list(csv.DictReader(l for l in open(os.path.join(folders[1], 'triaxial.csv')) if not l.startswith('#')))
assert len(tri) == 101, len(tri)
eps1 = [float(r['axial_strain']) for r in tri]
assert eps1[0] == 0 and float(tri[0]['volumetric_strain']) == 0
assert all(b > a for a, b in zip(eps1, eps1[1:])), eps1
# Calibration/final axial strain of the scene: the lid's travel reaches it; the cell shortens as
# exp(-rate t) in a whole number of steps per record, which ends it within one record's strain.
cell = summary['oedometer_loading'] == 'periodic cell'
assert abs(eps1[-1] - 0.1) < (0.1 / 100 if cell else 1e-6), eps1[-1]
h0, x0, y0 = (float(tri[0][k]) for k in ('height', 'width_x', 'width_y'))
for r in tri:
    s1, s3 = float(r['sigma_1']), float(r['sigma_3'])
    assert abs(s1 - float(r['sigma_zz'])) <= 1e-8 * abs(s1), r
    assert abs(s3 - 0.5 * (float(r['sigma_xx']) + float(r['sigma_yy']))) <= 1e-8 * abs(s3), r
    assert abs(float(r['phi']) - math.degrees(math.asin((s1 - s3) / (s1 + s3)))) < 1e-6, r
    v = float(r['height']) * float(r['width_x']) * float(r['width_y'])
    # Six lengths of 9 significant digits: up to 6 x 5e-9 of V/V_0.
    assert abs(float(r['volumetric_strain']) - (1 - v / (h0 * x0 * y0))) < 3e-8, r
    assert abs(float(r['axial_strain']) - (h0 - float(r['height'])) / h0) < 1e-8, r
if cell:
    # No walls: the lid and wall columns are empty.
    assert all(r[k] == '' for r in tri for k in ('lid', 'wall_x_min', 'wall_x_max', 'wall_y_min', 'wall_y_max'))
sigma3 = summary['confining_stress_Pa']
mean_s3 = sum(float(r['sigma_3']) for r in tri[1:]) / (len(tri) - 1)
assert abs(mean_s3 / sigma3 - 1) < 0.1, (mean_s3, sigma3)
phi, psi = values['friction angle'], values['dilatancy angle']
# material.prm has 9 significant digits, summary.json all 17.
assert abs(phi - summary['friction_angle_deg']) < 1e-8 * phi, (values, summary)
assert abs(psi - summary['dilatancy_angle_deg']) < 1e-8 * phi, (values, summary)
assert summary['continuum_strength'] == 'peak' and summary['friction_angle_deg'] == summary['peak_friction_angle_deg']
assert 0 <= psi <= phi, (phi, psi)
assert summary['dilatancy_angle_deg'] == min(max(summary['peak_dilatancy_angle_deg'], 0), summary['friction_angle_deg'])
phi_cs = summary['critical_friction_angle_deg']
assert 3 < phi_cs < 40, phi_cs  # a sanity range for this tiny, fast test (docs/calibration.md)
assert abs(summary['jaky_k0'] - (1 - math.sin(math.radians(phi_cs)))) < 1e-12
# A scene naming the material file takes its phi (and names the file); a material file without
# phi (an older one: E and nu only) leaves the scene's own phi, named as a Continuum entry.
with open(scene_with_material, 'w') as f:
    f.write('subsection Continuum\n  set material file = ranks_1/calibration/material.prm\n'
            '  set friction angle = 44\nend\n')
r = subprocess.run([upgrain, '--check', scene_with_material], capture_output=True, text=True, cwd=work)
assert r.returncode == 0, r.stderr
line = [l for l in r.stdout.splitlines() if 'continuum material:' in l][0]
phi_read = float(line.split('friction angle ')[1].split(' deg')[0])
assert phi_read == phi and 'deg (material file' in line.split('friction angle ')[1], line
with open(os.path.join(work, 'old_material.prm'), 'w') as f:
    f.write('subsection Continuum\n  set youngs modulus = 2e6\n  set poisson ratio = 0.3\nend\n')
with open(scene_with_material, 'w') as f:
    f.write('subsection Continuum\n  set material file = old_material.prm\n  set friction angle = 33\nend\n')
r = subprocess.run([upgrain, '--check', scene_with_material], capture_output=True, text=True, cwd=work)
assert r.returncode == 0, r.stderr
line = [l for l in r.stdout.splitlines() if 'continuum material:' in l][0]
assert 'friction angle 33 deg (Continuum entry)' in line and 'E 2000000 Pa (material file' in line, line
print(f"calibration: phi peak {summary['peak_friction_angle_deg']:.2f} deg, critical {phi_cs:.2f} +- "
      f"{summary['critical_friction_angle_spread_deg']:.2f} deg, psi {psi:.2f} deg, I {summary['inertial_number']:.2e}, "
      f"Jaky K0 {summary['jaky_k0']:.3f} (measured {summary['k0_deposited']:.3f})")
print(f"calibration: E {summary['youngs_modulus_Pa']:.4g} Pa, nu {summary['poisson_ratio']:.3f}, "
      f"wall time {summary['deposition_wall_time_s']:.1f} + {summary['oedometer_wall_time_s']:.1f} + "
      f"{summary['triaxial_wall_time_s']:.1f} s")
