#!/usr/bin/env python3
"""Checks that runs of one scene on different rank counts, or a run and its restarts, wrote the
same results.

Usage: compare_rank_outputs.py [--other-blocks | --no-checkpoints] [--meshes] [--report]
                               REFERENCE_FOLDER OTHER_FOLDER...

- Every HDF5 file (snapshots, grid stress, grid strain), XDMF file and grid CSV table:
  byte-identical.
- time_series.csv and summary.json: every number bitwise equal (the cumulative dissipation is
  an exact sum, docs/parallel.md), but the timings, how the work was shared and where a run was
  resumed.
- Checkpoints: every dataset and attribute the same bytes but the run's wall time, the steps it
  was resumed at (docs/restart.md, "Timings") and the run's identity; their checksum blocks differ
  with them. The run's bookkeeping (.upgrain/: its manifest and lock) is left out.
Report, plots and logs are skipped, and so are the deal.II meshes (a piece per rank) unless
--meshes is given, for runs on one rank count: then they too must be the same bytes (their
records carry no creation date, dem/files/undated_vtk.h). With --report, report.md is compared
line by line but its timings (the line "- Wall clock: ..." and the section "## Timings") and
the name of the scene file it gives.
With --other-blocks (runs on different rank counts) so are the compute-grid stress and strain,
whose blocks are those of each rank count, and the checkpoints, which keep the blocks; with
--no-checkpoints the checkpoints alone (a run continued with another end time, or stopped by a
signal, has other checkpoints by design: they hold the scene's text and the step they stopped at).
"""
import csv
import json
import os
import sys

# The deal.II meshes have a piece per rank: compared (--meshes) between runs on one rank count.
MESH_SUFFIXES = ('.pvtu', '.vtu', '.pvd')
SKIP_SUFFIXES = ('.md', '.png', '.log') + MESH_SUFFIXES
# The stress and strain per MPI block: the blocks are the rank count's own (docs/stress.md,
# docs/strain.md).
BLOCK_FILES = {'compute_grid_stress.csv', 'compute_grid_strain.csv'}
BLOCK_FOLDERS = ('compute_grid_strain' + os.sep, 'checkpoints' + os.sep)
SKIP_FILES = set()
SKIP_FOLDERS = ()
# The run's bookkeeping (docs/output.md, "Manifest", "Lock"): its identity, checksums of the
# timed report and its processes differ from run to run by design.
BOOKKEEPING = '.upgrain' + os.sep
# Timings, and how the work was shared, which depend on the rank count by design; where a run was
# resumed.
TIMINGS = {'wall_time_s', 'particle_steps_per_second', 'mpi_ranks', 'load_rebalances', 'load_owned_imbalance',
           'load_compute_imbalance', 'load_communication_share', 'segment_wall_time_s', 'resumed_at_steps'}
# The same in a checkpoint: attributes and datasets of /run (coupling/run/checkpoint.cc); and the
# identity of the run it belongs to, which two runs do not share (docs/restart.md).
CHECKPOINT_HISTORY = {'run/wall_seconds', 'run/resumed_at', 'run_id'}
COMPARE_REPORT = False


def report_lines(text):
    """report.md without its timings (the wall-clock line and the Timings section) and the name
    of the scene file (runs of one scene may start from files of other names)."""
    out, timings = [], False
    for line in text.splitlines():
        if line.startswith('## '):
            timings = line.startswith('## Timings')
        if line.startswith('Scene: `'):
            line = 'Scene: `...`' + line.split('`', 2)[2]
        if not timings and not line.startswith('- Wall clock:'):
            out.append(line)
    return out


def checkpoint_differences(a, b):
    """The datasets and attributes of two checkpoints that differ, but the run's history."""
    import h5py
    import numpy as np

    def items(path):
        found = {}
        with h5py.File(path, 'r') as f:
            def visit(name, obj):
                if isinstance(obj, h5py.Dataset):
                    found[name] = np.asarray(obj[()]).tobytes()
                for key, value in obj.attrs.items():
                    found[f'{name}/{key}' if name else key] = np.asarray(value).tobytes()
            visit('', f)
            f.visititems(visit)
        return {k: v for k, v in found.items() if k not in CHECKPOINT_HISTORY}

    ia, ib = items(a), items(b)
    return sorted(k for k in set(ia) | set(ib) if ia.get(k) != ib.get(k))


def files(folder):
    out = []
    for root, _, names in os.walk(folder):
        for n in names:
            rel = os.path.relpath(os.path.join(root, n), folder)
            if not rel.startswith(SKIP_FOLDERS) and not rel.startswith(BOOKKEEPING):
                out.append(rel)
    return sorted(out)


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
                    if x != y:
                        problems.append(f'{f} {name} at t = {row_a[0]}: {x} vs {y}')
        elif f == 'summary.json':
            ja, jb = json.loads(a), json.loads(b)
            for key in sorted(set(ja) | set(jb)):
                if key in TIMINGS:
                    continue
                if ja.get(key) != jb.get(key):
                    problems.append(f'{f} {key}: {ja.get(key)} vs {jb.get(key)}')
        elif f.startswith('checkpoints' + os.sep) and a != b:
            differ = checkpoint_differences(os.path.join(ref, f), os.path.join(other, f))
            if differ:
                problems.append(f'{f}: differs in {", ".join(differ[:5])}')
            else:
                identical += 1
        elif a != b:
            problems.append(f'{f}: bytes differ')
        else:
            identical += 1
    if COMPARE_REPORT:
        have = [os.path.exists(os.path.join(d, 'report.md')) for d in (ref, other)]
        if have[0] != have[1]:
            problems.append(f'report.md written by {"one" if any(have) else "neither"} of the runs')
        elif have[0]:
            la = report_lines(open(os.path.join(ref, 'report.md')).read())
            lb = report_lines(open(os.path.join(other, 'report.md')).read())
            for k in range(max(len(la), len(lb))):
                x = la[k] if k < len(la) else '(none)'
                y = lb[k] if k < len(lb) else '(none)'
                if x != y:
                    problems.append(f'report.md line {k + 1} (timings aside): {x!r} vs {y!r}')
                    break
    return identical, problems


def main():
    global SKIP_FILES, SKIP_FOLDERS
    global SKIP_SUFFIXES, COMPARE_REPORT
    args = sys.argv[1:]
    while args and args[0].startswith('--'):
        option = args.pop(0)
        if option == '--other-blocks':
            SKIP_FILES, SKIP_FOLDERS = BLOCK_FILES, BLOCK_FOLDERS
        elif option == '--no-checkpoints':
            SKIP_FOLDERS = ('checkpoints' + os.sep,)
        elif option == '--report':
            COMPARE_REPORT = True
        elif option == '--meshes':
            SKIP_SUFFIXES = tuple(s for s in SKIP_SUFFIXES if s not in MESH_SUFFIXES)
        else:
            sys.exit(f'unknown option {option}')
    ref = args[0]
    failed = False
    for other in args[1:]:
        identical, problems = compare(ref, other)
        for p in problems[:20]:
            print(f'{other}: {p}')
        failed = failed or bool(problems) or identical == 0
        print(f'{other}: {identical} files byte-identical to {ref}, {len(problems)} problems')
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
