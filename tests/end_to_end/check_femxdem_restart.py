#!/usr/bin/python3
"""Stops the FEM x DEM study (docs/femxdem.md, "Checkpoints and restart") with SIGTERM after its
first load step and continues it with `upgrain --study femxdem --restart`, then checks:
- the stopped run wrote one checkpoint, after the step it stopped at, exited with 143 and said how
  to continue; no working folder of the solver's files is left;
- `upgrain --restart` without --study is refused by name;
- the continued run resumed after that step and wrote the same bytes as a run that was not
  stopped: points.csv, point_history.csv, every femxdem-NNNN piece and .pvtu, femxdem.pvd, and
  load_displacement.csv but its wall-time column; summary.json the same but its timings and
  resume step;
- the same checkpoint continued on 2 ranks (the cells repartitioned by p4est) gives the same
  points to 1e-6 (not bitwise: the matrix is summed in another order);
- every point has its own packing (FEMxDEM/cell packings = 0), and a continued run prepares none
  of them again: its cells come with their packings in the checkpoint (summary.json's
  packings_prepared counts only the first, which the log reports, on each rank);
- the two cells the scene asks for (FEMxDEM/cell snapshots = 0:0, 1:3, written here into the
  scene) have a snapshot of every load step, before and after the restart, each of the cell's 60
  grains with their periodic images, the same bytes as the uninterrupted run's, and an XDMF
  series listing them all; on 2 ranks, where the second element's cells are the other rank's, too.

Usage: check_femxdem_restart.py UPGRAIN SCENE WORK [MPIEXEC]
"""
import csv
import filecmp
import json
import os
import shutil
import signal
import subprocess
import sys

upgrain, scene, work = sys.argv[1:4]
mpiexec = sys.argv[4] if len(sys.argv) > 4 else 'mpiexec'
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
with open(scene) as f:
    text = f.read().replace('subsection FEMxDEM\n',
                            'subsection FEMxDEM\n  set cell snapshots = 0:0, 1:3\n  set cell packings = 0\n', 1)
scene = os.path.join(work, 'scene.prm')
with open(scene, 'w') as f:
    f.write(text)
whole, broken, other = (os.path.join(work, n) for n in ('whole', 'broken', 'broken_on_2_ranks'))


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f'{" ".join(cmd)}: exit {r.returncode}\n{r.stdout}\n{r.stderr}')
    return r.stdout


def table(path, drop=()):
    rows = list(csv.DictReader(l for l in open(path) if not l.startswith('#')))
    return [{k: v for k, v in row.items() if k not in drop} for row in rows]


run([upgrain, '--study', 'femxdem', '--output', whole, scene])

# Stopped as soon as its first load step is in the log (three more to go).
proc = subprocess.Popen([upgrain, '--study', 'femxdem', '--output', broken, scene], stdout=subprocess.PIPE,
                        stderr=subprocess.STDOUT, text=True)
log = ''
for line in proc.stdout:
    log += line
    if 'femxdem: step 1/' in line:
        proc.send_signal(signal.SIGTERM)
code = proc.wait()
assert code == 143, f'a run stopped by SIGTERM must exit with 143, not {code}\n{log}'
assert 'stopped by signal 15' in log and 'after step 1, checkpoint' in log, log
assert 'femxdem: checkpoint ' + os.path.join(broken, 'checkpoints', 'checkpoint_000000001.h5') + \
    ' after load step 1 (' in log, log
assert 'continue with: upgrain --study femxdem --restart ' + broken in log, log
checkpoints = sorted(os.listdir(os.path.join(broken, 'checkpoints')))
assert checkpoints == ['checkpoint_000000001.h5'], checkpoints

r = subprocess.run([upgrain, '--restart', broken], capture_output=True, text=True)
assert r.returncode != 0 and 'it is a run of --study femxdem; continue it with upgrain --study femxdem ' \
    '--restart' in r.stdout + r.stderr, r.stdout + r.stderr

