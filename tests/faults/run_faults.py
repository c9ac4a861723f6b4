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
  restart_from_final_checkpoint
                       upgrain --restart on the finished reference run, and on a copy without
                       its end (report, summary, strain mesh, plots: killed while it wrote them):
                       each continues from the checkpoint before the last step and writes the
                       reference's files, report.md and summary.json included
  end_time_before_checkpoint
                       upgrain --restart DIR shorter.prm with an end time before the newest
                       checkpoint: exit 1, one line naming the file, the entry and the
                       checkpoint's time, the folder unchanged
  wall_time_of_all_segments
                       a run to 0.02 s continued to 0.04 s: summary.json and report.md give the
                       time of both segments and the step it was resumed at
  sigint_during_final_writing
                       SIGINT once the run has written summary.json, while it writes its strain
                       mesh, plots and report: they are finished, exit 130 with a message
  sigint_during_relaxation
                       SIGINT to a run that relaxes at its end, during the relaxation: exit 130,
                       the checkpoint to continue from named; the restart relaxes again and ends
                       with the bytes of an uninterrupted run

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


def same_as_reference(upgrain, work, folder, log, ranks=1, reference=None):
    # Checkpoints differ by design (the end time in their scene, a signal's extra one), and on
    # another rank count so do the compute grids (compare_rank_outputs.py).
    options = ['--report'] + (['--other-blocks'] if ranks > 1 else ['--no-checkpoints', '--meshes'])
    r = subprocess.run([sys.executable, COMPARE] + options + [reference or reference_of(work), folder],
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


def tree(folder):
    """Every file of `folder` with its size, modification time and bytes' hash."""
    import hashlib
    out = {}
    for root, _, names in os.walk(folder):
        for n in names:
            path = os.path.join(root, n)
            st = os.stat(path)
            out[os.path.relpath(path, folder)] = (st.st_size, st.st_mtime_ns,
                                                  hashlib.sha256(open(path, 'rb').read()).hexdigest())
    return out


def log_of(log, command):
    """Runs `command` appending to `log`, and returns it with its own part of the log."""
    start = os.path.getsize(log) if os.path.exists(log) else 0
    r = run(command, log)
    with open(log) as f:
        f.seek(start)
        return r, f.read()


def case_restart_from_final_checkpoint(upgrain, work, log):
    ref = reference_of(work)
    names = checkpoints(ref)
    last = int(CHECKPOINT.match(names[-1]).group(1))
    if last != round(END_TIME / 1e-5):
        fail(f'the reference run has no checkpoint at its last step: {names}')
    scene_line = [l for l in open(os.path.join(ref, 'report.md')) if l.startswith('Scene: ')]
    lost_end = ['report.md', 'summary.json', 'strain_mesh', 'strain_ln_J.png', 'strain_shear.png',
                'strain_final_map.png', 'strain_plots.log']
    for name, lost in (('finished', []), ('killed_at_its_end', lost_end)):
        folder = os.path.join(work, name)
        shutil.copytree(ref, folder)
        for f in lost:
            path = os.path.join(folder, f)
            shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)
        r, out = log_of(log, [upgrain, '--restart', folder])
        if r.returncode != 0:
            fail(f'{name}: the restart failed ({r.returncode}): {r.stderr.strip()}')
        if f'resuming from {os.path.join(folder, "checkpoints", names[-2])}' not in out:
            fail(f'{name}: the restart did not continue from the checkpoint before the last step, {names[-2]}')
        if not re.search(re.escape(names[-1]) + r' is at the run\'s end step', out):
            fail(f'{name}: the log does not say why {names[-1]} was passed over')
        # The restart's report names the scene the run was started with, not the restart.
        if [l for l in open(os.path.join(folder, 'report.md')) if l.startswith('Scene: ')] != scene_line:
            fail(f'{name}: report.md names another scene than the uninterrupted run\'s: {scene_line}')
        check_files_whole(folder)
        same_as_reference(upgrain, work, folder, log)


def case_end_time_before_checkpoint(upgrain, work, log):
    folder = os.path.join(work, 'run')
    shutil.copytree(reference_of(work), folder)
    before = tree(folder)
    shorter = scene_until(work, 0.025)
    r = run([upgrain, '--restart', folder, shorter], log)
    print(f'end time before the checkpoint: exit {r.returncode}: {r.stderr.strip()}')
    if r.returncode != 1:
        fail(f'an end time before the checkpoint must be refused with exit 1, not {r.returncode}')
    if len(r.stderr.strip().splitlines()) != 1:
        fail('the refusal is not one line')
    for part in (shorter, 'Simulation/end time = 0.025 s', 't = 0.04 s'):
        if part not in r.stderr:
            fail(f'the refusal does not name {part!r}')
    if tree(folder) != before:
        fail('the refused restart changed the folder')


