#!/usr/bin/env python3
"""Nothing a user wrote is lost, and no two runs mix (docs/output.md, "Manifest", "Lock";
docs/restart.md).

Usage: check_output_safety.py CASE UPGRAIN SCENE WORK

SCENE is a tiny scene with checkpoints. Cases:
- overwrite_keeps_foreign_files: a folder with a file named summary.json and someone's thesis/
  is refused by `Output/overwrite = true`, named, and left byte for byte; so is a run's folder
  with foreign files in it and under its subfolders, and one whose report was edited; once they
  are moved out, overwrite replaces the run.
- restart_keeps_foreign_files: files added to a run's folder while it runs (at the top, in
  snapshots/ with a later step's name, a hidden folder named like a staging folder) survive the
  kill -9 of the run, its restart and its end byte for byte; the restart says it left them;
  `upgrain --verify` then names exactly them as extra.
- restart_removes_half_written_mesh: a run killed at the rename that publishes its strain mesh
  (strace) leaves its staging folder; the restart removes it and the folder verifies whole.
- lock_refuses_second_run: while a run lives, a second run into its folder (with overwrite) and
  a restart of it are refused, naming the first's PID and host; after it is killed, the restart
  goes on.
- checkpoint_of_another_run_refused: a checkpoint of another run, put in a run's checkpoints/
  as its newest, is refused by `--restart`, naming both runs; the folder is left as it was.
- verify_names_missing_changed_extra: `upgrain --verify` passes a finished run and names a file
  removed, a file changed and a file added, with exit status 1.
"""
import hashlib
import os
import re
import shutil
import signal
import subprocess
import sys
import time


def fail(message):
    sys.exit(f'check_output_safety: {message}')


def tree(folder):
    """Every file under `folder` (bookkeeping aside) with the hash of its bytes."""
    out = {}
    for root, dirs, names in os.walk(folder):
        rel_root = os.path.relpath(root, folder)
        if rel_root.split(os.sep)[0] == '.upgrain':
            continue
        for d in dirs:
            out[os.path.normpath(os.path.join(rel_root, d)) + '/'] = 'folder'
        for n in names:
            p = os.path.join(root, n)
            out[os.path.normpath(os.path.join(rel_root, n))] = hashlib.sha256(open(p, 'rb').read()).hexdigest()
    return out


