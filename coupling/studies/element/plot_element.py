#!/usr/bin/env python3
"""The element study's plots (docs/element-tests.md): isotropic.png (solid fraction,
coordination number and bulk modulus against the pressure) and triaxial.png (q/p, the
volumetric strain and the solid fraction against the axial strain). Usage: plot_element.py FOLDER
"""
import csv
import os
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import NullFormatter  # noqa: E402


def table(path):
    with open(path) as f:
        rows = list(csv.DictReader(l for l in f if not l.startswith('#')))
    return {k: [float(r[k]) if r[k] else float('nan') for r in rows] for k in rows[0]}


def main():
    folder = sys.argv[1]
    iso = table(os.path.join(folder, 'isotropic.csv'))
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.6))
    for a, key, label in zip(ax, ('solid_fraction', 'coordination', 'bulk_modulus'),
                             ('solid fraction', 'coordination number', 'bulk modulus K (Pa)')):
        a.plot(iso['p'], iso[key], 'o-')
        a.set_xscale('log')
        a.xaxis.set_minor_formatter(NullFormatter())  # the minor labels overlap
        a.set_xlabel('p (Pa)')
        a.set_ylabel(label)
    ax[2].set_yscale('log')
    ax[2].yaxis.set_minor_formatter(NullFormatter())
    fig.suptitle('isotropic compression')
    fig.tight_layout()
    fig.savefig(os.path.join(folder, 'isotropic.png'), dpi=120)
    tri = table(os.path.join(folder, 'triaxial.csv'))
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.6))
    for a, key, label in zip(ax, ('q_over_p', 'volumetric_strain', 'solid_fraction'),
                             ('q / p', 'volumetric strain (compression +)', 'solid fraction')):
        a.plot(tri['axial_strain'], tri[key], '-')
        a.set_xlabel('axial strain')
        a.set_ylabel(label)
    fig.suptitle('drained triaxial compression')
    fig.tight_layout()
    fig.savefig(os.path.join(folder, 'triaxial.png'), dpi=120)


if __name__ == '__main__':
    main()