def case_wall_time_of_all_segments(upgrain, work, log):
    import h5py
    import json
    folder = os.path.join(work, 'run')
    first_half(upgrain, work, folder, log)
    with h5py.File(os.path.join(folder, 'checkpoints', 'checkpoint_000002000.h5'), 'r') as f:
        earlier = float(f['run'].attrs.get('wall_seconds', 0.0))
    if not earlier > 0.0:
        fail(f'the checkpoint at the end of the first segment keeps no wall time ({earlier})')
    restart_to_end(upgrain, work, folder, log)
    summary = json.load(open(os.path.join(folder, 'summary.json')))
    if summary['resumed_at_steps'] != [2000]:
        fail(f'summary.json resumed_at_steps is {summary["resumed_at_steps"]}, not [2000]')
    wall, segment = summary['wall_time_s'], summary['segment_wall_time_s']
    # The same two doubles added as the driver adds them: no tolerance.
    if not segment > 0.0 or wall != earlier + segment:
        fail(f'wall_time_s {wall} is not the first segment\'s {earlier} s and the second\'s {segment} s')
    rate = summary['particle_steps_per_second']
    if abs(rate - summary['steps'] * summary['particles'] / wall) > 1e-12 * rate:
        fail(f'particle_steps_per_second {rate} is not over every step and the whole wall time')
    with h5py.File(os.path.join(folder, 'checkpoints', 'checkpoint_000004000.h5'), 'r') as f:
        if list(f['run/resumed_at'][()]) != [2000] or not float(f['run'].attrs['wall_seconds']) > earlier:
            fail('the checkpoint of the second segment does not carry the first one\'s time and resume')
    line = [l for l in open(os.path.join(folder, 'report.md')) if l.startswith('- Wall clock:')]
    if len(line) != 1 or 'over 2 segments' not in line[0] or 'at step 2000' not in line[0]:
        fail(f'report.md does not give the time of both segments and where it resumed: {line}')
    same_as_reference(upgrain, work, folder, log)
    print(f'two segments: {earlier:.3f} + {segment:.3f} s = {wall:.3f} s, resumed at step 2000')


def sigint_when_written(upgrain, scene, folder, path, log):
    """Runs `scene` into `folder` and sends SIGINT once `path` exists: the process, its log and
    its standard error."""
    with open(log, 'a') as out:
        proc = subprocess.Popen([upgrain, '--output', folder, scene], stdout=out, stderr=subprocess.PIPE,
                                text=True, start_new_session=True)
    while not os.path.exists(path) and proc.poll() is None:
        time.sleep(0.002)
    os.kill(proc.pid, signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        fail('the run did not end within 60 s of the signal')
    out = open(log).read()
    open(log, 'a').write(err)
    return proc, out, err


def case_sigint_during_final_writing(upgrain, work, log):
    folder = os.path.join(work, 'run')
    # summary.json is the first file of the run's end; the strain mesh, plots and report follow.
    proc, out, err = sigint_when_written(upgrain, SCENE, folder, os.path.join(folder, 'summary.json'), log)
    print(f'SIGINT while the run wrote its end: exit {proc.returncode}')
    if proc.returncode != 128 + signal.SIGINT:
        fail(f'a signal during the end of a run must not be ignored: exit {proc.returncode}, not 130')
    if 'while the run wrote its results: they were finished first' not in out:
        fail('the run did not say that it finished its results before it stopped')
    if err.strip():
        fail(f'a stop on request is no error: {err.strip()}')
    check_files_whole(folder)
    reference_plots = [f for f in os.listdir(reference_of(work)) if f.endswith('.png')]
    missing = [f for f in reference_plots if not os.path.exists(os.path.join(folder, f))]
    if missing:
        fail(f'the plots the signal reached were not finished: {missing}')
    same_as_reference(upgrain, work, folder, log)


def case_sigint_during_relaxation(upgrain, work, log):
    text = open(SCENE).read().replace('set relax at end = false',
                                      'set relax at end = true\n  set max relaxation steps = 20000')
    scene = os.path.join(work, 'relaxing.prm')
    open(scene, 'w').write(text)
    reference = os.path.join(work, 'reference')
    r = run([upgrain, '--output', reference, scene], log)
    if r.returncode != 0:
        fail(f'the uninterrupted run failed ({r.returncode}): {r.stderr.strip()}')
    folder = os.path.join(work, 'run')
    # The checkpoint of the last step is written just before the relaxation begins.
    last = os.path.join(folder, 'checkpoints', 'checkpoint_000004000.h5')
    proc, out, err = sigint_when_written(upgrain, scene, folder, last, log)
    print(f'SIGINT during the relaxation: exit {proc.returncode}')
    if proc.returncode != 128 + signal.SIGINT:
        fail(f'a run stopped during its relaxation must exit with 130, not {proc.returncode}')
    if 'during the relaxation at the end' not in out or f'checkpoint {last}' not in out or \
       'continue with: upgrain --restart' not in out:
        fail('the run did not say that it stopped in its relaxation, from where and how to continue')
    if os.path.exists(os.path.join(folder, 'summary.json')):
        fail('a run stopped in its relaxation wrote its summary')
    check_files_whole(folder)
    r, out = log_of(log, [upgrain, '--restart', folder])
    if r.returncode != 0:
        fail(f'the restart failed ({r.returncode}): {r.stderr.strip()}')
    if f'resuming from {last}' not in out:
        fail('the restart did not continue from the checkpoint the relaxation began at')
    same_as_reference(upgrain, work, folder, log, reference=reference)


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
