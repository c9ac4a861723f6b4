#!/usr/bin/env python3
"""The element study's plots (docs/element-tests.md): isotropic.png (solid fraction,
coordination number and bulk modulus against the pressure), triaxial.png (q/p, the
volumetric strain and the solid fraction against the axial strain) and, when the study sheared,
shear.png (the steady friction coefficient and solid fraction against the inertial number, with
the fits mu(I) and phi(I), and tau/P along the shear path). Usage: plot_element.py FOLDER
"""
import csv
import json
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
    if os.path.exists(os.path.join(folder, 'shear.csv')):
        shear(folder)


def shear(folder):
    steady = table(os.path.join(folder, 'shear.csv'))
    path = table(os.path.join(folder, 'shear_path.csv'))
    order = sorted(range(len(steady['inertial_number'])), key=lambda k: steady['inertial_number'][k])
    i = [steady['inertial_number'][k] for k in order]
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.6))
    ax[0].errorbar(i, [steady['friction'][k] for k in order],
                   yerr=[steady['friction_spread'][k] for k in order], fmt='o', capsize=3, label='steady state')
    ax[1].plot(i, [steady['solid_fraction'][k] for k in order], 'o', label='steady state')
    with open(os.path.join(folder, os.pardir, 'summary.json')) as f:
        fit = json.load(f)
    if fit.get('mu_s') is not None:
        dense = [min(i) * (max(i) / min(i)) ** (k / 100) for k in range(101)]
        ax[0].plot(dense, [fit['mu_s'] + (fit['mu_2'] - fit['mu_s']) / (1 + fit['I0'] / x) for x in dense], '-',
                   label=f"mu_s {fit['mu_s']:.3f}, mu_2 {fit['mu_2']:.3f}, I0 {fit['I0']:.3g}")
        ax[1].plot(dense, [fit['phi_max'] - fit['phi_slope'] * x for x in dense], '-',
                   label=f"{fit['phi_max']:.4f} - {fit['phi_slope']:.3f} I")
    for a in ax[:2]:
        a.set_xscale('log')
        a.set_xlabel('inertial number I')
        a.legend(fontsize=8)
    ax[0].set_ylabel('friction coefficient tau / P')
    ax[1].set_ylabel('solid fraction')
    targets = sorted(set(path['target_inertial_number']))
    for t in targets:
        rows = [k for k, v in enumerate(path['target_inertial_number']) if v == t]
        ax[2].plot([path['shear_strain'][k] for k in rows], [path['friction'][k] for k in rows], '-',
                   label=f'I* = {t:g}')
    ax[2].set_xlabel('shear strain at this I')
    ax[2].set_ylabel('tau / P')
    ax[2].legend(fontsize=7)
    fig.suptitle('simple shear at a constant normal stress')
    fig.tight_layout()
    fig.savefig(os.path.join(folder, 'shear.png'), dpi=120)


if __name__ == '__main__':
    main()
