"""A study of the driver run on a rank count, for the checks that compare rank counts
(check_calibration.py, femxdem_run.py)."""
import subprocess
import sys


def run_study(upgrain, study, scene, out, ranks, mpiexec):
    """Runs `upgrain --study STUDY` on `ranks` ranks into `out`; exits with its output when it
    fails, returns its stdout otherwise."""
    cmd = [upgrain, '--study', study, '--output', out, scene]
    if ranks > 1:
        cmd = [mpiexec, '-n', str(ranks)] + cmd
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f'{ranks} rank(s): exit {r.returncode}\n{r.stdout}\n{r.stderr}')
    return r.stdout
