#!/usr/bin/env python3
"""Overlays the drained triaxial paths of several `upgrain --study element` runs: q/p and the
volumetric strain against the axial strain, one line per run (docs/element-tests.md).

Usage: plot_triaxial_paths.py OUT.png LABEL=FOLDER [LABEL=FOLDER ...]
Runs whose labels share the text before the first '#' share a colour (seeds of one sample size).
"""
import csv
import os
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402


def path(folder):
    with open(os.path.join(folder, 'element', 'triaxial.csv')) as f:
        rows = list(csv.DictReader(l for l in f if not l.startswith('#')))
    return ([float(r['axial_strain']) for r in rows], [float(r['q_over_p']) for r in rows],
            [float(r['volumetric_strain']) for r in rows])


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, runs = sys.argv[1], [a.split('=', 1) for a in sys.argv[2:]]
    groups = sorted({label.split('#')[0] for label, _ in runs}, key=lambda g: [l.split('#')[0] for l, _ in runs].index(g))
    colour = {g: f'C{k}' for k, g in enumerate(groups)}
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.8))
    seen = set()
    for label, folder in runs:
        eps, qp, ev = path(folder)
        g = label.split('#')[0]
        kw = {'color': colour[g], 'lw': 1, 'label': g if g not in seen else None}
        seen.add(g)
        ax[0].plot(eps, qp, **kw)
        ax[1].plot(eps, ev, **kw)
    ax[0].set_ylabel('q / p')
    ax[1].set_ylabel('volumetric strain (compression +)')
    for a in ax:
        a.set_xlabel('axial strain')
        a.legend(fontsize=8)
    fig.suptitle('drained triaxial compression, three seeds per sample')
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == '__main__':
    main()
