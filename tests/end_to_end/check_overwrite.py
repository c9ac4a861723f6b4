#!/usr/bin/env python3
"""Output/overwrite = true replaces the earlier run whole (docs/output.md, "Overwrite").

Usage: check_overwrite.py UPGRAIN SCENE WORK

1. SCENE runs to twice its end time into WORK/out (more snapshots, grid files and rows).
2. SCENE runs again, to its own end time, into WORK/out with Output/overwrite = true, and once
   more into the fresh folder WORK/fresh.
3. WORK/out must hold exactly the files of WORK/fresh (nothing of the longer run left: no later
   snapshot, no grid file, no mesh listed in strain_mesh/strain.pvd, no longer table), its time
   series must end at the end time, and every JSON file must be valid JSON (no NaN or Infinity,
   which Python's reader would otherwise take), also for a run without gravity, whose ratio of
   kinetic to released energy has no value.
4. A folder holding other files than a run (no manifest), or a run and a scene file (a file its
   manifest does not list), is refused with overwrite = true, and keeps them
   (faults.overwrite_keeps_foreign_files tests more such folders).
"""
import json
import os
import re
import shutil
import subprocess
import sys


def scene(path, source, end_time=None, overwrite=False):
    text = open(source).read()
    if end_time is not None:
        text, n = re.subn(r'set end time = ([0-9.e-]+)', f'set end time = {end_time}', text)
        assert n == 1, 'the scene must set Simulation/end time once'
    if overwrite:  # into the scene's Output subsection (a second one would be refused)
        assert 'subsection Output\n' in text, 'the scene must have an Output subsection'
        text = text.replace('subsection Output\n', 'subsection Output\n  set overwrite = true\n', 1)
    open(path, 'w').write(text)
    return path


def run(upgrain, prm, folder, expect_ok=True):
    r = subprocess.run([upgrain, '--output', folder, prm], capture_output=True, text=True)
    if expect_ok and r.returncode != 0:
        sys.exit(f'upgrain failed on {prm} ({r.returncode}): {r.stderr}')
    return r


def files(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder) for d, _, names in os.walk(folder) for f in names)


def strict_json(path):
    def refuse(constant):
        raise ValueError(f'{path}: {constant} is not JSON')
    return json.load(open(path), parse_constant=refuse)


def main():
    upgrain, source, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    end = float(re.search(r'set end time = ([0-9.e-]+)', open(source).read()).group(1))
    out, fresh = os.path.join(work, 'out'), os.path.join(work, 'fresh')
    run(upgrain, scene(os.path.join(work, 'long.prm'), source, 2 * end), out)
    long_files = files(out)
    short = scene(os.path.join(work, 'short.prm'), source, overwrite=True)
    run(upgrain, short, out)
    run(upgrain, short, fresh)
    got, want = files(out), files(fresh)
    if got != want:
        sys.exit(f'after overwrite the folder holds {len(got)} files, a fresh run {len(want)}; '
                 f'left from the earlier run: {sorted(set(got) - set(want))[:10]}')
    if len(long_files) <= len(want):
        sys.exit('the longer run wrote no more files than the shorter: the check would not see a mix')
    rows = [l for l in open(os.path.join(out, 'time_series.csv')) if l[:1].isdigit()]
    if abs(float(rows[-1].split(',')[0]) - end) > 1e-9:
        sys.exit(f'time_series.csv ends at {rows[-1].split(",")[0]} s, not at the end time {end} s')
    pvd = os.path.join(out, 'strain_mesh', 'strain.pvd')
    if os.path.exists(pvd):
        listed = re.findall(r'file="([^"]+)"', open(pvd).read())
        missing = [f for f in listed if not os.path.exists(os.path.join(out, 'strain_mesh', f))]
        if missing or len(listed) != len([f for f in files(out) if f.startswith('grid_strain' + os.sep)]):
            sys.exit(f'strain.pvd lists {len(listed)} meshes ({missing[:3]} missing) for the run\'s strain files')
    # Without gravity no energy is released: kinetic_to_released has no value (null, not inf).
    still = os.path.join(work, 'no_gravity')
    text = open(os.path.join(work, 'short.prm')).read().replace('set overwrite = true\n', '')
    text = re.sub(r'set end time = [0-9.e-]+', f'set end time = {end / 10}', text)
    open(os.path.join(work, 'no_gravity.prm'), 'w').write(text + 'subsection Effects\n  set gravity acceleration = 0\nend\n')
    run(upgrain, os.path.join(work, 'no_gravity.prm'), still)
    if strict_json(os.path.join(still, 'summary.json')).get('kinetic_to_released', 0) is not None:
        sys.exit('without gravity summary.json must give kinetic_to_released as null')
    checked = 0
    for folder in (out, fresh, still):
        for f in files(folder):
            if f.endswith('.json'):
                strict_json(os.path.join(folder, f))
                checked += 1
    # A folder of someone's own files is not a run: overwrite refuses it and leaves them.
    mine = os.path.join(work, 'mine')
    os.makedirs(mine)
    open(os.path.join(mine, 'notes.txt'), 'w').write('my notes\n')
    r = run(upgrain, short, mine, expect_ok=False)
    if r.returncode == 0 or 'no manifest of a run' not in r.stderr or files(mine) != ['notes.txt']:
        sys.exit(f'overwrite of a folder that holds no run was not refused, or touched it: {r.stderr}')
    # Nor is a run's folder that holds the user's scene file: overwrite would remove it.
    shutil.copy(short, os.path.join(out, 'mine.prm'))
    r = run(upgrain, short, out, expect_ok=False)
    if r.returncode == 0 or 'did not write (mine.prm)' not in r.stderr or 'mine.prm' not in files(out):
        sys.exit(f'overwrite of a folder holding a scene file was not refused, or removed it: {r.stderr}')
    print(f'overwrite: {len(long_files)} files of the longer run replaced by the {len(want)} of the new one; '
          f'{checked} JSON files valid')


if __name__ == '__main__':
    main()
