#!/usr/bin/env python3
"""Faults a long run must survive (docs/restart.md, "Faults"): each case injects one into a run
of fault_scene.prm and checks what the run did about it and that nothing was lost.

Usage: run_faults.py UPGRAIN WORK CASE

CASE is one of:
  reference            the scene run once, uninterrupted (WORK/reference); the other cases
                       compare their continued runs with it (a CTest fixture)
  file_size_limit      a checkpoint write fails (RLIMIT_FSIZE between the largest other file
                       and a checkpoint, SIGXFSZ ignored, so write() fails with EFBIG)
  disk_full            the output folder on a small tmpfs, filled up during the run (ENOSPC);
                       skipped (exit 77) where tmpfs cannot be mounted
  read_only_folder     the output folder's parent is a read-only bind mount; skipped (77)
                       where that cannot be mounted
  corrupt_checkpoint   a byte in the middle of the newest checkpoint flipped
  truncated_checkpoint the newest checkpoint cut to half its length
  other_scene          upgrain --restart DIR other.prm, other.prm another scene
  rank_killed          one of three ranks killed by SIGKILL under mpiexec
  sigint               SIGINT to a run of one process
  sighup_one_rank      SIGHUP to one of two ranks under mpiexec
  sigint_during_calibration
                       SIGINT to a study (tests/end_to_end/tiny_study.prm) while it calibrates
                       its continua on the bed: exit 130, a message that says where it stopped
                       and what it left, the DEM output whole, no report

After a write failure the run must stop with exit 1 and an error naming the file, leave no
file under a final name that does not read (every .h5 opens, checkpoints pass their checksum
through a restart), keep the previous checkpoint, and `upgrain --restart` must continue once
the fault is gone and end with the bytes of the uninterrupted run (compare_rank_outputs.py).
"""
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, 'fault_scene.prm')
COMPARE = os.path.join(HERE, '..', 'end_to_end', 'compare_rank_outputs.py')
SKIP = 77
END_TIME = 0.04  # fault_scene.prm's
CHECKPOINT = re.compile(r'checkpoint_(\d+)\.h5$')


def reference_of(work):
    """The uninterrupted run's folder (case reference), beside each case's work folder."""
    return os.path.join(os.path.dirname(work), 'reference', 'run')


def fail(message):
    sys.exit('FAILED: ' + message)


def scene_until(work, end_time):
    """fault_scene.prm with another end time (what a restart may change)."""
    text = open(SCENE).read()
    text, n = re.subn(r'set end time = [0-9.e-]+', f'set end time = {end_time}', text)
    if n != 1:
        fail('fault_scene.prm has no single end time')
    path = os.path.join(work, f'scene_until_{end_time}.prm')
    open(path, 'w').write(text)
    return path


def mpi(ranks, args):
    return (['mpiexec', '-n', str(ranks)] if ranks > 1 else []) + args


def run(cmd, log, timeout=120, **kw):
    with open(log, 'a') as out:
        out.write('$ ' + ' '.join(cmd) + '\n')
        out.flush()
        r = subprocess.run(cmd, stdout=out, stderr=subprocess.PIPE, timeout=timeout, text=True, **kw)
        out.write(r.stderr)
    return r


def checkpoints(folder):
    d = os.path.join(folder, 'checkpoints')
    found = [f for f in os.listdir(d) if CHECKPOINT.match(f)] if os.path.isdir(d) else []
    return sorted(found, key=lambda f: int(CHECKPOINT.match(f).group(1)))


def check_files_whole(folder, temporary_allowed=False):
    """Every file under a final name reads: HDF5 files open and list, JSON parses, and no
    temporary file is left (unless a process was killed: a restart removes them)."""
    import h5py
    import json
    for root, _, names in os.walk(folder):
        for n in names:
            path = os.path.join(root, n)
            if '.tmp.' in n:
                if not temporary_allowed:
                    fail(f'temporary file left behind: {path}')
                continue
            if n.endswith('.h5'):
                try:
                    with h5py.File(path, 'r') as f:
                        f.visit(lambda name: None)
                except Exception as e:  # noqa: BLE001 - any failure to read is the finding
                    fail(f'{path} is under its final name but does not read: {e}')
            if n.endswith('.json'):
                json.load(open(path))


