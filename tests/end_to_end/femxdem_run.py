"""What the FEM x DEM checks (check_femxdem.py, check_femxdem_column.py) share: a run of the study
on a rank count, and the tables it writes."""
import csv
import subprocess
import sys


def table(path):
    """The rows of a CSV table, its '#' comment lines left out."""
    return list(csv.DictReader(l for l in open(path) if not l.startswith('#')))


def run_femxdem(upgrain, scene, out, ranks, mpiexec):
    """Runs `upgrain --study femxdem` on `ranks` ranks into `out`; exits with its output when it
    fails, returns its stdout otherwise."""
    cmd = [upgrain, '--study', 'femxdem', '--output', out, scene]
    if ranks > 1:
        cmd = [mpiexec, '-n', str(ranks)] + cmd
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f'{ranks} rank(s): exit {r.returncode}\n{r.stdout}\n{r.stderr}')
    return r.stdout