def put(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as f:
        f.write(text)


def scene(path, source, end_time=None, overwrite=False, extra=''):
    text = open(source).read()
    if end_time is not None:
        text, n = re.subn(r'set end time = ([0-9.e-]+)', f'set end time = {end_time}', text)
        assert n == 1
    if overwrite:
        text = text.replace('subsection Output\n', 'subsection Output\n  set overwrite = true\n', 1)
    put(path, text + extra)
    return path


def upgrain_run(upgrain, args, expect_ok=True):
    r = subprocess.run([upgrain] + args, capture_output=True, text=True, timeout=600)
    if expect_ok and r.returncode != 0:
        fail(f'upgrain {" ".join(args)} failed ({r.returncode}): {r.stderr}')
    return r


def wait_for(condition, what, limit=120.0):
    t0 = time.monotonic()
    while not condition():
        if time.monotonic() - t0 > limit:
            fail(f'timed out waiting for {what}')
        time.sleep(0.05)


def has_checkpoint(folder):
    d = os.path.join(folder, 'checkpoints')
    return os.path.isdir(d) and any(f.endswith('.h5') and '.tmp.' not in f for f in os.listdir(d))


def start_and_kill(upgrain, prm, folder, after_checkpoint=True, before_kill=None):
    """Starts a run into `folder`, waits for a checkpoint, runs `before_kill`, then SIGKILLs it."""
    p = subprocess.Popen([upgrain, '--output', folder, prm], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wait_for(lambda: has_checkpoint(folder) or p.poll() is not None, 'a checkpoint')
    if p.poll() is not None:
        fail(f'the run ended before it could be killed ({p.returncode}): make the scene longer')
    if before_kill:
        before_kill(p)
    p.send_signal(signal.SIGKILL)
    p.wait()
    return p


def case_overwrite_keeps_foreign_files(upgrain, source, work):
    short = scene(os.path.join(work, 'short.prm'), source, overwrite=True)
    # The probe's folder: a summary.json and a thesis, no run.
    probe = os.path.join(work, 'p')
    put(os.path.join(probe, 'thesis', 'a.tex'), 'x\n')
    put(os.path.join(probe, 'summary.json'), '{}\n')
    before = tree(probe)
    r = upgrain_run(upgrain, ['--output', probe, short], expect_ok=False)
    if r.returncode == 0 or 'no manifest of a run' not in r.stderr:
        fail(f'overwrite of a folder with summary.json and thesis/ was not refused: {r.returncode} {r.stderr}')
    if tree(probe) != before:
        fail('the refused overwrite changed the folder')
    # A run's folder with foreign files at the top and in its subfolders, and an edited report.
    out = os.path.join(work, 'out')
    upgrain_run(upgrain, ['--output', out, short])
    mine = {os.path.join(out, 'notes.txt'): 'my notes\n',
            os.path.join(out, 'snapshots', 'particles_999999999.h5'): 'not a snapshot\n',
            os.path.join(out, 'mine.prm'): '# my scene\n'}
    for path, text in mine.items():
        put(path, text)
    before = tree(out)
    r = upgrain_run(upgrain, ['--output', out, short], expect_ok=False)
    for name in ('notes.txt', 'snapshots/particles_999999999.h5', 'mine.prm'):
        if name not in r.stderr:
            fail(f'the refusal does not name {name}: {r.stderr}')
    if r.returncode == 0 or tree(out) != before:
        fail(f'overwrite of a run with foreign files was not refused, or changed the folder: {r.stderr}')
    for path in mine:
        os.remove(path)
    with open(os.path.join(out, 'report.md'), 'a') as f:
        f.write('my comment\n')
    before = tree(out)
    r = upgrain_run(upgrain, ['--output', out, short], expect_ok=False)
    if r.returncode == 0 or 'report.md' not in r.stderr or 'changed since' not in r.stderr or tree(out) != before:
        fail(f'overwrite of a run with an edited report was not refused, or changed the folder: {r.stderr}')
    os.remove(os.path.join(out, 'report.md'))
    upgrain_run(upgrain, ['--output', out, short])
    v = upgrain_run(upgrain, ['--verify', out])
    print(f'overwrite refused three times with the paths named, then replaced the run: {v.stdout.splitlines()[-1]}')


def case_restart_keeps_foreign_files(upgrain, source, work):
    prm = scene(os.path.join(work, 'run.prm'), source)
    out = os.path.join(work, 'out')
    foreign = {os.path.join(out, 'notes.txt'): 'my notes\n',
               os.path.join(out, 'snapshots', 'particles_999999999.h5'): 'a file named like a later snapshot\n',
               os.path.join(out, 'strain_mesh', '.strain_1.tmp.1', 'keep.txt'): 'named like a staging folder\n',
               os.path.join(out, 'checkpoints', 'readme.txt'): 'mine\n'}

    def add_foreign(_):
        for path, text in foreign.items():
            put(path, text)

    start_and_kill(upgrain, prm, out, before_kill=add_foreign)
    want = {k: v for k, v in tree(out).items() if any(k == os.path.relpath(p, out) for p in foreign)}
    r = upgrain_run(upgrain, ['--restart', out])
    if 'left alone, not written by the run' not in r.stdout:
        fail(f'the restart did not say which files it left alone:\n{r.stdout}')
    got = tree(out)
    for rel, digest in want.items():
        if got.get(rel) != digest:
            fail(f'{rel} was removed or changed by the restart')
    v = upgrain_run(upgrain, ['--verify', out], expect_ok=False)
    extra = re.search(r'(\d+) extra', v.stdout)
    if v.returncode != 1 or not extra or int(extra.group(1)) != 4 or 'missing' in v.stdout or 'changed' in v.stdout:
        fail(f'--verify after the restart should name exactly the 4 foreign paths as extra:\n{v.stdout}')
    for path in foreign:
        os.remove(path)
    shutil.rmtree(os.path.join(out, 'strain_mesh', '.strain_1.tmp.1'))
    upgrain_run(upgrain, ['--verify', out])
    print(f'{len(foreign)} foreign files kept through a kill -9 and a restart; the folder verifies whole without them')


def case_restart_removes_half_written_mesh(upgrain, source, work):
    prm = scene(os.path.join(work, 'run.prm'), source)
    ref = os.path.join(work, 'ref')
    # Which rename publishes the strain mesh: strace counts each thread's calls apart, so the
    # number is that of the thread's renames up to the first that moves a piece out of its
    # staging folder.
    trace = os.path.join(work, 'trace.txt')
    subprocess.run(['strace', '-f', '-qq', '-e', 'trace=rename', '-o', trace, upgrain, '--output', ref, prm],
                   capture_output=True, check=True)
    calls = [l.split(None, 1) for l in open(trace) if 'rename(' in l and 'resumed' not in l]
    hit = next((k for k, (_, call) in enumerate(calls) if re.search(r'\.strain_\d+\.tmp\.\d+/strain_', call)), None)
    if hit is None:
        fail('no rename of a strain-mesh piece in the run: the scene must enable Strain')
    tid = calls[hit][0]
    at = sum(1 for t, _ in calls[:hit + 1] if t == tid)
    out = os.path.join(work, 'out')
    subprocess.run(['strace', '-f', '-qq', '-o', '/dev/null', '-e', 'trace=rename', '-e',
                    f'inject=rename:signal=SIGKILL:when={at}', upgrain, '--output', out, prm], capture_output=True)
    staged = [os.path.join(d, n) for d, dirs, _ in os.walk(out) for n in dirs if '.tmp.' in n]
    if not staged:
        fail('the kill at the mesh rename left no staging folder: the case tests nothing')
    upgrain_run(upgrain, ['--restart', out])
    left = [os.path.join(d, n) for d, dirs, files in os.walk(out) for n in dirs + files if '.tmp.' in n]
    if left:
        fail(f'the restart left temporary paths: {left}')
    upgrain_run(upgrain, ['--verify', out])
    print(f'killed at rename {at} of its thread (the strain mesh), left {staged}; the restart removed it')


def case_lock_refuses_second_run(upgrain, source, work):
    end = float(re.search(r'set end time = ([0-9.e-]+)', open(source).read()).group(1))
    long_prm = scene(os.path.join(work, 'long.prm'), source, end_time=40 * end)
    second = scene(os.path.join(work, 'second.prm'), source, overwrite=True)
    out = os.path.join(work, 'out')

    def second_runs(p):
        for args in (['--output', out, second], ['--restart', out]):
            r = upgrain_run(upgrain, args, expect_ok=False)
            if r.returncode == 0 or f'in use by another run of upgrain (PID {p.pid} on host' not in r.stderr:
                fail(f'upgrain {" ".join(args)} was not refused with the first run\'s PID {p.pid}: {r.stderr}')
        if p.poll() is not None:
            fail('the first run ended while the second was refused: the case tests nothing')

    first = start_and_kill(upgrain, long_prm, out, before_kill=second_runs)
    # Once the first is dead, its folder is free: the restart resumes (and is stopped by SIGTERM).
    log = os.path.join(work, 'restart.log')
    with open(log, 'w') as f:
        p = subprocess.Popen([upgrain, '--restart', out], stdout=f, stderr=subprocess.STDOUT)
        wait_for(lambda: 'resuming from' in open(log).read() or p.poll() is not None, 'the restart')
        p.send_signal(signal.SIGTERM)
        p.wait(timeout=300)
    text = open(log).read()
    if 'in use' in text or 'resuming from' not in text:
        fail(f'the restart after the first run died did not resume:\n{text}')
    print(f'a second run and a restart refused while PID {first.pid} lived; a restart resumed once it was dead')


def case_checkpoint_of_another_run_refused(upgrain, source, work):
    a_prm = scene(os.path.join(work, 'a.prm'), source)
    b_prm = scene(os.path.join(work, 'b.prm'), source)
    text = open(b_prm).read()  # another scene: another fill
    put(b_prm, text.replace('subsection Fill\n', 'subsection Fill\n  set seed = 7\n', 1) if 'subsection Fill\n' in text
        else text + 'subsection Fill\n  set seed = 7\nend\n')
    a, b = os.path.join(work, 'a'), os.path.join(work, 'b')
    upgrain_run(upgrain, ['--output', a, a_prm])
    start_and_kill(upgrain, b_prm, b)
    newest = sorted(f for f in os.listdir(os.path.join(a, 'checkpoints')) if f.endswith('.h5'))[-1]
    shutil.copy(os.path.join(a, 'checkpoints', newest), os.path.join(b, 'checkpoints', 'checkpoint_999999999.h5'))
    before = tree(b)
    r = upgrain_run(upgrain, ['--restart', b], expect_ok=False)
    ids = re.findall(r'run (\S+-\d+-[0-9a-f]{8})', r.stderr)
    if r.returncode == 0 or 'checkpoint_999999999.h5' not in r.stderr or len(set(ids)) != 2:
        fail(f'a checkpoint of another run was not refused naming both runs: {r.stderr}')
    if tree(b) != before:
        fail('the refused restart changed the folder')
    print(f'refused: {r.stderr.strip().splitlines()[-1][:200]}')


def case_verify_names_missing_changed_extra(upgrain, source, work):
    prm = scene(os.path.join(work, 'run.prm'), source)
    out = os.path.join(work, 'out')
    upgrain_run(upgrain, ['--output', out, prm])
    v = upgrain_run(upgrain, ['--verify', out])
    if 'every listed file is present' not in v.stdout:
        fail(f'--verify of a finished run: {v.stdout}')
    os.remove(os.path.join(out, 'summary.json'))
    with open(os.path.join(out, 'time_series.csv'), 'a') as f:
        f.write('1,2,3\n')
    put(os.path.join(out, 'snapshots', 'extra.txt'), 'x')
    v = upgrain_run(upgrain, ['--verify', out], expect_ok=False)
    want = [r'1 missing[^\n]*\n\s+summary.json', r'1 changed[^\n]*\n\s+time_series.csv', r'1 extra[^\n]*\n\s+snapshots/extra.txt']
    if v.returncode != 1 or not all(re.search(w, v.stdout) for w in want):
        fail(f'--verify did not name the missing, changed and extra files (exit {v.returncode}):\n{v.stdout}')
    r = upgrain_run(upgrain, ['--verify', os.path.join(work, 'nothing')], expect_ok=False)
    if r.returncode == 0 or 'manifest' not in r.stderr:
        fail(f'--verify of a folder without a manifest: {r.returncode} {r.stderr}')
    print('--verify: ' + ' | '.join(l.strip() for l in v.stdout.splitlines()))


def main():
    case, upgrain, source, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    globals()['case_' + case](os.path.abspath(upgrain), os.path.abspath(source), os.path.abspath(work))


if __name__ == '__main__':
    main()
