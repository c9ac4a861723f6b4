#!/usr/bin/env python3
"""Checks a run of `upgrain --study element` on tiny_element.prm (docs/element-tests.md).

Usage: check_element.py FOLDER RANKS PARTICLES

- isotropic.csv: one row per pressure (2, 4 kPa); the mean pressure averaged over the last
  quarter of each hold within 1 % of its target (the proportional servo's fixed point is the
  target: a packing at rest needs no strain rate, so what is left is the packing's fluctuation;
  measured 3e-5 and 4e-6 relative), each axis within 2 %; the solid fraction that of a jammed
  frictional packing (0.5 to 0.74) and not falling with the pressure; the coordination number
  above 3; the bulk modulus positive.
- triaxial.csv: 101 states; eps_1 at the end 1 - (1 - dt)^10500 (L_zz = -1/s for 10,500 steps
  of dt = 1e-5 s, each face x -> x + dt L x on the cell's grid), to 1e-9; sigma_3
  over the shearing (past its first tenth) within 6 % of the target: the proportional servo
  lags by the lateral strain rate over its gain, about rate / (2 gain) = 5 % here (measured 4.2 %); the deviator
  rising from the isotropic state to q/p > 0.3.
- shear.csv: three steady states at the targets 0.01, 0.1, 0.3; each one's inertial number
  from its mean normal stress within 5 % of its target, that stress within 5 % of 4 kPa (the
  servo's mean over a steady state with no net dilation is its target); the friction
  coefficient tau/P at I = 0.3 above that at I = 0.01 by more than their spreads' sum (the rate
  dependence of mu(I)), the solid fraction lower (dilatancy with I); shear_path.csv: 20 states
  per inertial number, the last at the strain 1 to within 20 steps' strain (the steps are
  rounded down to a whole number per state).
- the plots: shear.png beside isotropic.png and triaxial.png whenever those were drawn (the
  figure script reads the fits from summary.json).
- summary.json: the grains, the friction angles finite, the peak not below the critical state's
  less its spread; material.prm written when it says so.
"""
import csv
import json
import os
import sys


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(l for l in f if not l.startswith('#')))


def main():
    folder, _, particles = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    element = os.path.join(folder, 'element')
    problems = []
    iso = rows(os.path.join(element, 'isotropic.csv'))
    targets = [float(r['target']) for r in iso]
    if targets != [2000.0, 4000.0]:
        problems.append(f'isotropic targets {targets}')
    last_phi = 0.0
    for r in iso:
        t, p = float(r['target']), float(r['p'])
        if abs(p / t - 1) > 0.01:
            problems.append(f'p {p} at target {t}: off by more than 1 %')
        for a in 'xyz':
            if abs(float(r['p_' + a]) / t - 1) > 0.02:
                problems.append(f'p_{a} {r["p_" + a]} at target {t}: off by more than 2 %')
        phi = float(r['solid_fraction'])
        if not 0.5 < phi < 0.74 or phi < last_phi:
            problems.append(f'solid fraction {phi} at {t} (before: {last_phi})')
        last_phi = phi
        if not float(r['coordination']) > 3.0:
            problems.append(f'coordination {r["coordination"]} at {t}')
        if not float(r['bulk_modulus']) > 0.0:
            problems.append(f'bulk modulus {r["bulk_modulus"]} at {t}')
    tri = rows(os.path.join(element, 'triaxial.csv'))
    if len(tri) != 101:
        problems.append(f'{len(tri)} triaxial states, not 101')
    eps = float(tri[-1]['axial_strain'])
    if abs(eps - (1 - (1 - 1e-5)**10500)) > 1e-9:
        problems.append(f'final axial strain {eps}')
    shearing = [float(r['sigma_3']) for r in tri[11:]]
    mean_s3 = sum(shearing) / len(shearing)
    if abs(mean_s3 / 4000.0 - 1) > 0.06:
        problems.append(f'sigma_3 {mean_s3} over the shearing, target 4000')
    if not max(float(r['q_over_p']) for r in tri) > 0.3:
        problems.append('q/p never above 0.3')
    shear = rows(os.path.join(element, 'shear.csv'))
    if [float(r['target_inertial_number']) for r in shear] != [0.01, 0.1, 0.3]:
        problems.append(f'shear targets {[r["target_inertial_number"] for r in shear]}')
    for r in shear:
        t, i, n = float(r['target_inertial_number']), float(r['inertial_number']), float(r['normal_stress'])
        if abs(i / t - 1) > 0.05 or abs(n / 4000.0 - 1) > 0.05:
            problems.append(f'shear at I* {t}: I {i}, normal stress {n}')
    if len(shear) == 3:
        slow, fast = shear[0], shear[2]
        if not (float(fast['friction']) - float(slow['friction']) >
                float(fast['friction_spread']) + float(slow['friction_spread'])):
            problems.append(f'friction at I 0.3 {fast["friction"]} not above that at 0.01 {slow["friction"]} '
                            'by more than the spreads')
        if not float(fast['solid_fraction']) < float(slow['solid_fraction']):
            problems.append(f'solid fraction at I 0.3 {fast["solid_fraction"]}, at 0.01 {slow["solid_fraction"]}')
    path = rows(os.path.join(element, 'shear_path.csv'))
    if len(path) != 60:
        problems.append(f'{len(path)} shear states, not 60')
    for r in shear:
        last = [float(p['shear_strain']) for p in path if p['target_inertial_number'] == r['target_inertial_number']]
        steps = 20 * float(r['shear_rate']) * 1e-5
        if not last or not 0 <= 1.0 - last[-1] < steps:
            problems.append(f'shear at I* {r["target_inertial_number"]} ends at strain {last[-1:]}')
    drawn = [os.path.exists(os.path.join(element, f)) for f in ('isotropic.png', 'triaxial.png', 'shear.png')]
    if drawn[0] and not all(drawn):
        problems.append(f'plots drawn: isotropic, triaxial, shear {drawn} (see element/plots.log)')
    with open(os.path.join(folder, 'summary.json')) as f:
        s = json.load(f)
    if s['particles'] != particles:
        problems.append(f'{s["particles"]} grains')
    peak, crit, spread = (s['peak_friction_angle_deg'], s['critical_friction_angle_deg'],
                          s['critical_friction_angle_spread_deg'])
    if peak is None or crit is None or spread is None or peak < crit - spread:
        problems.append(f'friction angles: peak {peak}, critical {crit} +- {spread}')
    if s['material_file'] != os.path.exists(os.path.join(element, 'material.prm')):
        problems.append('material.prm against summary.json material_file')
    for p in problems:
        print(p)
    print(f'{folder}: p {[r["p"] for r in iso]}, solid fraction {[r["solid_fraction"] for r in iso]}, '
          f'sigma_3 {mean_s3:.1f}, peak {peak:.2f} deg, critical {crit:.2f} deg, '
          f'mu {[r["friction"] for r in shear]}: {len(problems)} problems')
    sys.exit(1 if problems else 0)


if __name__ == '__main__':
    main()