def same_as_reference(upgrain, work, folder, log, ranks=1):
    # Checkpoints differ by design (the end time in their scene, a signal's extra one), and on
    # another rank count so do the compute grids (compare_rank_outputs.py).
    options = ['--other-blocks'] if ranks > 1 else ['--no-checkpoints', '--meshes']
    r = subprocess.run([sys.executable, COMPARE] + options + [reference_of(work), folder],
                       capture_output=True, text=True)
    if r.returncode != 0:
        fail(f'the continued run differs from the uninterrupted one:\n{r.stdout}{r.stderr}')
    print(r.stdout.strip().splitlines()[-1] if r.stdout.strip() else 'same bytes as the uninterrupted run')


def restart_to_end(upgrain, work, folder, log, ranks=1):
    r = run(mpi(ranks, [upgrain, '--restart', folder, scene_until(work, END_TIME)]), log)
    if r.returncode != 0:
        fail(f'the restart after the fault failed ({r.returncode}): {r.stderr.strip()}')
    return r


def first_half(upgrain, work, folder, log):
    """The scene to 0.02 s: checkpoints at 0.01 and 0.02 s."""
    r = run([upgrain, '--output', folder, scene_until(work, END_TIME / 2)], log)
    if r.returncode != 0:
        fail(f'the first half failed ({r.returncode}): {r.stderr.strip()}')
    return checkpoints(folder)


def write_failure(upgrain, work, log, folder, preexec, expect_file):
    """The second half under a write fault: exit 1, the file named, the earlier checkpoints
    kept and whole."""
    before = first_half(upgrain, work, folder, log)
    r = run([upgrain, '--restart', folder, scene_until(work, END_TIME)], log, preexec_fn=preexec)
    print(f'under the fault: exit {r.returncode}: {r.stderr.strip()}')
    if r.returncode != 1:
        fail(f'a run whose write fails must exit with 1, not {r.returncode}')
    named = re.search(r'cannot (write|append to|create folder|rename) (\S+)', r.stderr)
    if not named or not expect_file.search(named.group(2)):
        fail(f'the error does not name the file that could not be written: {r.stderr.strip()}')
    if len(r.stderr.strip().splitlines()) != 1:
        fail('the error is not one line')
    failed = os.path.basename(named.group(2).rstrip(':'))
    for name in checkpoints(folder):
        if name not in before:
            fail(f'{name} got its final name although its write failed' if name == failed else
                 f'a checkpoint written under the fault survived: {name}')
    if [c for c in before if c not in checkpoints(folder)]:
        fail('an earlier checkpoint was lost')
    if os.path.exists(os.path.join(os.path.dirname(named.group(2)), failed)) and failed.endswith('.h5'):
        fail(f'{failed}, whose write failed, is under its final name')
    check_files_whole(folder)
    return named.group(2)


def case_file_size_limit(upgrain, work, log):
    # The limit lies between every other file of the run and a checkpoint, so the first file to
    # fail is the next checkpoint.
    ref = reference_of(work)
    sizes = {}
    for root, _, names in os.walk(ref):
        for n in names:
            if not n.endswith(('.png', '.md', '.log', '.vtu', '.pvtu', '.pvd')):
                sizes[os.path.relpath(os.path.join(root, n), ref)] = os.path.getsize(os.path.join(root, n))
    ckpt = min(s for f, s in sizes.items() if CHECKPOINT.search(f))
    other = max(s for f, s in sizes.items() if not CHECKPOINT.search(f))
    if other >= ckpt:
        fail(f'the scene cannot single out a checkpoint: its largest other file has {other} bytes, '
             f'a checkpoint {ckpt}')
    limit = (other + ckpt) // 2

    def limited():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # write() then fails with EFBIG
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    folder = os.path.join(work, 'run')
    write_failure(upgrain, work, log, folder, limited, re.compile(r'checkpoint_0*3000\.h5'))
    restart_to_end(upgrain, work, folder, log)
    same_as_reference(upgrain, work, folder, log)


