#!/usr/bin/python3
"""UniFuse's depth evaluation in NumPy, written from its published definitions (Jiang et al.,
"UniFuse: Unidirectional Fusion for 360 Panorama Depth Estimation", RA-L 2021; repository
alibaba/UniFuse-Unidirectional-Fusion: metrics.py, evaluate.py, datasets/threeD60.py) and
OpenCV's documented INTER_NEAREST rule, independently of the C++ in eval/. The test
tests/eval/unifuse_depth_test.cpp writes the cases, this script scores them, the test
compares.

    unifuse_depth_reference.py CASES.json RESULTS.json

CASES: {"cases": [{"name", "median_align": bool, "views": [{"pred": HxW, "gt": hxw}]}]},
depths in metres, null for NaN. RESULTS: {name: {"per_view": [metrics or null], "mean":
metrics, "clamped": {...}}}; a metric that is NaN is written as null.

The rules, in UniFuse's order:
  1. the ground truth is resized onto the prediction's grid by nearest neighbour as
     cv2.resize(..., interpolation=INTER_NEAREST) does: source index
     min(floor(i * (1 / (out / in))), in - 1) per axis;
  2. counted pixels (val_mask): 0 < gt <= 10 and gt not NaN;
  3. on the counted float32 values: gt < 0.1 -> 0.1, pred < 0.1 -> 0.1, gt > 10 -> 10, and
     gt -> 10 where pred > 10 (the prediction keeps its value);
  4. median alignment (optional): pred *= median(gt) / median(pred) in float32, torch.median
     being the lower middle element;
  5. abs_ = mean|g - p|, abs_rel = mean(|g - p| / g), sq_rel = mean((g - p)^2 / g),
     rms = sqrt(mean (g - p)^2), log_rms = sqrt(mean (log10 g - log10 p)^2),
     log10 = mean|log10(p / g)|, a_n = mean(max(g / p, p / g) < 1.25^n);
  6. the Evaluator's AverageMeter, fed once per image with n = 1: the plain mean over images.
"""
import json
import sys

import numpy as np

MIN_DEPTH = np.float32(0.1)
MAX_DEPTH = np.float32(10.0)
KEYS = ["mae", "abs_rel", "sq_rel", "rmse", "rmse_log", "log10", "delta1", "delta2", "delta3"]


def as_array(rows):
    return np.array([[np.nan if v is None else v for v in row] for row in rows], dtype=np.float64).astype(np.float32)


def opencv_nearest_indices(out_size, in_size):
    step = 1.0 / (out_size / in_size)
    return np.minimum(np.floor(np.arange(out_size) * step).astype(np.int64), in_size - 1)


def resize_nearest(image, height, width):
    rows = opencv_nearest_indices(height, image.shape[0])
    cols = opencv_nearest_indices(width, image.shape[1])
    return image[np.ix_(rows, cols)]


def lower_median(values):
    return np.sort(values)[(values.size - 1) // 2]


def one_image(pred, gt, median_align, clamped):
    gt = resize_nearest(gt, *pred.shape)
    with np.errstate(invalid="ignore"):
        mask = (gt > 0) & (gt <= MAX_DEPTH) & ~np.isnan(gt)
    g = gt[mask].copy()
    p = pred[mask].copy()
    clamped["gt_low"] += int(np.sum(g < MIN_DEPTH))
    clamped["pred_low"] += int(np.sum(p < MIN_DEPTH))
    clamped["pred_high"] += int(np.sum(p > MAX_DEPTH))
    g[g < MIN_DEPTH] = MIN_DEPTH
    p[p < MIN_DEPTH] = MIN_DEPTH
    g[g > MAX_DEPTH] = MAX_DEPTH
    g[p > MAX_DEPTH] = MAX_DEPTH
    if g.size == 0:
        return None
    if median_align:
        p = p * np.float32(lower_median(g) / lower_median(p))
    g, p = g.astype(np.float64), p.astype(np.float64)
    ratio = np.maximum(g / p, p / g)
    return {
        "mae": np.mean(np.abs(g - p)),
        "abs_rel": np.mean(np.abs(g - p) / g),
        "sq_rel": np.mean((g - p) ** 2 / g),
        "rmse": np.sqrt(np.mean((g - p) ** 2)),
        "rmse_log": np.sqrt(np.mean((np.log10(g) - np.log10(p)) ** 2)),
        "log10": np.mean(np.abs(np.log10(p / g))),
        "delta1": np.mean(ratio < 1.25),
        "delta2": np.mean(ratio < 1.25 ** 2),
        "delta3": np.mean(ratio < 1.25 ** 3),
        "pixels": int(g.size),
    }


def average_meter(per_view):
    """The Evaluator's AverageMeter with update(value, n=1) per image; a view with nothing
    counted is NaN in UniFuse and makes the average NaN."""
    if any(v is None for v in per_view):
        return None
    return {k: sum(float(v[k]) for v in per_view) / len(per_view) for k in KEYS}


def plain(metrics):
    """JSON has no NaN: an undefined metric is null."""
    if metrics is None:
        return None
    return {k: (None if np.isnan(v) else float(v)) for k, v in metrics.items()}


def main():
    cases = json.load(open(sys.argv[1]))["cases"]
    results = {}
    for case in cases:
        clamped = {"gt_low": 0, "pred_low": 0, "pred_high": 0}
        per_view = [one_image(as_array(v["pred"]), as_array(v["gt"]), case["median_align"], clamped)
                    for v in case["views"]]
        results[case["name"]] = {"per_view": [plain(m) for m in per_view], "mean": plain(average_meter(per_view)),
                                 "clamped": clamped}
    with open(sys.argv[2], "w") as f:
        json.dump(results, f)


if __name__ == "__main__":
    main()
