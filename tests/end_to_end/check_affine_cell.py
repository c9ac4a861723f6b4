#!/usr/bin/env python3
"""Checks a run of tiny_affine_cell.prm (docs/periodic.md, "Strain over a periodic cell").

Usage: check_affine_cell.py FOLDER RANKS PARTICLES

- time_series.csv: no contact at any row (the gas never touches: otherwise the test says nothing).
- cell_deformation.csv: a row per strain evaluation (at least 10), each with every grain in the fit
  and the best-fit F of all grains within 1e-12 of the cell's h h0^-1 in every component (the
  grains on the mean flow, followed across the faces and the tilt's remaps); the last row of the
  motion (t <= 0.1 s: the run's relaxation holds the cell after it) sheared (F_xz above 0.4) and
  squeezed along x, stretched along z as the rates say: (1 + L_dd dt)^steps to 1e-9 (each face
  x -> x + dt L x on the cell's grid, dt = 1e-5 s).
"""
import csv
import os
import sys


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(l for l in f if not l.startswith('#')))


def main():
    folder, particles = sys.argv[1], int(sys.argv[3])
    problems = []
    series = rows(os.path.join(folder, 'time_series.csv'))
    if any(int(r['particle_contacts']) != 0 for r in series):
        problems.append('the gas touched: contacts in the time series')
    cell = rows(os.path.join(folder, 'cell_deformation.csv'))
    if len(cell) < 10:
        problems.append(f'{len(cell)} rows in cell_deformation.csv')
    worst = 0.0
    for r in cell:
        if int(r['grains']) != particles:
            problems.append(f'{r["grains"]} grains in the fit at t = {r["time"]}')
        d = max(abs(float(r['F_grains_' + c]) - float(r['F_cell_' + c]))
                for c in ('xx', 'xy', 'xz', 'yx', 'yy', 'yz', 'zx', 'zy', 'zz'))
        worst = max(worst, d, float(r['difference']))
    if worst > 1e-12:
        problems.append(f'best-fit F off the cell F by {worst:.3g}')
    moving = [r for r in cell if float(r['time']) <= 0.1 + 1e-9]
    last = moving[-1] if moving else None
    if last:
        if not float(last['F_cell_xz']) > 0.4:
            problems.append(f'F_xz {last["F_cell_xz"]}: not sheared')
        steps = int(last['step'])
        for c, rate in (('xx', -1.0), ('zz', 2.0)):
            expected = (1 + rate * 1e-5)**steps
            if abs(float(last['F_cell_' + c]) / expected - 1) > 1e-9:
                problems.append(f'F_{c} {last["F_cell_" + c]} against (1 + {rate} dt)^{steps} = {expected}')
    for p in problems:
        print(p)
    print(f'{folder}: {len(cell)} rows, largest |F_grains - F_cell| {worst:.3g}: {len(problems)} problems')
    sys.exit(1 if problems else 0)


if __name__ == '__main__':
    main()
