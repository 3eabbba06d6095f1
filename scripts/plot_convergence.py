#!/usr/bin/python3
"""Plots `phyir bench convergence` CSV: relative RMSE versus seconds (log-log), one point per spp.

    plot_convergence.py convergence.csv out.png [machine description]
    plot_convergence.py --scenes out.png OUT/<name>/convergence.csv ...   (a suite's scenes, one
                                                                         curve each, named by folder)
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    if not os.path.isfile(path):
        sys.exit(f"plot_convergence.py: {path}: no such file")
    rows = list(csv.DictReader(open(path)))
    if not rows:
        sys.exit(f"{path}: no rows")
    return rows


def plot_curve(ax, rows, label):
    seconds = [float(r["seconds"]) for r in rows]
    error = [float(r["relative_rmse"]) for r in rows]
    ax.loglog(seconds, error, "o-", label=label)
    for r, x, y in zip(rows, seconds, error):
        ax.annotate(f'{r["spp"]} spp', (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)


def main():
    args = sys.argv[1:]
    scenes = bool(args) and args[0] == "--scenes"
    if scenes:
        if len(args) < 3:
            sys.exit(__doc__)
        output, title = args[1], "Path tracer: accuracy versus time, per scene"
        for path in args[2:]:
            plot_curve(ax_for(len(args) - 2), read(path), os.path.basename(os.path.dirname(os.path.abspath(path))))
    else:
        if len(args) < 2:
            sys.exit(__doc__)
        output, title = args[1], "Accuracy versus time"
        plot_curve(ax_for(1), read(args[0]), "phyir path tracer")
        if len(args) > 2:
            title += "\n" + args[2]
    ax = plt.gca()
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relative RMSE vs converged reference")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    plt.gcf().tight_layout()
    plt.gcf().savefig(output, dpi=120)


def ax_for(curves):
    """The one axes of the figure, made on first use (larger for several curves)."""
    if not plt.get_fignums():
        plt.subplots(figsize=(6, 4.2) if curves == 1 else (7.5, 5))
    return plt.gca()


if __name__ == "__main__":
    main()