def mount(args):
    return subprocess.run(['mount'] + args, capture_output=True, text=True).returncode == 0


def case_disk_full(upgrain, work, log):
    disk = os.path.join(work, 'disk')
    os.makedirs(disk)
    if not mount(['-t', 'tmpfs', '-o', 'size=16m', 'tmpfs', disk]):
        print('tmpfs cannot be mounted here: skipped')
        sys.exit(SKIP)
    try:
        folder = os.path.join(disk, 'run')
        filler = os.path.join(disk, 'filler')
        before = first_half(upgrain, work, folder, log)

        def full():
            # All but 64 kB taken: the second half fails at its first larger write.
            st = os.statvfs(disk)
            with open(filler, 'wb') as f:
                f.write(b'\0' * max(0, st.f_bavail * st.f_frsize - 65536))

        full()
        r = run([upgrain, '--restart', folder, scene_until(work, END_TIME)], log)
        print(f'disk full: exit {r.returncode}: {r.stderr.strip()}')
        if r.returncode != 1:
            fail(f'a run on a full disk must exit with 1, not {r.returncode}')
        if not re.search(r'cannot (write|append to|rename) ' + re.escape(folder), r.stderr):
            fail(f'the error does not name the file: {r.stderr.strip()}')
        if [c for c in before if c not in checkpoints(folder)]:
            fail('an earlier checkpoint was lost')
        check_files_whole(folder)
        os.remove(filler)  # space is back
        restart_to_end(upgrain, work, folder, log)
        same_as_reference(upgrain, work, folder, log)
    finally:
        subprocess.run(['umount', disk])


def case_read_only_folder(upgrain, work, log):
    parent = os.path.join(work, 'read_only')
    os.makedirs(parent)
    if not (mount(['--bind', parent, parent]) and mount(['-o', 'remount,bind,ro', parent])):
        print('a read-only bind mount cannot be made here: skipped')
        subprocess.run(['umount', parent], capture_output=True)
        sys.exit(SKIP)
    try:
        folder = os.path.join(parent, 'run')
        r = run([upgrain, '--output', folder, SCENE], log)
        print(f'read-only parent: exit {r.returncode}: {r.stderr.strip()}')
        if r.returncode != 1 or 'Read-only file system' not in r.stderr or folder not in r.stderr:
            fail('a folder that cannot be created must be refused, naming it and why')
    finally:
        subprocess.run(['umount', parent])


def damaged_checkpoint(upgrain, work, log, damage, reason):
    folder = os.path.join(work, 'run')
    shutil.copytree(reference_of(work), folder)
    names = checkpoints(folder)
    newest = os.path.join(folder, 'checkpoints', names[-1])
    damage(newest)
    r = run([upgrain, '--restart', folder], log)
    out = open(log).read()
    if r.returncode != 0:
        fail(f'the restart failed ({r.returncode}): {r.stderr.strip()}')
    if not re.search(r'refused checkpoint .*' + re.escape(names[-1]) + '.*' + reason, out):
        fail(f'the damaged checkpoint {names[-1]} was not refused with "{reason}"')
    if f'resuming from {os.path.join(folder, "checkpoints", names[-2])}' not in out:
        fail(f'the run did not resume from the next older checkpoint {names[-2]}')
    same_as_reference(upgrain, work, folder, log)


