#!/usr/bin/env python3
"""The time step past its limit, through the driver (docs/time-step.md, docs/hard-cases.md):

1. 1.5 x the safe step without the override is refused: exit 1, "exceeds the safe step",
   nothing written.
2. With 'allow unsafe time step = true' at FACTOR x the safe step the run goes unstable; the
   runaway-overlap guard stops it: exit 1 and a one-line diagnosis naming the step, the
   contact's particle, the time step against the safe one. The output folder is consistent:
   no temporary file is left, every HDF5 file opens with its particles whole, the time
   series' rows are complete, and the last snapshot is the last good state: the step before
   the one the guard names, written by the driver when the guard stopped the run, and the same
   bits as the state of a run of the same scene that ends at that step.

Usage: run_unsafe_step.py UPGRAIN WORK FACTOR
"""
import csv
import glob
import os
import re
import shutil
import subprocess
import sys

import h5py

SCENE = """subsection Particles
  set count = 150
  set youngs modulus = 5e7
end
subsection Container
  set length x = 0.015
  set length y = 0.015
end
subsection Fill
  set bottom gap = 0.005
  set position jitter = 0.5
end
subsection Simulation
  set time step = {dt!r}
  set allow unsafe time step = {unsafe}
  set end time = {end!r}
end
subsection Output
  set folder = {folder}
  set snapshot interval = 0.01
  set time series interval = 0.001
end
subsection Study
  set compare with continuum = false
  set relax at end = false
end
"""


def fail(message):
    sys.exit('FAILED: ' + message)


def write_scene(work, name, dt, unsafe, end=0.3):
    folder = os.path.join(work, name)
    path = os.path.join(work, name + '.prm')
    with open(path, 'w') as f:
        f.write(SCENE.format(dt=dt, unsafe='true' if unsafe else 'false', folder=folder, end=end))
    return path, folder


def run(upgrain, *args):
    return subprocess.run([upgrain, *args], capture_output=True, text=True, timeout=300)


def main():
    upgrain, work, factor = sys.argv[1], sys.argv[2], float(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    probe, _ = write_scene(work, 'probe', 1e-6, False)
    p = run(upgrain, '--check', probe)
    m = re.search(r'safe ([0-9.e+-]+) s', p.stdout)
    if p.returncode != 0 or not m:
        fail('--check gave no safe step:\n' + p.stdout + p.stderr)
    safe = float(m.group(1))  # printed to 3 digits: 1.5 x it is past the limit regardless

    scene, folder = write_scene(work, 'refused', 1.5 * safe, False)
    p = run(upgrain, scene)
    print('1.5 x safe, no override: exit', p.returncode, p.stderr.strip())
    if p.returncode != 1 or 'exceeds the safe step' not in p.stderr:
        fail('1.5 x the safe step was not refused')
    if os.path.exists(folder):
        fail('the refused run wrote ' + folder)

    scene, folder = write_scene(work, 'unstable', factor * safe, True)
    p = run(upgrain, scene)
    print(f'{factor} x safe with the override: exit', p.returncode, p.stderr.strip())
    m = re.search(r'runaway overlap at step (\d+) \(t = [0-9.e+-]+ s\): an overlap of particle (\d+) with '
                  r"(particle \d+|wall '\w+') reached ([0-9.e+-]+) of a radius", p.stderr)
    if p.returncode != 1 or not m:
        fail('the unstable run was not stopped by the runaway-overlap guard')
    if 'time step' not in p.stderr or 'too large' not in p.stderr:
        fail('the diagnosis does not name the time step as the likely cause')
    failed_at = int(m.group(1))
    good = failed_at - 1
    if f'the last good state, step {good}, is written as the last snapshot' not in p.stderr:
        fail(f'the diagnosis does not say that the last good state (step {good}) is written')

    left = [f for f in glob.glob(os.path.join(folder, '**', '*'), recursive=True) if re.search(r'\.tmp\.\d+$', f)]
    if left:
        fail('temporary files left: ' + ', '.join(left))
    snapshots = sorted(glob.glob(os.path.join(folder, 'snapshots', 'particles_*.h5')))
    if not snapshots:
        fail('no snapshot written before the failure')
    last_step = -1
    for name in glob.glob(os.path.join(folder, '**', '*.h5'), recursive=True):
        with h5py.File(name, 'r') as h:
            if 'particles' in h:
                if h['particles/id'].shape[0] != 150:
                    fail(name + ' does not hold the 150 particles')
                if 'snapshots' in name:
                    last_step = max(last_step, int(h.attrs['step']))
    if last_step != good:
        fail(f'the last snapshot (step {last_step}) is not the last good state (step {good}, the guard named '
             f'step {failed_at})')
    # The same scene run to that step and no further: its final snapshot is the state the
    # failed run had there, bit for bit (the driver replayed to it from its last snapshot).
    scene, reference = write_scene(work, 'reference', factor * safe, True, end=good * factor * safe)
    p = run(upgrain, scene)
    if p.returncode != 0:
        fail('the run to the last good step failed:\n' + p.stderr)
    name = f'particles_{good:09d}.h5'
    compared = 0
    with h5py.File(os.path.join(folder, 'snapshots', name), 'r') as a, \
            h5py.File(os.path.join(reference, 'snapshots', name), 'r') as b:
        for key in b['particles']:
            if not (a['particles/' + key][()] == b['particles/' + key][()]).all():
                fail(f'the last good state differs from the run to step {good} in particles/{key}')
            compared += 1
    print(f'the last good state, step {good}, equals the run to that step in its {compared} particle datasets')
    with open(os.path.join(folder, 'time_series.csv')) as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith('#')]
    widths = {len(r) for r in rows}
    if len(widths) != 1 or len(rows) < 2:
        fail(f'time_series.csv has rows of widths {widths}')
    print(f'output folder: {len(snapshots)} snapshots, the last at step {last_step} = {failed_at} - 1; '
          f'{len(rows) - 1} complete time-series rows; no temporary file')
    print('OK')


main()
