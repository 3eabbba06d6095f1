#!/usr/bin/python3
"""Loss curve of a `phyir train` run: plot_training.py train_log.csv loss_curve.png

Reads the CSV written by phyir train (stage, epoch, global_step, loss, <components>, lr,
seconds) and plots the total loss and each weighted-in component against the step, on a
log scale, with the per-epoch mean of the total as a second line. Needs Debian's
/usr/bin/python3 (python3-matplotlib)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_training.py train_log.csv loss_curve.png")
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{sys.argv[1]}: no rows")
    skip = {"stage", "epoch", "global_step", "lr", "seconds"}
    names = [k for k in rows[0].keys() if k not in skip]
    steps = [int(r["global_step"]) for r in rows]
    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=100)
    for name in names:
        values = [float(r[name]) for r in rows]
        if all(v > 0 for v in values):
            ax.plot(steps, values, label=name, linewidth=2.0 if name == "loss" else 1.0)
    epochs = {}
    for r in rows:
        epochs.setdefault(int(r["epoch"]), []).append((int(r["global_step"]), float(r["loss"])))
    ex = [max(s for s, _ in v) for v in epochs.values()]
    ey = [sum(l for _, l in v) / len(v) for v in epochs.values()]
    ax.plot(ex, ey, "k--o", markersize=3, label="epoch mean")
    ax.set_yscale("log")
    ax.set_xlabel("step")
    ax.set_ylabel("loss")
    ax.set_title(f"phyir train --stage {rows[0]['stage']}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2])


if __name__ == "__main__":
    main()
