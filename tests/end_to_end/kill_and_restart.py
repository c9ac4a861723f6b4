#!/usr/bin/env python3
"""Kills runs of a scene at random moments, continues each with `upgrain --restart`, and checks
that the continued run wrote the same files as a run that was not interrupted
(docs/restart.md).

Usage: kill_and_restart.py UPGRAIN SCENE WORK [--kills N] [--signal KILL|TERM]
                           [--ranks R] [--restart-ranks R2] [--seed S] [--delays LOW HIGH]
                           [--kill-while-finishing]

1. The scene runs once without interruption (WORK/whole), on R ranks, and its wall time T is
   measured.
2. The same scene runs in WORK/broken; it is sent the signal after a random fraction of T
   (0.1 to 0.8; a restart's LOW to HIGH, 0.1 to 0.5 by default). Each following start is `upgrain --restart WORK/broken` on R2 ranks (R2 = R
   by default), again killed, N times in all; then one last restart runs to the end. A start
   that ends before its signal counts as done.
   With --kill-while-finishing the last restart is killed with SIGKILL once it has written
   its strain on the mesh (strain_mesh/strain.pvd), while it makes its plots and report, and
   the run is restarted once more: a restart of a run that had reached its last step continues
   from the checkpoint before it and writes the run's end again (docs/restart.md).
3. With SIGTERM each stopped run writes a checkpoint and, on one rank, exits with 143 (under
   mpiexec the launcher reports its own code). No temporary file may remain once the last run
   has ended.
4. compare_rank_outputs.py --report compares the two folders: every HDF5, XDMF and CSV file
   byte-identical (the deal.II meshes too when the rank count stays), the checkpoints but the
   run's wall time and resume steps, time_series.csv and summary.json field by field but the
   timings and resume steps, and report.md line by line but its wall-clock line (and, on other
   rank counts, the compute-grid files and the checkpoints, which follow the blocks).
"""
import argparse
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def command(upgrain, ranks, args):
    if ranks <= 1:
        return [upgrain] + args
    return ['mpiexec', '-n', str(ranks), upgrain] + args


def resumed(log_name, offset):
    """Where the start that wrote the log from `offset` on resumed (the driver's stdout is
    line-buffered, so the line is there even when the start was killed)."""
    with open(log_name, errors='replace') as f:
        f.seek(offset)
        m = re.search(r'resuming from \S+ at step (\d+)', f.read())
    return f'resumed at step {m.group(1)}, ' if m else ''


def kill_leftovers(folder, limit=10.0):
    """SIGKILLs every process whose command line names `folder` and waits until none is left."""
    key = folder.encode()  # as it stands on the command lines the script gave
    t0 = time.monotonic()
    while True:
        left = []
        for pid in filter(str.isdigit, os.listdir('/proc')):
            try:
                with open(f'/proc/{pid}/cmdline', 'rb') as f:
                    cmd = f.read()
            except OSError:
                continue
            if int(pid) != os.getpid() and key in cmd:
                left.append(int(pid))
        if not left:
            return
        if time.monotonic() - t0 > limit:
            sys.exit(f'processes of the killed run still alive after {limit} s: {left}')
        for pid in left:
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
        time.sleep(0.05)


def wait_for_checkpoint(proc, folder, limit):
    """The time at which `folder` first holds a checkpoint, or the run ended, or `limit` s passed."""
    t0 = time.monotonic()
    while proc.poll() is None and time.monotonic() - t0 < limit:
        if os.path.isdir(folder) and any(f.endswith('.h5') for f in os.listdir(folder)):
            break
        time.sleep(0.01)
    return time.monotonic()


