#!/usr/bin/env python3
"""Checks an accuracy study's results (docs/accuracy.md). Usage: check_accuracy.py FOLDER
(the study's output folder, or its accuracy/ folder).

- the skin's rows: every change 0 (the same bits);
- the time step's rows: the Hertz collision's error shrinks with the step at the order of
  velocity Verlet (2, within 0.3) between the two smallest steps;
- the continuum's rows: Q1's stress error halves with each refinement (order 1 in h, within
  0.2); Q2 reproduces the analytic column to 1e-10;
- the contact solver's rows (ellipsoid scenes): one marked row per knob, the scene's own; a
  looser gradient bound never gives a smaller depth error against the constructed contacts, the
  loosest a larger one than the tightest, and a bound of 1e10 eps stays below 1e-6 c; a cap of 2 Newton steps gives a larger error than 30;
- every row has a wall time, and an exact error or a change of the bed;
- the report names, per knob, its cheapest setting within the tolerance.
"""
import csv
import math
import os
import sys


def main():
    folder = sys.argv[1]
    if os.path.isdir(os.path.join(folder, 'accuracy')):
        folder = os.path.join(folder, 'accuracy')
    with open(os.path.join(folder, 'accuracy.csv')) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith('#')))
    problems = []
    num = lambda r, k: float(r[k])
    for r in rows:
        if not (math.isfinite(num(r, 'wall_s')) and num(r, 'wall_s') > 0):
            problems.append(f"{r['knob']} {r['setting']}: no wall time")
        changes = [num(r, k) for k in r if k.endswith('_change')]
        if not (math.isfinite(num(r, 'exact_error')) or any(math.isfinite(c) for c in changes)):
            problems.append(f"{r['knob']} {r['setting']}: neither an exact error nor a change")
    for r in rows:
        if r['knob'] == 'skin':
            bad = [k for k in r if k.endswith('_change') and math.isfinite(num(r, k)) and num(r, k) != 0.0]
            if bad:
                problems.append(f"skin {r['setting']}: {bad} changed; the skin must change no bit")
    steps = sorted((num(r, 'value'), num(r, 'exact_error')) for r in rows if r['knob'] == 'time step')
    if len(steps) >= 2:
        (f1, e1), (f2, e2) = steps[0], steps[1]
        order = math.log(e2 / e1) / math.log(f2 / f1)
        print(f'time step: collision error {e1:.3g} at {f1:.3g}, {e2:.3g} at {f2:.3g}: order {order:.2f}')
        if abs(order - 2.0) > 0.3:
            problems.append(f'time step: order {order:.2f}, not 2')
    else:
        problems.append('time step: fewer than two rows')
    fem = {r['setting']: num(r, 'exact_error') for r in rows if r['knob'] == 'fem'}
    q1 = [fem[k] for k in sorted(fem) if k.startswith('Q1')]
    if len(q1) >= 2:
        order = math.log(q1[0] / q1[1]) / math.log(2.0)
        print(f'fem: Q1 stress error {q1[0]:.3g} -> {q1[1]:.3g}: order {order:.2f}')
        if abs(order - 1.0) > 0.2:
            problems.append(f'fem: Q1 order {order:.2f}, not 1')
    for k, e in fem.items():
        if k.startswith('Q2') and not e < 1e-10:
            problems.append(f'fem: {k} error {e:.3g}, the analytic column is quadratic')
    for knob in ('solver tolerance', 'solver iterations'):
        own = [r for r in rows if r['knob'] == knob]
        if own and sum(r['default'] == '1' for r in own) != 1:
            problems.append(f'{knob}: {sum(r["default"] == "1" for r in own)} rows marked as the scene\'s own, not 1')
    tol = sorted((num(r, 'value'), num(r, 'exact_error')) for r in rows if r['knob'] == 'solver tolerance')
    for (t1, e1), (t2, e2) in zip(tol, tol[1:]):
        if e2 < e1:
            problems.append(f'solver tolerance: {t2:.3g} gives a smaller depth error ({e2:.3g}) than {t1:.3g} ({e1:.3g})')
    if len(tol) >= 2 and not tol[-1][1] > tol[0][1]:
        problems.append(f'solver tolerance: {tol[-1][0]:.3g} gives no larger error than {tol[0][0]:.3g}: the bound is not felt')
    for t, e in tol:
        print(f'solver tolerance {t:.3g}: depth error {e:.3g} c')
        if t <= 1e10 and not e < 1e-6:
            problems.append(f'solver tolerance {t:.3g}: depth error {e:.3g} c')
    caps = {num(r, 'value'): num(r, 'exact_error') for r in rows if r['knob'] == 'solver iterations'}
    if 2.0 in caps and 30.0 in caps:
        print(f'solver iterations: depth error {caps[30.0]:.3g} c at 30, {caps[2.0]:.3g} c at 2')
        if not caps[2.0] > caps[30.0]:
            problems.append('solver iterations: a cap of 2 gives no larger error than 30')
    report = open(os.path.join(folder, 'accuracy.md')).read()
    knobs = {r['knob'] for r in rows if r['knob'] != 'reference'}
    if report.count('Cheapest setting within the tolerance') != len(knobs):
        problems.append('the report does not name a cheapest setting for every knob')
    for p in problems:
        print('problem:', p)
    print(f'{len(rows)} rows, {len(problems)} problems')
    sys.exit(1 if problems else 0)


if __name__ == '__main__':
    main()
