#!/usr/bin/env python3
"""A bed settled on 1 rank and continued on 2 is balanced at the restart (docs/restart.md,
docs/parallel.md "Load balance").

Usage: check_restart_balance.py UPGRAIN SCENE WORK MPIEXEC NP_FLAG

1. The scene runs to its end time on 2 ranks without interruption (WORK/whole).
2. It runs on 1 rank to its Checkpoint/interval (WORK/broken; its last step writes a
   checkpoint), and is continued with `upgrain --restart WORK/broken SCENE` on 2 ranks.
3. The case: the bed is at rest from the restart on, so its lists are not rebuilt after it (the
   neighbor_builds column of time_series.csv stays), and no rebuild can move the planes.
4. The continued run's summary.json must give an owned imbalance (load_owned_imbalance, max/mean
   of the grains per rank) below 1.1: with the default planes every grain lay in the lower block
   (2.0). Every file but the timings and the checkpoints must equal the uninterrupted run's
   (compare_rank_outputs.py --other-blocks).
"""
import csv
import json
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def run(command, log):
    r = subprocess.run(command, stdout=log, stderr=log)
    if r.returncode != 0:
        sys.exit(f'{" ".join(command)} failed ({r.returncode}); see {log.name}')


def main():
    upgrain, scene, work, mpiexec, np_flag = sys.argv[1:6]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    log = open(os.path.join(work, 'runs.log'), 'w')
    text = open(scene).read()
    restart = float(re.search(r'set interval\s*=\s*(\S+)', text[text.index('subsection Checkpoint'):]).group(1))
    first = os.path.join(work, 'first.prm')
    with open(first, 'w') as f:
        f.write(re.sub(r'set end time\s*=\s*\S+', f'set end time = {restart!r}', text))
    two = [mpiexec, np_flag, '2', upgrain]
    whole, broken = os.path.join(work, 'whole'), os.path.join(work, 'broken')
    run(two + ['--output', whole, scene], log)
    run([upgrain, '--output', broken, first], log)
    run(two + ['--restart', broken, scene], log)
    rows = list(csv.reader(l for l in open(os.path.join(broken, 'time_series.csv')) if not l.startswith('#')))
    t, builds = rows[0].index('time'), rows[0].index('neighbor_builds')
    after = {r[builds] for r in rows[1:] if float(r[t]) >= restart}
    if len(after) != 1:
        sys.exit(f'the case: the bed is rebuilt after the restart at {restart} s (neighbor builds {sorted(after)}), '
                 'where a rebuild could rebalance it; restart it later')
    summary = json.load(open(os.path.join(broken, 'summary.json')))
    imbalance, rebalances = summary['load_owned_imbalance'], summary['load_rebalances']
    print(f'restarted on 2 ranks from a checkpoint of 1: owned imbalance {imbalance:.3f}, {rebalances} '
          f'rebalances (the uninterrupted run: '
          f'{json.load(open(os.path.join(whole, "summary.json")))["load_owned_imbalance"]:.3f})')
    if not imbalance < 1.1:
        sys.exit(f'the restart onto 2 ranks left the grains unbalanced: owned max/mean {imbalance}')
    compare = [sys.executable, os.path.join(HERE, 'compare_rank_outputs.py'), '--other-blocks', whole, broken]
    sys.exit(subprocess.run(compare).returncode)


if __name__ == '__main__':
    main()