def main():
    p = argparse.ArgumentParser()
    p.add_argument('upgrain')
    p.add_argument('scene')
    p.add_argument('work')
    p.add_argument('--kills', type=int, default=3)
    p.add_argument('--signal', choices=['KILL', 'TERM'], default='KILL')
    p.add_argument('--ranks', type=int, default=1)
    p.add_argument('--restart-ranks', type=int, default=0)
    p.add_argument('--seed', type=int, default=1)
    p.add_argument('--delays', type=float, nargs=2, default=[0.1, 0.5], metavar=('LOW', 'HIGH'),
                   help="a restart's signal after LOW to HIGH of the uninterrupted run's wall time")
    p.add_argument('--kill-while-finishing', action='store_true',
                   help='kill the last restart while it writes its plots and report, then restart again')
    a = p.parse_args()
    rng = random.Random(a.seed)
    restart_ranks = a.restart_ranks or a.ranks
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    whole = os.path.join(a.work, 'whole')
    broken = os.path.join(a.work, 'broken')
    log = open(os.path.join(a.work, 'runs.log'), 'w')

    t0 = time.monotonic()
    r = subprocess.run(command(a.upgrain, a.ranks, ['--output', whole, a.scene]), stdout=log, stderr=log)
    wall = time.monotonic() - t0
    if r.returncode != 0:
        sys.exit(f'the uninterrupted run failed ({r.returncode}); see {log.name}')
    print(f'uninterrupted run: {wall:.2f} s')

    sig = signal.SIGKILL if a.signal == 'KILL' else signal.SIGTERM
    done = False
    for k in range(a.kills):
        args = ['--output', broken, a.scene] if k == 0 else ['--restart', broken]
        ranks = a.ranks if k == 0 else restart_ranks
        delay = rng.uniform(0.0, 0.5) * wall if k == 0 else rng.uniform(*a.delays) * wall
        log.flush()
        where = log.tell()
        started = time.monotonic()
        proc = subprocess.Popen(command(a.upgrain, ranks, args), stdout=log, stderr=log, start_new_session=True)
        if k == 0:
            # The first start is killed after its first checkpoint (a run killed before it has
            # nothing to continue from, and the start-up time of the ranks varies with the
            # machine's load); then after `delay` more.
            first = wait_for_checkpoint(proc, os.path.join(broken, 'checkpoints'), 4.0 * wall + 30.0)
            delay += first - started
        try:
            code = proc.wait(timeout=max(delay - (time.monotonic() - started), 0.0))
            print(f'start {k + 1}: ended by itself ({code}) before its signal at {delay:.2f} s')
            if code != 0:
                sys.exit(f'start {k + 1} failed with {code}; see {log.name}')
            done = True
            break
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, sig)  # the launcher and every rank
            code = proc.wait()
            if sig == signal.SIGKILL:
                # Ranks that mpiexec started outside its process group outlive a SIGKILL of the
                # launcher for a moment; a batch system kills them too (cgroups). Without this
                # they would append rows beside the restarted run.
                kill_leftovers(broken)
            print(f'start {k + 1}: {resumed(log.name, where)}signal {a.signal} at {delay:.2f} s, exit {code}')
            # One process: 128 + 15. Under mpiexec the launcher reports its own code.
            if sig == signal.SIGTERM and ranks == 1 and code != 143:
                sys.exit(f'a run stopped by SIGTERM must exit with 143, not {code}; see {log.name}')
    if not done and a.kill_while_finishing:
        log.flush()
        where = log.tell()
        # A start killed at random may have reached its end and written strain.pvd: this one's
        # is the one with another modification time.
        mesh = os.path.join(broken, 'strain_mesh', 'strain.pvd')
        stamp = lambda: os.stat(mesh).st_mtime_ns if os.path.exists(mesh) else None  # noqa: E731
        before = stamp()
        proc = subprocess.Popen(command(a.upgrain, restart_ranks, ['--restart', broken]), stdout=log, stderr=log,
                                start_new_session=True)
        while proc.poll() is None and stamp() == before:
            time.sleep(0.005)
        if proc.poll() is not None:
            sys.exit(f'the restart to be killed while it finished ended first ({proc.returncode}); see {log.name}')
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
        kill_leftovers(broken)
        print(f'start {a.kills + 1}: {resumed(log.name, where)}SIGKILL while it wrote its plots and report')
    if not done:
        r = subprocess.run(command(a.upgrain, restart_ranks, ['--restart', broken]), stdout=log, stderr=log)
        if r.returncode != 0:
            sys.exit(f'the last restart failed ({r.returncode}); see {log.name}')
    leftovers = [os.path.join(d, f) for d, _, files in os.walk(broken) for f in files if '.tmp.' in f]
    if leftovers:
        sys.exit(f'temporary files left behind: {leftovers[:5]}')
    compare = [sys.executable, os.path.join(HERE, 'compare_rank_outputs.py'), '--report']
    compare.append('--other-blocks' if restart_ranks != a.ranks else '--meshes')
    compare += [whole, broken]
    sys.exit(subprocess.run(compare).returncode)


if __name__ == '__main__':
    main()
