#!/usr/bin/python3
"""Plots `phyir bench convergence` CSV: relative RMSE versus seconds (log-log), one point per spp."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: plot_convergence.py convergence.csv out.png [machine description]")
    rows = list(csv.DictReader(open(sys.argv[1])))
    if not rows:
        sys.exit(f"{sys.argv[1]}: no rows")
    seconds = [float(r["seconds"]) for r in rows]
    error = [float(r["relative_rmse"]) for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.loglog(seconds, error, "o-", label="phyir path tracer")
    for r, x, y in zip(rows, seconds, error):
        ax.annotate(f'{r["spp"]} spp', (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("relative RMSE vs converged reference")
    title = "Accuracy versus time"
    if len(sys.argv) > 3:
        title += "\n" + sys.argv[3]
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