def case_corrupt_checkpoint(upgrain, work, log):
    def flip(path):
        with open(path, 'r+b') as f:
            f.seek(os.path.getsize(path) // 2)
            b = f.read(1)
            f.seek(-1, 1)
            f.write(bytes([b[0] ^ 0x10]))

    damaged_checkpoint(upgrain, work, log, flip, 'do not match its checksum')


def case_truncated_checkpoint(upgrain, work, log):
    damaged_checkpoint(upgrain, work, log, lambda path: os.truncate(path, os.path.getsize(path) // 2),
                       'do not match its checksum')


def case_other_scene(upgrain, work, log):
    folder = os.path.join(work, 'run')
    shutil.copytree(reference_of(work), folder)
    other = scene_until(work, END_TIME)
    text = open(other).read().replace('set count = 150', 'set count = 160')
    text = text.replace('set youngs modulus = 5e7', 'set youngs modulus = 6e7')
    open(other, 'w').write(text)
    r = run([upgrain, '--restart', folder, other], log)
    print(f'other scene: exit {r.returncode}: {r.stderr.strip()}')
    if r.returncode != 1:
        fail(f'a restart with another scene must be refused, exit {r.returncode}')
    for entry in ("Particles/count: '150' -> '160'", "Particles/youngs modulus: '5e7' -> '6e7'"):
        if entry not in r.stderr:
            fail(f'the refusal does not name {entry}')
    if other not in r.stderr:
        fail('the refusal does not name the scene file')


def started(proc, folder, timeout=60):
    """Waits until the run has written its first checkpoint (so it is well under way)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if checkpoints(folder):
            return
        if proc.poll() is not None:
            fail(f'the run ended ({proc.returncode}) before it could be interrupted')
        time.sleep(0.02)
    fail('the run wrote no checkpoint in time')


def ranks_of(launcher):
    """The upgrain processes under an mpiexec (its children's children included)."""
    out = subprocess.run(['ps', '-eo', 'pid,ppid,comm'], capture_output=True, text=True).stdout.split('\n')[1:]
    rows = [l.split() for l in out if l.strip()]
    children = {}
    for pid, ppid, comm in rows:
        children.setdefault(int(ppid), []).append((int(pid), comm))
    found, todo = [], [launcher]
    while todo:
        for pid, comm in children.get(todo.pop(), []):
            todo.append(pid)
            if comm == 'upgrain':
                found.append(pid)
    return sorted(found)


def long_scene(work):
    """The scene 25 times as long, so that a signal finds it running."""
    return scene_until(work, 1.0)


def case_rank_killed(upgrain, work, log):
    folder = os.path.join(work, 'run')
    with open(log, 'a') as out:
        proc = subprocess.Popen(mpi(3, [upgrain, '--output', folder, long_scene(work)]), stdout=out,
                                stderr=out, start_new_session=True)
    started(proc, folder)
    ranks = ranks_of(proc.pid)
    if len(ranks) != 3:
        os.killpg(proc.pid, signal.SIGKILL)
        fail(f'expected 3 ranks, found {ranks}')
    os.kill(ranks[1], signal.SIGKILL)
    t0 = time.monotonic()
    try:
        code = proc.wait(timeout=30)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        fail('the other ranks did not stop within 30 s of one being killed (a hang)')
    ended = time.monotonic() - t0

    def running():
        alive = []
        for p in ranks:
            try:
                with open(f'/proc/{p}/stat') as f:
                    if f.read().split()[2] != 'Z':
                        alive.append(p)
            except OSError:
                pass
        return alive

    # mpiexec signals the other ranks as it ends; on a loaded machine they may take a moment
    # to go. Ten seconds is far beyond that and far below a hang.
    left = running()
    while left and time.monotonic() - t0 < ended + 10.0:
        time.sleep(0.1)
        left = running()
    print(f'one rank killed: mpiexec ended after {ended:.1f} s with {code}; every rank gone '
          f'{time.monotonic() - t0:.1f} s after the kill' if not left else
          f'one rank killed: mpiexec ended after {ended:.1f} s with {code}')
    if code == 0:
        fail('mpiexec reported success although a rank was killed')
    if left:
        fail(f'ranks still running: {left}')
    check_files_whole(folder, temporary_allowed=True)


def stop_by_signal(upgrain, work, log, ranks, sig, target):
    folder = os.path.join(work, 'run')
    with open(log, 'a') as out:
        proc = subprocess.Popen(mpi(ranks, [upgrain, '--output', folder, scene_until(work, END_TIME)]),
                                stdout=out, stderr=subprocess.PIPE, text=True, start_new_session=True)
    started(proc, folder)
    pids = [proc.pid] if ranks == 1 else ranks_of(proc.pid)
    os.kill(pids[target], sig)
    try:
        _, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        fail('the run did not stop within 60 s of the signal')
    open(log, 'a').write(err)
    out = open(log).read()
    print(f'{signal.Signals(sig).name} to rank {target} of {ranks}: exit {proc.returncode}')
    if proc.returncode == 0 and 'done:' in out and 'stopped by signal' not in out:
        print('the run ended before the signal took effect: nothing to check')
        return folder
    if proc.returncode != 128 + sig:
        fail(f'a run stopped by {signal.Signals(sig).name} must exit with {128 + sig}, not {proc.returncode}')
    if f'stopped by signal {int(sig)}' not in out or 'continue with: upgrain --restart' not in out:
        fail('the run did not say that it stopped, with its checkpoint and how to continue')
    if err.count('error') > 0:
        fail(f'a stop on request is no error: {err.strip()}')
    check_files_whole(folder)
    restart_to_end(upgrain, work, folder, log, ranks)
    same_as_reference(upgrain, work, folder, log, ranks)
    return folder


def case_sigint(upgrain, work, log):
    stop_by_signal(upgrain, work, log, 1, signal.SIGINT, 0)


def case_sighup_one_rank(upgrain, work, log):
    stop_by_signal(upgrain, work, log, 2, signal.SIGHUP, 1)


def case_sigint_during_calibration(upgrain, work, log):
    scene = os.path.join(HERE, '..', 'end_to_end', 'tiny_study.prm')
    folder = os.path.join(work, 'run')
    out_path = os.path.join(work, 'study.log')
    with open(out_path, 'w') as out:
        proc = subprocess.Popen([upgrain, '--output', folder, scene], stdout=out, stderr=subprocess.PIPE,
                                text=True, start_new_session=True)
    end = time.monotonic() + 120
    while 'calibration of the continua on this bed' not in open(out_path).read():
        if proc.poll() is not None or time.monotonic() > end:
            os.killpg(proc.pid, signal.SIGKILL)
            fail(f'the study did not reach its calibration ({proc.returncode})')
        time.sleep(0.05)
    time.sleep(0.5)
    os.kill(proc.pid, signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        fail('the study did not stop within 60 s of the signal')
    text = open(out_path).read()
    open(log, 'a').write(text + err)
    if proc.returncode != 128 + signal.SIGINT:
        fail(f'a study stopped by SIGINT must exit with {128 + signal.SIGINT}, not {proc.returncode}: {err.strip()}')
    if 'during the calibration of the continua' not in text or 'run the study again' not in text:
        fail('the study did not say that it stopped in its calibration, and what to do')
    if err.count('error') > 0:
        fail(f'a stop on request is no error: {err.strip()}')
    for name in ('summary.json', 'grid_stress.csv', 'time_series.csv'):
        if not os.path.exists(os.path.join(folder, name)):
            fail(f'the DEM output lost {name}')
    for name in ('report.md', 'study.json', 'calibration/material.prm'):
        if os.path.exists(os.path.join(folder, name)):
            fail(f'{name} written by a study stopped before its continua')
    check_files_whole(folder)
    print('SIGINT during the calibration: exit 130, DEM output whole, no report')


def case_reference(upgrain, work, log):
    folder = reference_of(work)
    r = run([upgrain, '--output', folder, SCENE], log)
    if r.returncode != 0:
        fail(f'the uninterrupted run failed ({r.returncode}): {r.stderr.strip()}')
    check_files_whole(folder)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    upgrain, work, case = sys.argv[1:]
    work = os.path.abspath(os.path.join(work, case))
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    log = os.path.join(work, 'runs.log')
    globals()['case_' + case](upgrain, work, log)
    print(f'{case}: passed')


if __name__ == '__main__':
    main()
