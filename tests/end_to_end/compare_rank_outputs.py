#!/usr/bin/env python3
"""Checks that runs of one scene on different rank counts wrote the same results.

Usage: compare_rank_outputs.py REFERENCE_FOLDER OTHER_FOLDER...

- Every HDF5 file (snapshots, grid stress, grid strain), XDMF file and grid CSV table:
  byte-identical.
- time_series.csv and summary.json: every number bitwise equal, except the cumulative
  dissipation (and the totals built on it), which is summed per rank and equal to 1e-12
  relative (the balance error, itself a ratio, to 1e-12 absolute; docs/parallel.md), and
  the timings and rank count.
Report, plots, logs and the deal.II meshes (which carry their creation time) are skipped,
and the compute-grid stress and strain, whose blocks are those of each rank count.
"""
import csv
import json
import os
import sys

SKIP_SUFFIXES = ('.md', '.png', '.log', '.pvtu', '.vtu', '.pvd')
# The stress and strain per MPI block: the blocks are the rank count's own (docs/stress.md,
# docs/strain.md).
SKIP_FILES = {'compute_grid_stress.csv', 'compute_grid_strain.csv'}
SKIP_FOLDERS = ('compute_grid_strain' + os.sep,)
ROUND_OFF = {'dissipated_damping', 'dissipated_friction', 'tangential_stiffness_change', 'total',
             'balance_error', 'dissipated_damping_J', 'dissipated_friction_J',
             'tangential_stiffness_change_J', 'energy_balance_error'}
# Timings, and how the work was shared, which depend on the rank count by design.
TIMINGS = {'wall_time_s', 'particle_steps_per_second', 'mpi_ranks', 'load_rebalances', 'load_owned_imbalance',
           'load_compute_imbalance', 'load_communication_share'}


def files(folder):
    out = []
    for root, _, names in os.walk(folder):
        for n in names:
            rel = os.path.relpath(os.path.join(root, n), folder)
            if not rel.startswith(SKIP_FOLDERS):
                out.append(rel)
    return sorted(out)


# The balance error is already a ratio to the energy put into play, and a difference of
# nearly equal totals: its round-off is compared absolutely (1e-12 of that energy).
NORMALISED = {'balance_error', 'energy_balance_error'}


def close(a, b, what, problems, normalised=False):
    a, b = float(a), float(b)
    if a == b:
        return
    scale = 1.0 if normalised else max(abs(a), abs(b), 1e-300)
    if abs(a - b) > 1e-12 * scale:
        problems.append(f'{what}: {a!r} vs {b!r} (beyond 1e-12 {"absolute" if normalised else "relative"})')


def compare(ref, other):
    problems = []
    ref_files, other_files = files(ref), files(other)
    if [f for f in ref_files if not f.endswith(SKIP_SUFFIXES)] != \
       [f for f in other_files if not f.endswith(SKIP_SUFFIXES)]:
        problems.append(f'different file sets: {sorted(set(ref_files) ^ set(other_files))}')
    identical = 0
    for f in ref_files:
        if f.endswith(SKIP_SUFFIXES) or f in SKIP_FILES or f not in other_files:
            continue
        a = open(os.path.join(ref, f), 'rb').read()
        b = open(os.path.join(other, f), 'rb').read()
        if f == 'time_series.csv':
            ra = list(csv.reader(l for l in a.decode().splitlines() if not l.startswith('#')))
            rb = list(csv.reader(l for l in b.decode().splitlines() if not l.startswith('#')))
            header = ra[0]
            if len(ra) != len(rb):
                problems.append(f'{f}: {len(ra)} vs {len(rb)} rows')
                continue
            for row_a, row_b in zip(ra[1:], rb[1:]):
                for name, x, y in zip(header, row_a, row_b):
                    if name in ROUND_OFF:
                        close(x, y, f'{f} {name} at t = {row_a[0]}', problems, name in NORMALISED)
                    elif x != y:
                        problems.append(f'{f} {name} at t = {row_a[0]}: {x} vs {y}')
        elif f == 'summary.json':
            ja, jb = json.loads(a), json.loads(b)
            for key in ja:
                if key in TIMINGS:
                    continue
                if key in ROUND_OFF:
                    close(ja[key], jb[key], f'{f} {key}', problems, key in NORMALISED)
                elif ja[key] != jb.get(key):
                    problems.append(f'{f} {key}: {ja[key]} vs {jb.get(key)}')
        elif a != b:
            problems.append(f'{f}: bytes differ')
        else:
            identical += 1
    return identical, problems


def main():
    ref = sys.argv[1]
    failed = False
    for other in sys.argv[2:]:
        identical, problems = compare(ref, other)
        for p in problems[:20]:
            print(f'{other}: {p}')
        failed = failed or bool(problems) or identical == 0
        print(f'{other}: {identical} files byte-identical to {ref}, {len(problems)} problems')
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
