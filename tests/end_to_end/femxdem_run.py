"""What the FEM x DEM checks (check_femxdem.py, check_femxdem_column.py) share: a run of the study
on a rank count, and the tables it writes."""
import csv

from study_run import run_study


def table(path):
    """The rows of a CSV table, its '#' comment lines left out."""
    return list(csv.DictReader(l for l in open(path) if not l.startswith('#')))


def run_femxdem(upgrain, scene, out, ranks, mpiexec):
    """Runs `upgrain --study femxdem` on `ranks` ranks into `out` (study_run.py)."""
    return run_study(upgrain, 'femxdem', scene, out, ranks, mpiexec)
