#!/usr/bin/env python3
"""Pareto plots of an accuracy study (docs/accuracy.md): per knob, the change a setting makes
against the wall time of its run, on log axes, the scene's own setting marked. Usage:
plot_accuracy.py FOLDER (the study's accuracy/ folder, holding accuracy.csv)."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import NullFormatter, ScalarFormatter  # noqa: E402


def main():
    folder = sys.argv[1]
    with open(os.path.join(folder, 'accuracy.csv')) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith('#')))
    knobs = []
    for r in rows:
        if r['knob'] not in ('reference',) and r['knob'] not in knobs:
            knobs.append(r['knob'])
    for knob in knobs:
        own = [r for r in rows if r['knob'] == knob]
        exact = any(math.isfinite(float(r['exact_error'])) for r in own)
        key = 'exact_error' if exact else 'worst_change'
        points = [(float(r['wall_s']), float(r[key]), r['setting'], r['default'] == '1') for r in own]
        shown = [(t, max(e, 1e-16), s, d) for t, e, s, d in points if math.isfinite(e) and math.isfinite(t)]
        fig, ax = plt.subplots(figsize=(6.0, 4.2))
        if shown:
            ax.plot([p[0] for p in shown], [p[1] for p in shown], 'o-', color='tab:blue')
            for t, e, s, d in shown:
                ax.annotate(s, (t, e), fontsize=7, xytext=(4, 4), textcoords='offset points')
                if d:
                    ax.plot([t], [e], 's', color='tab:red', markersize=9, label='the scene as given')
            times = [p[0] for p in shown]
            # Wall times of a knob often span less than a decade, where a log axis has no labelled
            # tick: plain seconds then.
            if max(times) > 10 * min(times):
                ax.set_xscale('log')
                ax.xaxis.set_major_formatter(ScalarFormatter())
                ax.xaxis.set_minor_formatter(NullFormatter())
            ax.set_yscale('log')
        else:
            ax.text(0.5, 0.5, 'no change to plot (cost only)', transform=ax.transAxes, ha='center')
            for t, e, s, d in points:
                ax.axvline(t, color='tab:red' if d else 'tab:gray', lw=1)
        ax.set_xlabel('wall time of the run (s)')
        ax.set_ylabel('error against the exact answer' if exact else 'largest relative change of the bed')
        ax.set_title(knob)
        if any(d for *_, d in shown):
            ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(folder, 'pareto_' + ''.join(c if c.isalnum() else '_' for c in knob) + '.png'), dpi=110)
        plt.close(fig)


if __name__ == '__main__':
    main()
