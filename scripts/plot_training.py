#!/usr/bin/python3
"""Loss curve of a `phyir train` run: plot_training.py train_log.csv loss_curve.png

Reads the CSV written by phyir train (stage, epoch, global_step, loss, <components>, lr,
seconds) and plots the total loss and each weighted-in component against the step, on a
log scale, with the per-epoch mean of the total as a second line. When val_log.csv (the
validation passes: train_loss, val_loss, val_<components>, phyir eval's metrics) lies beside
it, the validation loss joins the first panel and a second panel shows the metrics against
the epoch (each on a log scale; the SSIM and delta metrics rise when the model improves).
Needs Debian's /usr/bin/python3 (python3-matplotlib)."""
import csv
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The metrics worth a line in the validation panel (the others are in val_log.csv).
VAL_METRICS = ["basecolor_mse", "roughness_mse", "metalness_mse", "normal_deg", "depth_abs_rel", "depth_rmse",
               "depth_delta1", "rerender_mse", "probe_ssim"]


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    try:
        v = float(text)
    except (TypeError, ValueError):
        return math.nan
    return v


def plot_losses(ax, rows, val_rows):
    skip = {"stage", "epoch", "global_step", "lr", "seconds"}
    names = [k for k in rows[0].keys() if k not in skip]
    steps = [int(r["global_step"]) for r in rows]
    for name in names:
        values = [number(r[name]) for r in rows]
        if all(v > 0 for v in values):
            ax.plot(steps, values, label=name, linewidth=2.0 if name == "loss" else 1.0)
    epochs = {}
    for r in rows:
        epochs.setdefault(int(r["epoch"]), []).append((int(r["global_step"]), number(r["loss"])))
    ex = [max(s for s, _ in v) for v in epochs.values()]
    ey = [sum(l for _, l in v) / len(v) for v in epochs.values()]
    ax.plot(ex, ey, "k--o", markersize=3, label="epoch mean")
    if val_rows:
        vx = [int(r["global_step"]) for r in val_rows]
        vy = [number(r["val_loss"]) for r in val_rows]
        ax.plot(vx, vy, "r-s", markersize=4, label="validation loss")
    ax.set_yscale("log")
    ax.set_xlabel("step")
    ax.set_ylabel("loss")
    ax.set_title(f"phyir train --stage {rows[0]['stage']}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def plot_metrics(ax, val_rows):
    epochs = [int(r["epoch"]) for r in val_rows]
    for name in VAL_METRICS:
        if name not in val_rows[0]:
            continue
        values = [number(r[name]) for r in val_rows]
        if all(v > 0 for v in values):
            ax.plot(epochs, values, "-o", markersize=3, label=name)
    ax.set_yscale("log")
    ax.set_xlabel("epoch")
    ax.set_ylabel("validation metric")
    ax.set_title("validation (phyir eval's metrics)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_training.py train_log.csv loss_curve.png")
    rows = read_rows(sys.argv[1])
    if not rows:
        sys.exit(f"{sys.argv[1]}: no rows")
    val_path = Path(sys.argv[1]).with_name("val_log.csv")
    val_rows = read_rows(val_path) if val_path.is_file() else []
    if val_rows:
        fig, (ax, ax_val) = plt.subplots(1, 2, figsize=(13, 4.5), dpi=100)
        plot_metrics(ax_val, val_rows)
    else:
        fig, ax = plt.subplots(figsize=(8, 4.5), dpi=100)
    plot_losses(ax, rows, val_rows)
    fig.tight_layout()
    fig.savefig(sys.argv[2])


if __name__ == "__main__":
    main()
