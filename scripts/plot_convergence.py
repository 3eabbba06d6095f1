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
        args = args[1:]
    if len(args) < 2:
        sys.exit(__doc__)
    output = args[0] if scenes else args[1]
    fig, ax = plt.subplots(figsize=(7.5, 5) if scenes else (6, 4.2))
    if scenes:  # out.png, then one CSV per scene, named by its folder
        title = "Path tracer: accuracy versus time, per scene"
        for path in args[1:]:
            plot_curve(ax, read(path), os.path.basename(os.path.dirname(os.path.abspath(path))))
    else:
        title = "Accuracy versus time" + ("\n" + args[2] if len(args) > 2 else "")
        plot_curve(ax, read(args[0]), "phyir path tracer")
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relative RMSE vs converged reference")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(output, dpi=120)


if __name__ == "__main__":
    main()
