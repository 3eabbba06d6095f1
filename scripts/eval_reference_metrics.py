#!/usr/bin/python3
"""Independent reference values for phyir eval's metrics (tests/eval/metrics_test.cpp).

Reads a JSON file of cases written by the test, computes each with numpy / scipy / skimage
(Debian's python3-numpy, python3-skimage; run with /usr/bin/python3), writes a JSON file of
results keyed by case name. Nothing here is shared with the C++ code: the formulas are
re-derived from their definitions (docs/eval.md) or taken from skimage.

    /usr/bin/python3 scripts/eval_reference_metrics.py cases.json results.json
"""
import json
import math
import sys

import numpy as np
from scipy import ndimage
from skimage.metrics import structural_similarity


def arr(x):
    return np.asarray(x, dtype=np.float64)


def masked(case):
    p, g, m = arr(case["pred"]), arr(case["gt"]), arr(case["mask"]) > 0.5
    return p[m], g[m]  # [N, C]


def mse(case):
    p, g = masked(case)
    return float(np.mean((p - g) ** 2))


def mae(case):
    p, g = masked(case)
    return float(np.mean(np.abs(p - g)))


def angular(case):
    p, g = masked(case)
    p = p / np.linalg.norm(p, axis=1, keepdims=True)
    g = g / np.linalg.norm(g, axis=1, keepdims=True)
    return float(np.degrees(np.arccos(np.clip(np.sum(p * g, axis=1), -1.0, 1.0))).mean())


def depth(case):
    p, g = masked(case)
    p, g = p[:, 0], g[:, 0]
    keep = g > 0
    p, g = np.maximum(p[keep], 1e-3), g[keep]
    ratio = np.maximum(p / g, g / p)
    return {
        "mae": float(np.mean(np.abs(p - g))),
        "abs_rel": float(np.mean(np.abs(p - g) / g)),
        "sq_rel": float(np.mean((p - g) ** 2 / g)),
        "rmse": float(np.sqrt(np.mean((p - g) ** 2))),
        "rmse_log": float(np.sqrt(np.mean((np.log(p) - np.log(g)) ** 2))),
        "log10": float(np.mean(np.abs(np.log10(p) - np.log10(g)))),
        "delta1": float(np.mean(ratio < 1.25)),
        "delta2": float(np.mean(ratio < 1.25 ** 2)),
        "delta3": float(np.mean(ratio < 1.25 ** 3)),
    }


def ssim_skimage(case):
    x, y = arr(case["x"]), arr(case["y"])
    return float(structural_similarity(x, y, gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
                                       data_range=1.0, channel_axis=2, win_size=case["win_size"]))


def ssim_eq7(x, y):
    """Eq. 7's SSIM: 5x5 Gaussian (sigma 1.5; truncate 1.0 gives scipy radius int(1.5 + 0.5) = 2),
    rows replicated ('nearest'), columns wrapped, C1 = 1e-4, C2 = 9e-4, mean over texels and channels."""
    c1, c2 = 1e-4, 9e-4
    values = []
    for c in range(x.shape[2]):
        a, b = x[:, :, c], y[:, :, c]
        blur = lambda t: ndimage.gaussian_filter(t, sigma=1.5, truncate=1.0, mode=("nearest", "wrap"))
        ma, mb = blur(a), blur(b)
        saa, sbb, sab = blur(a * a) - ma * ma, blur(b * b) - mb * mb, blur(a * b) - ma * mb
        values.append(((2 * ma * mb + c1) * (2 * sab + c2)) / ((ma * ma + mb * mb + c1) * (saa + sbb + c2)))
    return float(np.mean(values))


def area_resize(image, out_h, out_w):
    """Exact box resampling by going through the common multiple grid (np.repeat, block means)."""
    h, w = image.shape[:2]
    ly, lx = math.lcm(h, out_h), math.lcm(w, out_w)
    fine = np.repeat(np.repeat(image, ly // h, axis=0), lx // w, axis=1)
    return fine.reshape(out_h, ly // out_h, out_w, lx // out_w, -1).mean(axis=(1, 3))


def probe_ssim(case):
    """Mean over probes valid on both sides of eq. 7's SSIM of log(1 + L), grids matched by cell centre."""
    pred, gt = arr(case["pred"]), arr(case["gt"])
    pm, gm = arr(case["pred_mask"]), arr(case["gt_mask"])
    (pH, pW), (gH, gW) = pm.shape, gm.shape
    ph, pw, gh, gw = pred.shape[0] // pH, pred.shape[1] // pW, gt.shape[0] // gH, gt.shape[1] // gW
    H, W = (pH, pW) if pH * pW < gH * gW else (gH, gW)
    h, w = (ph, pw) if ph * pw < gh * gw else (gh, gw)
    scores = []
    for i in range(H):
        for j in range(W):
            v, u = (i + 0.5) / H, (j + 0.5) / W
            pi, pj = min(pH - 1, int(np.floor(v * pH))), min(pW - 1, int(np.floor(u * pW)))
            gi, gj = min(gH - 1, int(np.floor(v * gH))), min(gW - 1, int(np.floor(u * gW)))
            if pm[pi, pj] <= 0.5 or gm[gi, gj] <= 0.5:
                continue
            a = area_resize(pred[pi * ph:(pi + 1) * ph, pj * pw:(pj + 1) * pw], h, w)
            b = area_resize(gt[gi * gh:(gi + 1) * gh, gj * gw:(gj + 1) * gw], h, w)
            scores.append(ssim_eq7(np.log1p(a), np.log1p(b)))
    return {"ssim": float(np.mean(scores)), "probes": len(scores)}


def run(case):
    metric = case["metric"]
    if metric == "mse":
        return mse(case)
    if metric == "mae":
        return mae(case)
    if metric == "angular":
        return angular(case)
    if metric == "depth":
        return depth(case)
    if metric == "ssim_skimage":
        return ssim_skimage(case)
    if metric == "ssim_eq7":
        return ssim_eq7(arr(case["x"]), arr(case["y"]))
    if metric == "area_resize":
        return area_resize(arr(case["image"]), case["height"], case["width"]).tolist()
    if metric == "probe_ssim":
        return probe_ssim(case)
    raise ValueError("unknown metric " + metric)


def main():
    cases = json.load(open(sys.argv[1]))["cases"]
    results = {c["name"]: run(c) for c in cases}
    with open(sys.argv[2], "w") as f:
        json.dump(results, f)


if __name__ == "__main__":
    main()
