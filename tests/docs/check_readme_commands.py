#!/usr/bin/env python3
"""The README's command blocks work as written, in the order a new user meets them.

Usage: check_readme_commands.py README UPGRAIN TINY_SCENE WORK

- The block of the two set-up commands (scripts/run-default.sh, scripts/test.sh) is not run:
  CI runs scripts/test.sh itself, and the first command's result is what this test starts
  from: a finished run in ./upgrain-output (the tiny scene, where the default study takes
  minutes).
- Every other ```sh block runs line by line, verbatim, through bash in WORK, with
  build/coupling/upgrain a link to the driver under test. Before a line that runs a scene (not
  --help, --check, --print-parameters or --verify), the scene file it names is replaced by the
  tiny scene with the same Output section, so that the line runs in seconds; its own lines are
  unchanged. Each line must exit with 0.
"""
import os
import re
import shutil
import subprocess
import sys


def blocks(readme):
    return re.findall(r'```sh\n(.*?)```', open(readme).read(), re.S)


def commands(block):
    out = []
    for line in block.splitlines():
        code = line.split('#')[0].strip()
        if code:
            out.append(line.strip())
    return out


def main():
    readme, upgrain, tiny, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(work, 'build', 'coupling'))
    os.symlink(os.path.abspath(upgrain), os.path.join(work, 'build', 'coupling', 'upgrain'))
    # What the first command leaves: a finished run in ./upgrain-output.
    r = subprocess.run([upgrain, '--output', 'upgrain-output', os.path.abspath(tiny)], cwd=work,
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f'the run that stands for the first command failed: {r.stderr}')
    ran = 0
    for block in blocks(readme):
        if 'scripts/run-default.sh' in block or 'scripts/test.sh' in block:
            continue
        for line in commands(block):
            runs_scene = not re.search(r'--(help|check|print-parameters|verify)\b', line) and \
                line.split()[0].endswith('upgrain')
            scene = next((w for w in line.split('#')[0].split() if w.endswith('.prm')), None)
            if runs_scene and scene and os.path.exists(os.path.join(work, scene)):
                shutil.copy(tiny, os.path.join(work, scene))
            r = subprocess.run(['bash', '-c', line], cwd=work, capture_output=True, text=True, timeout=900)
            if r.returncode != 0:
                sys.exit(f'README line failed ({r.returncode}): {line}\nstdout: {r.stdout[-2000:]}\n'
                         f'stderr: {r.stderr[-2000:]}')
            ran += 1
            print(f'ok: {line}')
    if ran == 0:
        sys.exit('no README command was run: the blocks were not found')
    print(f'{ran} README commands ran as written')


if __name__ == '__main__':
    main()