shutil.copytree(broken, other)
log = run([upgrain, '--study', 'femxdem', '--restart', broken])
assert 'resuming from ' + os.path.join(broken, 'checkpoints', checkpoints[0]) + ' after load step 1' in log, log
assert 'femxdem: resumed after load step 1 of 4' in log, log
assert 'femxdem: step 1/' not in log and 'femxdem: step 2/4' in log, log
assert not os.path.exists(os.path.join(broken, 'checkpoints', 'femxdem_state')), 'the working folder is left'

a, b = os.path.join(whole, 'femxdem'), os.path.join(broken, 'femxdem')
same = [f for f in sorted(os.listdir(a)) if f.endswith(('.vtu', '.pvtu', '.pvd')) or f.startswith('point')]
assert len(same) >= 13, same
_, mismatch, errors = filecmp.cmpfiles(a, b, same, shallow=False)
assert not mismatch and not errors, (mismatch, errors)
assert table(os.path.join(a, 'load_displacement.csv'), ('wall_s',)) == \
    table(os.path.join(b, 'load_displacement.csv'), ('wall_s',))
timing = ('preparation_s', 'solve_s', 'grain_steps_per_core_second', 'resumed_after_step', 'packings_prepared')
s1, s2 = (json.load(open(os.path.join(f, 'summary.json'))) for f in (whole, broken))
assert s1['resumed_after_step'] is None and s2['resumed_after_step'] == 1, (s1, s2)
# Every point its own packing: the run prepared each point's and the first (the log's); the
# continued run only the first, its cells loaded from the checkpoint with their packings.
assert s1['packings_prepared'] == 9 and s2['packings_prepared'] == 1, (s1, s2)
assert {k: v for k, v in s1.items() if k not in timing} == {k: v for k, v in s2.items() if k not in timing}

log = run([mpiexec, '-n', '2', upgrain, '--study', 'femxdem', '--restart', other])
assert 'femxdem: resumed after load step 1 of 4' in log, log
s3 = json.load(open(os.path.join(other, 'summary.json')))
assert s3['packings_prepared'] == 2, s3  # the first, on each rank
p1, p2 = table(os.path.join(a, 'points.csv')), table(os.path.join(other, 'femxdem', 'points.csv'))
assert len(p1) == len(p2) == 8, (len(p1), len(p2))
for x, y in zip(p1, p2):
    assert (x['cell'], x['point']) == (y['cell'], y['point']), (x, y)
    for k in ('sigma_xx', 'sigma_yy', 'sigma_xy', 'eps_yy', 'solid_fraction'):
        u, v = float(x[k]), float(y[k])
        assert abs(u - v) <= 1e-6 * max(abs(u), abs(v), 1e-3), (k, x, y)
for run_folder in (whole, broken, other):
    for cell in ('0_0', '1_3'):
        d = os.path.join(run_folder, 'femxdem', 'cells', cell)
        files = sorted(os.listdir(d))
        assert files == ['cell.xdmf'] + [f'cell_{k:04d}.h5' for k in range(5)], (d, files)
        xdmf = open(os.path.join(d, 'cell.xdmf')).read()
        assert all(f'cell_{k:04d}.h5:/particles/position' in xdmf for k in range(5)), xdmf
    assert sorted(os.listdir(os.path.join(run_folder, 'femxdem', 'cells'))) == ['0_0', '1_3']
for cell in ('0_0', '1_3'):
    names = [f'cell_{k:04d}.h5' for k in range(5)] + ['cell.xdmf']
    _, mismatch, errors = filecmp.cmpfiles(os.path.join(a, 'cells', cell), os.path.join(b, 'cells', cell),
                                           names, shallow=False)
    assert not mismatch and not errors, (cell, mismatch, errors)
try:
    import h5py
    with h5py.File(os.path.join(a, 'cells', '1_3', 'cell_0004.h5'), 'r') as f:
        assert f['particles/position'].shape == (60, 3) and f['particles/image'].shape == (60, 3)
        assert int(f.attrs['step']) == 4
except ImportError:
    pass
print('FEM x DEM restart: stopped after step 1, continued to the same bytes on 1 rank and to 1e-6 on 2')
