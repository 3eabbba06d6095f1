#!/usr/bin/python3
"""Errors and time to equal error for the phyir / Cycles comparison (scripts/cycles/compare.sh).

    compare.py camera SCENE.gltf
        prints the world position of the scene's first camera node as x,y,z
    compare.py analyse --runs DIR --figures DIR --name NAME --spp-list 1,2,... --repeats R
                       --modes principled,ue4 --reference-spp ours=4096,cycles_principled=4096,...
                       [--phyir-sweep sweep] [--machine machine.txt] [--title "mini room"]
        reads DIR (layout written by compare.sh or compare_furnished.sh), writes NAME's CSV
        and PNG figures; with reference/KEY_a.exr and KEY_b.exr present (two half references
        of different seeds), also the references' own noise, measured
    compare.py average OUT.exr A.exr B.exr
        writes the pixel mean of two images of equal sample counts (two half references)

Error: relative RMSE = sqrt(mean((a - b)^2)) / mean(|b|) over the RGB channels of every
pixel, b the reference: the definition of `phyir bench convergence` (core/src/image_error.cpp).
Time to an error: log-log interpolation between the two sweep points around it.
Needs Debian's /usr/bin/python3 with python3-numpy, python3-openimageio and python3-matplotlib.
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np
import OpenImageIO as oiio

DEFAULT_TARGETS = "0.5,0.3,0.2,0.1"


# --- glTF camera --------------------------------------------------------------------------

def node_matrix(node):
    if "matrix" in node:
        return np.array(node["matrix"], dtype=float).reshape(4, 4).T  # glTF is column-major
    t = np.array(node.get("translation", [0, 0, 0]), dtype=float)
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    s = np.array(node.get("scale", [1, 1, 1]), dtype=float)
    m = np.eye(4)
    m[:3, :3] = r * s
    m[:3, 3] = t
    return m


def camera_position(path):
    gltf = json.load(open(path))
    nodes = gltf.get("nodes", [])
    scene = gltf.get("scenes", [{}])[gltf.get("scene", 0)]
    stack = [(i, np.eye(4)) for i in scene.get("nodes", [])]
    while stack:  # depth first, in file order
        index, parent = stack.pop(0)
        world = parent @ node_matrix(nodes[index])
        if "camera" in nodes[index]:
            return world[:3, 3]
        stack[0:0] = [(c, world) for c in nodes[index].get("children", [])]
    sys.exit(f"{path}: no node of the default scene has a camera")


# --- images and errors ----------------------------------------------------------------------

def read_exr(path, channels=("R", "G", "B")):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"{path}: cannot open ({oiio.geterror()})")
    spec = image.spec()
    pixels = image.read_image(format=oiio.FLOAT)
    image.close()
    if pixels is None:
        sys.exit(f"{path}: cannot read pixels")
    pixels = pixels.reshape(spec.height, spec.width, spec.nchannels)
    names = list(spec.channelnames)
    picked = []
    for c in channels:
        matches = [i for i, n in enumerate(names) if n == c or n.endswith("." + c)]
        if not matches:
            sys.exit(f"{path}: no channel '{c}' among {names}")
        picked.append(matches[0])
    out = pixels[..., picked]
    if not np.isfinite(out).all():
        print(f"warning: {path}: {np.count_nonzero(~np.isfinite(out))} non-finite values", file=sys.stderr)
    return out


def relative_rmse(a, b):
    return float(np.sqrt(np.mean((a.astype(np.float64) - b) ** 2)) / np.mean(np.abs(b)))


def rmse(a, b):
    return float(np.sqrt(np.mean((a.astype(np.float64) - b) ** 2)))


def time_to_error(seconds, errors, target):
    """Seconds at which the (seconds, error) curve first reaches `target`, log-log interpolated.

    Returns (seconds, how): how is "interpolated", "below the first point" (returns the first
    point's seconds as an upper bound) or "not reached" (None).
    """
    for i, (t, e) in enumerate(zip(seconds, errors)):
        if e <= target:
            if i == 0:
                return t, "at or below the first point"
            t0, e0 = seconds[i - 1], errors[i - 1]
            f = (math.log(target) - math.log(e0)) / (math.log(e) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t) - math.log(t0))), "interpolated"
    return None, "not reached"


# --- the sweep ----------------------------------------------------------------------------------

def load_json(path):
    with open(path) as f:
        return json.load(f)


def load_at_start(base):
    """The 1-minute load average when a render started (written by common.sh), or NaN."""
    try:
        return float(open(base + ".load").read().split()[0])
    except (OSError, ValueError, IndexError):
        return float("nan")


def sweep_point(runs, key, spp, repeat, phyir_sweep="sweep"):
    """Image and times of one sweep render."""
    if key == "ours":
        base = os.path.join(runs, phyir_sweep, f"ours_spp{spp}_r{repeat}")
        report = load_json(os.path.join(base, "render.json"))
        process = load_json(base + ".time.json")
        return read_exr(os.path.join(base, "color.exr")), {
            "render_seconds": report["timings"]["color_seconds"],
            "total_seconds": report["timings"]["total_seconds"],
            "process_seconds": process["wall_seconds"],
            "cpu_seconds": process["user_seconds"] + process["system_seconds"],
            "nonfinite": report.get("counters", {}).get("nonfinite_samples_caught", 0),
            "load": load_at_start(base),
        }
    base = os.path.join(runs, "sweep", f"{key}_spp{spp}_r{repeat}")
    report = load_json(base + ".json")
    process = load_json(base + ".time.json")
    t = report["timings"]
    if t["render_seconds"] is None:
        sys.exit(f"{base}.json: Cycles' render time was not found in its log")
    return read_exr(base + ".exr"), {
        "render_seconds": t["render_seconds"],
        "total_seconds": t["render_call_seconds"],
        "process_seconds": process["wall_seconds"],
        "cpu_seconds": t["render_call_cpu_seconds"],
        "nonfinite": 0,
        "load": load_at_start(base),
    }


def noise_constant(points, key, reference_spp):
    """a in relative_rmse(n) ~ a sqrt(1/n + 1/N) against the renderer's own reference (N spp),
    from the sweep's highest spp (the rate of stratified samplers approaches 1/sqrt(n) there)."""
    top = max(p["spp"] for p in points if p["renderer"] == key)
    values = [p["rel_own"] / math.sqrt(1.0 / p["spp"] + 1.0 / reference_spp)
              for p in points if p["renderer"] == key and p["spp"] * 4 >= top]
    return float(np.median(values)) if values else float("nan")


def alignment(ours, cycles):
    """Relative RMSE of Cycles' converged image against ours under shifts and flips."""
    rows = {}
    for dx in (-2, -1, 0, 1, 2):
        rows[f"shift {dx:+d} px"] = relative_rmse(np.roll(cycles, dx, axis=1), ours)
    rows["mirrored left-right"] = relative_rmse(cycles[:, ::-1], ours)
    rows["upside down"] = relative_rmse(cycles[::-1], ours)
    rows["rotated 90 deg about up"] = relative_rmse(np.roll(cycles, cycles.shape[1] // 4, axis=1), ours)
    return rows


def depth_agreement(runs):
    ours_path = os.path.join(runs, "align", "ours", "depth.exr")
    cycles_path = os.path.join(runs, "align", "cycles.exr")
    if not (os.path.exists(ours_path) and os.path.exists(cycles_path)):
        return None
    ours = read_exr(ours_path, ("Y",))[..., 0]
    cycles = read_exr(cycles_path, ("Depth.Z",))[..., 0]
    valid = (ours > 0) & np.isfinite(cycles) & (cycles > 0) & (cycles < 1e9)
    rel = np.abs(cycles[valid] - ours[valid]) / ours[valid]
    return {"pixels": int(valid.sum()), "median_relative_difference": float(np.median(rel)),
            "fraction_within_1_percent": float(np.mean(rel < 0.01)),
            "fraction_within_5_percent": float(np.mean(rel < 0.05))}


def lights_mask(runs):
    """Pixels whose centre sees an emitter, grown by one pixel: where pixel-area antialiasing
    of a light (a huge contrast) dominates the error rather than light transport."""
    mask = read_exr(os.path.join(runs, "align", "ours", "mask_emissive.exr"), ("Y",))[..., 0] > 0.5
    grown = mask.copy()
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            grown |= np.roll(np.roll(mask, dy, axis=0), dx, axis=1)
    return grown


def blur(image, radius):
    """Box blur of a 2-D image, wrapping around horizontally like the panorama."""
    out = np.zeros_like(image, dtype=np.float64)
    padded = np.pad(image, ((radius, radius), (0, 0)), mode="edge")
    for dy in range(-radius, radius + 1):
        rows = padded[radius + dy: radius + dy + image.shape[0]]
        for dx in range(-radius, radius + 1):
            out += np.roll(rows, dx, axis=1)
    return out / (2 * radius + 1) ** 2


def preview(image, exposure):
    x = np.clip(image * 2.0 ** exposure, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def analyse(args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs, name = args.runs, args.name
    spps = [int(s) for s in args.spp_list.split(",")]
    modes = [m for m in args.modes.split(",") if m]
    keys = ["ours"] + [f"cycles_{m}" for m in modes]
    labels = {"ours": "phyir", "cycles_principled": "Cycles, Principled BSDF (as imported)",
              "cycles_ue4": "Cycles, UE4 terms (rebuilt)"}
    machine = open(os.path.join(runs, args.machine)).read()
    reference_spp = {k: int(v) for k, v in (item.split("=") for item in args.reference_spp.split(","))}
    targets = [float(t) for t in args.targets.split(",")]
    keep = ~lights_mask(runs)
    refs = {"ours": read_exr(os.path.join(runs, "reference", "ours.exr"))}
    for m in modes:
        refs[f"cycles_{m}"] = read_exr(os.path.join(runs, "reference", f"cycles_{m}.exr"))

    halves = {}  # measured: relative RMSE of the two half references; the mean's is half of it
    for key in keys:
        a, b = (os.path.join(runs, "reference", f"{key}_{h}.exr") for h in "ab")
        if os.path.exists(a) and os.path.exists(b):
            d = relative_rmse(read_exr(a), read_exr(b))
            halves[key] = {"halves_relative_rmse": d, "reference_relative_rmse": d / 2}

    # Sweep: time = minimum over repeats, error = mean over repeats (one seed each).
    points = []
    for key in keys:
        for spp in spps:
            errors_shared, errors_own, rmse_shared, errors_own_unlit, times = [], [], [], [], []
            for r in range(1, args.repeats + 1):
                image, t = sweep_point(runs, key, spp, r, args.phyir_sweep)
                errors_shared.append(relative_rmse(image, refs["ours"]))
                rmse_shared.append(rmse(image, refs["ours"]))
                errors_own.append(relative_rmse(image, refs[key]))
                errors_own_unlit.append(relative_rmse(image[keep], refs[key][keep]))
                times.append(t)
            points.append({
                "renderer": key, "spp": spp,
                "render_seconds": min(t["render_seconds"] for t in times),
                "render_seconds_max": max(t["render_seconds"] for t in times),
                "total_seconds": min(t["total_seconds"] for t in times),
                "process_seconds": min(t["process_seconds"] for t in times),
                "cpu_seconds": min(t["cpu_seconds"] for t in times),
                "rel_shared": float(np.mean(errors_shared)), "rmse_shared": float(np.mean(rmse_shared)),
                "rel_own": float(np.mean(errors_own)),
                "rel_own_no_lights": float(np.mean(errors_own_unlit)),
                # The reference's own noise adds in quadrature (independent renders): removed,
                # where the half references measured it.
                "rel_own_clean": (math.sqrt(max(np.mean(np.square(errors_own))
                                                - halves[key]["reference_relative_rmse"] ** 2, 1e-12))
                                  if key in halves else float("nan")),
                "nonfinite": sum(t["nonfinite"] for t in times),
                "load_min": min(t["load"] for t in times), "load_max": max(t["load"] for t in times),
            })

    os.makedirs(args.figures, exist_ok=True)
    csv_path = os.path.join(args.figures, f"cycles_{name}.csv")
    with open(csv_path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["renderer", "spp", "render_seconds", "render_seconds_max", "total_seconds", "process_seconds",
                    "cpu_seconds", "relative_rmse_shared_reference", "rmse_shared_reference",
                    "relative_rmse_own_reference", "relative_rmse_own_reference_lights_excluded",
                    "relative_rmse_own_reference_noise_removed", "load_average_min", "load_average_max"])
        for p in points:
            w.writerow([p["renderer"], p["spp"], f'{p["render_seconds"]:.4f}', f'{p["render_seconds_max"]:.4f}',
                        f'{p["total_seconds"]:.4f}', f'{p["process_seconds"]:.3f}', f'{p["cpu_seconds"]:.3f}',
                        f'{p["rel_shared"]:.5f}', f'{p["rmse_shared"]:.5f}', f'{p["rel_own"]:.5f}',
                        f'{p["rel_own_no_lights"]:.5f}', f'{p["rel_own_clean"]:.5f}',
                        f'{p["load_min"]:.2f}', f'{p["load_max"]:.2f}'])

    # Time to equal error, on render seconds and on CPU seconds.
    summary = []
    columns = {"own": "rel_own", "phyir": "rel_shared", "own_lights_excluded": "rel_own_no_lights",
               "own_reference_noise_removed": "rel_own_clean"}
    curves = ([(k, "own") for k in keys] + [(k, "phyir") for k in keys if k != "ours"] +
              [(k, "own_lights_excluded") for k in keys] +
              [(k, "own_reference_noise_removed") for k in keys if k in halves and "ours" in halves])
    for key, against in curves:
        pts = [p for p in points if p["renderer"] == key]
        errors = [p[columns[against]] for p in pts]
        for clock in ("render_seconds", "cpu_seconds"):
            for target in targets:
                t, how = time_to_error([p[clock] for p in pts], errors, target)
                summary.append({"renderer": key, "reference": against,
                                "clock": clock, "target": target, "seconds": t, "how": how})
    for s in summary:
        ours = next(o for o in summary if o["renderer"] == "ours" and o["clock"] == s["clock"]
                    and o["target"] == s["target"]
                    and o["reference"] == ("own" if s["reference"] == "phyir" else s["reference"]))
        s["ratio_to_phyir"] = (s["seconds"] / ours["seconds"]
                               if s["seconds"] and ours["seconds"] else None)
    summary_path = os.path.join(args.figures, f"cycles_{name}_time_to_error.csv")
    with open(summary_path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["renderer", "reference", "clock", "target_relative_rmse", "seconds", "how",
                    "seconds_over_phyir_seconds"])
        for s in summary:
            w.writerow([s["renderer"], s["reference"], s["clock"], s["target"],
                        "" if s["seconds"] is None else f'{s["seconds"]:.3f}', s["how"],
                        "" if s["ratio_to_phyir"] is None else f'{s["ratio_to_phyir"]:.2f}'])

    # Converged images: agreement, noise expected from the sweeps, alignment, depth.
    noise = {k: noise_constant(points, k, reference_spp[k]) for k in keys}
    agreement = {}
    for m in modes:
        key = f"cycles_{m}"
        a, b = refs[key], refs["ours"]
        expected = math.sqrt(noise["ours"] ** 2 / reference_spp["ours"] + noise[key] ** 2 / reference_spp[key])
        agreement[key] = {
            "relative_rmse": relative_rmse(a, b),
            "expected_from_noise": expected,
            "mean_ratio_rgb": (a.reshape(-1, 3).mean(0) / b.reshape(-1, 3).mean(0)).tolist(),
            "alignment": alignment(b, a),
        }
    # Cycles' half references and their mean are renders independent of phyir's reference:
    # points at N/2 and N spp of the curve against phyir's reference, past the sweep's end.
    references_against_phyir = {}
    for key in keys:
        if key == "ours" or key not in halves:
            continue
        rows = {}
        cpu = {}
        for h in "ab":
            t = load_json(os.path.join(runs, "reference", f"{key}_{h}.json"))["timings"]
            cpu[h] = t["render_call_cpu_seconds"]
            rows[f"half_{h}"] = {"spp": reference_spp[key] // 2, "cpu_seconds": cpu[h],
                                 "relative_rmse": relative_rmse(read_exr(os.path.join(runs, "reference", f"{key}_{h}.exr")),
                                                                refs["ours"])}
        rows["mean"] = {"spp": reference_spp[key], "cpu_seconds": cpu["a"] + cpu["b"],
                        "relative_rmse": relative_rmse(refs[key], refs["ours"])}
        references_against_phyir[key] = rows
    report = {"name": name, "reference_spp": reference_spp, "noise_constant": noise,
              "references_against_phyir": references_against_phyir,
              "reference_noise": {k: noise[k] / math.sqrt(reference_spp[k]) for k in keys},
              "reference_noise_measured": halves,
              "agreement": agreement, "depth": depth_agreement(runs),
              "nonfinite_samples_caught_phyir": sum(p["nonfinite"] for p in points if p["renderer"] == "ours"),
              "time_to_error": summary}
    with open(os.path.join(args.figures, f"cycles_{name}.json"), "w") as f:
        json.dump(report, f, indent=1)

    # Figure 1: relative RMSE versus seconds (top: render wall time, bottom: CPU time),
    # against own and shared references.
    panels = [("rel_own", "each against its own converged reference"),
              ("rel_shared", "all against phyir's converged reference"),
              ("rel_own_no_lights", "own reference, directly seen lights excluded")]
    clocks = [("render_seconds", "render wall time, s (minimum of repeats)"),
              ("cpu_seconds", "CPU time (user + system), s (minimum of repeats)")]
    fig, axes = plt.subplots(2, 3, figsize=(14, 8.2), sharey=True)
    colours = {"ours": "C0", "cycles_principled": "C3", "cycles_ue4": "C2"}
    for row, (clock, xlabel) in enumerate(clocks):
        for ax, (column, title) in zip(axes[row], panels):
            for key in keys:
                pts = [p for p in points if p["renderer"] == key]
                errors = [p[column] for p in pts]
                ax.loglog([p[clock] for p in pts], errors, "o-", color=colours.get(key), ms=4,
                          label=labels.get(key, key))
                for p, e in zip(pts, errors):
                    if p["spp"] in (1, 16, spps[-1]):
                        ax.annotate(f'{p["spp"]} spp', (p[clock], e), textcoords="offset points",
                                    xytext=(3, 3), fontsize=7, color=colours.get(key))
            for target in targets:
                ax.axhline(target, color="0.6", lw=0.8, ls=":")
            ax.set_xlabel(xlabel, fontsize=8)
            ax.grid(True, which="both", alpha=0.3)
            ax.set_title(title, fontsize=9)
        axes[row, 0].set_ylabel("relative RMSE")
    axes[0, 0].legend(fontsize=8)
    cpu = next((line.split(": ", 1)[1] for line in machine.splitlines() if line.startswith("cpu:")), "")
    fig.suptitle(f"phyir vs Cycles, {args.title or name + ' room'}, {refs['ours'].shape[1]}x{refs['ours'].shape[0]} "
                 f"equirect, {cpu}", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(args.figures, f"cycles_{name}.png"), dpi=100)
    plt.close(fig)

    # Figure 2: the converged images (top) and Cycles / phyir luminance, blurred over 5x5
    # pixels so that the bias shows rather than the references' noise (bottom).
    exposure = -math.log2(max(np.percentile(refs["ours"], 99), 1e-6))
    fig, axes = plt.subplots(2, len(keys), figsize=(4.2 * len(keys), 4.6), squeeze=False)
    luminance = {k: blur(refs[k] @ np.array([0.2126, 0.7152, 0.0722]), 2) for k in keys}
    for col, key in enumerate(keys):
        axes[0, col].imshow(preview(refs[key], exposure), interpolation="nearest")
        axes[0, col].set_title(f"{labels.get(key, key)}, {reference_spp[key]} spp", fontsize=8)
        if key == "ours":
            axes[1, col].axis("off")
            axes[1, col].text(0.02, 0.5, f"exposure {exposure:+.2f} stops, sRGB\n"
                              "below: Cycles / phyir luminance,\n5x5 box-blurred",
                              fontsize=8, va="center", transform=axes[1, col].transAxes)
        else:
            shown = axes[1, col].imshow(luminance[key] / np.maximum(luminance["ours"], 1e-6), cmap="RdBu_r",
                                        vmin=0.8, vmax=1.2, interpolation="nearest")
            fig.colorbar(shown, ax=axes[1, col], fraction=0.024, pad=0.01)
            axes[1, col].set_title(f"{labels.get(key, key)} / phyir", fontsize=8)
        for row in range(2):
            axes[row, col].set_xticks([])
            axes[row, col].set_yticks([])
    fig.tight_layout()
    fig.savefig(os.path.join(args.figures, f"cycles_{name}_images.png"), dpi=80)
    plt.close(fig)

    # Console summary.
    print(f"wrote {csv_path}, {summary_path} and figures in {args.figures}")
    for s in summary:
        t = "not reached" if s["seconds"] is None else f'{s["seconds"]:.2f} s'
        r = "" if s["ratio_to_phyir"] is None else f' ({s["ratio_to_phyir"]:.2f}x phyir)'
        print(f'  {s["clock"]:14s} {s["renderer"]:18s} vs {s["reference"]:21s} reference: '
              f'{s["target"]:.0%} in {t}{r}')
    for key, a in agreement.items():
        print(f'  converged {key} vs phyir: relative RMSE {a["relative_rmse"]:.4f} '
              f'(noise alone ~{a["expected_from_noise"]:.4f}), mean ratio {np.round(a["mean_ratio_rgb"], 4)}')
    print(f'  depth: {report["depth"]}')
    for key, rows in references_against_phyir.items():
        for label, row in rows.items():
            print(f'  {key} reference {label} ({row["spp"]} spp, {row["cpu_seconds"]:.1f} CPU s) against '
                  f'phyir\'s reference: relative RMSE {row["relative_rmse"]:.4f}')
    for key, h in halves.items():
        print(f'  {key} reference: half references differ by {h["halves_relative_rmse"]:.4f}, so the '
              f'reference (their mean) has relative RMSE ~{h["reference_relative_rmse"]:.4f}')


def average(args):
    """Mean of two EXR images (RGB), written as float RGB."""
    a, b = read_exr(args.a), read_exr(args.b)
    if a.shape != b.shape:
        sys.exit(f"{args.a}, {args.b}: sizes differ ({a.shape} against {b.shape})")
    mean = np.ascontiguousarray((a.astype(np.float64) + b) / 2)  # read_exr picks channels: a strided view
    spec = oiio.ImageSpec(mean.shape[1], mean.shape[0], 3, oiio.FLOAT)
    out = oiio.ImageOutput.create(args.out)
    if out is None or not out.open(args.out, spec) or not out.write_image(mean.astype(np.float32)):
        sys.exit(f"{args.out}: cannot write ({oiio.geterror()})")
    out.close()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    cam = sub.add_parser("camera")
    cam.add_argument("scene")
    an = sub.add_parser("analyse")
    an.add_argument("--runs", required=True)
    an.add_argument("--figures", required=True)
    an.add_argument("--name", required=True)
    an.add_argument("--spp-list", required=True)
    an.add_argument("--repeats", type=int, default=2)
    an.add_argument("--modes", default="principled,ue4")
    an.add_argument("--targets", default=DEFAULT_TARGETS, help="relative RMSE levels to time")
    an.add_argument("--reference-spp", required=True, help="ours=4096,cycles_principled=4096,...")
    an.add_argument("--phyir-sweep", default="sweep", help="folder of RUNS holding phyir's sweep renders")
    an.add_argument("--machine", default="machine.txt", help="file of RUNS describing the machine")
    an.add_argument("--title", default="", help="scene name in the figure's title (default: NAME room)")
    av = sub.add_parser("average")
    av.add_argument("out")
    av.add_argument("a")
    av.add_argument("b")
    args = parser.parse_args()
    if args.command == "average":
        average(args)
    elif args.command == "camera":
        p = camera_position(args.scene)
        print(f"{p[0]:.6g},{p[1]:.6g},{p[2]:.6g}")
    else:
        analyse(args)


if __name__ == "__main__":
    main()
