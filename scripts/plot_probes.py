#!/usr/bin/python3
"""Plots `phyir bench probes` results: relative RMSE against a converged reference versus
seconds for the whole probe grid, one series per (mode, probe resolution).

    /usr/bin/python3 scripts/plot_probes.py [--cpu] probes.csv probes.png [more.csv ...]

Extra CSV files (e.g. several scenes) are drawn on the same axes, their scene in the label
(their folder's name where two files name the same scene: a suite's OUT/<name>/probes.csv).
--cpu: the process's CPU seconds on the x axis instead of wall seconds (runs that shared the
machine with other work), the 2-minute target as 240 CPU seconds of two cores.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    args = sys.argv[1:]
    cpu = "--cpu" in args
    args = [a for a in args if a != "--cpu"]
    if len(args) < 2:
        sys.exit(__doc__)
    output = args[1]
    paths = list(dict.fromkeys([args[0]] + args[2:]))  # a file given twice is read once
    seconds = "cpu_seconds" if cpu else "seconds"
    per_file = []
    for path in paths:
        with open(path) as f:
            per_file.append((path, list(csv.DictReader(f))))
    # A suite's files may name one scene alike (two generated rooms are both room_0): then
    # each file's rows are named by its folder (the suite's scene name under --suite).
    names = [{r["scene"] for r in file_rows} for _, file_rows in per_file]
    if sum(len(n) for n in names) > len(set().union(*names)):
        for path, file_rows in per_file:
            for r in file_rows:
                r["scene"] = os.path.basename(os.path.dirname(os.path.abspath(path)))
    rows = [r for _, file_rows in per_file for r in file_rows]
    if not rows:
        sys.exit(f"plot_probes.py: no rows in {paths}")
    scenes = sorted({r["scene"] for r in rows})
    fig, ax = plt.subplots(figsize=(7.5 if len(scenes) == 1 else 11, 5))
    series = {}
    first = {}  # (scene, config) -> position of its first run in the files
    for position, r in enumerate(rows):
        key = (r["scene"], r["mode"], r["resolution"], r["grid"])
        series.setdefault(key, []).append(r)
        r["first_run"] = first.setdefault((r["scene"], r["grid"], r["resolution"], r["config"]), position) == position
    markers = {"path": "s", "cache": "o"}
    for (scene, mode, res, grid), points in sorted(series.items()):
        points.sort(key=lambda r: float(r[seconds]))
        x = [float(r[seconds]) for r in points]
        y = [float(r["relative_rmse"]) for r in points]
        label = f"{mode}, {grid} grid of {res} probes"
        if len(scenes) > 1:
            label = f"{scene}: {label}"
        if mode == "path":
            label += " (time extrapolated)"
        # The line joins the plain MODE:SPP[:CACHE_SPP] settings; variants (another seed,
        # sharing off, ...) and repeated runs are points of the same colour.
        plain = [i for i, r in enumerate(points) if len(r["config"].split(":")) <= 3 and r["first_run"]]
        line = ax.plot([x[i] for i in plain], [y[i] for i in plain], marker=markers.get(mode, "x"),
                       linestyle="-" if mode == "cache" else "--", label=label)[0]
        others = [i for i in range(len(points)) if i not in plain]
        ax.plot([x[i] for i in others], [y[i] for i in others], marker=markers.get(mode, "x"), linestyle="none",
                color=line.get_color(), fillstyle="none")
        named = set()
        for r, xi, yi in zip(points, x, y):
            if r["config"] in named:
                continue
            named.add(r["config"])
            tag = f"{r['spp']} spp" + (f"/{r['cache_spp']}" if mode == "cache" else "")
            # Settings past MODE:SPP:CACHE_SPP (cell, seed, direct cells, spread) are named
            # as given, so that two runs of one spp stay apart.
            extra = r["config"].split(":")[3:]
            if extra:
                tag += " (" + ":".join(extra) + ")"
            ax.annotate(tag, (xi, yi), textcoords="offset points", xytext=(4, 3), fontsize=7)
    noise = max(float(r["reference_noise"]) for r in rows)
    ax.axhline(0.05, color="tab:red", linewidth=0.8, linestyle=":", label="target: 5% relative RMSE")
    # The 2-minute target is the paper's grid's (128x256 probes); a smaller grid's seconds are not held to it.
    if any(r["grid"] == "128x256" for r in rows):
        ax.axvline(240 if cpu else 120, color="tab:red", linewidth=0.8, linestyle="-.",
                   label="target: 2 minutes" + (" of 2 cores" if cpu else ""))
    ax.axhline(noise, color="gray", linewidth=0.8, linestyle=":",
               label=("largest " if len(scenes) > 1 else "") + f"reference noise ({noise:.3f})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("CPU seconds for the whole grid (2 threads)" if cpu else
                  "seconds for the whole grid (wall clock, 2 threads)")
    ax.set_ylabel("relative RMSE vs converged reference (valid probes)")
    ax.set_title("Per-pixel light probes: error versus time" +
                 (f" ({scenes[0]})" if len(scenes) == 1 else f", {len(scenes)} scenes"))
    ax.grid(True, which="both", linewidth=0.3)
    if len(scenes) > 1:  # beside the axes: the scenes' curves fill them
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    else:
        ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(output, dpi=130)


main()
