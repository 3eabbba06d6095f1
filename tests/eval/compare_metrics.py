#!/usr/bin/python3
"""Compares a phyir eval metrics.json with the checked-in expectations
(tests/data/eval/expected_metrics.json) and with the baselines. Used by
tests/scripts/eval_regression_test.sh; --write rewrites the expectations
(scripts/refresh_eval_expectations.sh).

    compare_metrics.py METRICS EXPECTED [--write]

The test pins every processor-dependent kernel to its SSE4.1 level
(tests/scripts/pinned_kernels.sh), so one set of expectations holds on every x86-64
processor and the tolerances stay narrow everywhere.

Exit status 1 when a metric is outside its tolerance (each failure printed on one line).
Beating the baselines is checked and printed metric by metric; metrics that do not beat
them are listed (a tiny network trained for a few steps is not expected to beat a constant
on every map) but only the ones listed in the expectations' "must_beat" fail the test.
"""
import json
import os
import sys

# Per-metric tolerance: |actual - expected| <= abs + rel * |expected|. See docs/eval.md
# ("Regression test") for how they were set.
DEFAULT_TOLERANCE = {"rel": 0.02, "abs": 1e-4}
PIN_VARIABLES = ("DNNL_MAX_CPU_ISA", "ATEN_CPU_CAPABILITY", "GLIBC_TUNABLES", "PHYIR_EMBREE_MAX_ISA")


def kernel_pin():
    """The kernel caps this run was made under (pinned_kernels.sh)."""
    return {k: os.environ.get(k, "") for k in PIN_VARIABLES}


COUNT_KEYS = {"pixels_maps", "pixels_depth", "pixels_rerender", "probes_compared", "relight_positions"}
HIGHER_IS_BETTER = {"probe_ssim", "depth_delta1", "depth_delta2", "depth_delta3"}


def write(expected_path, ours, constant, input_bc):
    """Rewrites the expectations, keeping tolerances and must_beat; returns the exit status."""
    try:
        old = json.load(open(expected_path))
    except (OSError, ValueError):
        old = {}
    beaten = [k for k in ours if k not in COUNT_KEYS and ours[k] is not None and constant.get(k) is not None
              and ((ours[k] > constant[k]) if k in HIGHER_IS_BETTER else (ours[k] < constant[k]))]
    out = {
        "comment": old.get("comment", "phyir eval regression expectations; rewrite with "
                           "scripts/refresh_eval_expectations.sh"),
        "tolerance": old.get("tolerance", DEFAULT_TOLERANCE),
        "tolerance_overrides": old.get("tolerance_overrides", {}),
        "must_beat": old.get("must_beat", sorted(beaten)),
        "recorded_under": kernel_pin(),
        "metrics": ours,
        "baselines": {"constant_mean": constant, "input_as_basecolor": input_bc},
    }
    with open(expected_path, "w") as f:
        json.dump(out, f, indent=2, sort_keys=True)
        f.write("\n")
    print(f"wrote {expected_path} (kernels pinned: {out['recorded_under']})")
    return 0


def main():
    metrics_path, expected_path = sys.argv[1], sys.argv[2]
    metrics = json.load(open(metrics_path))
    ours = metrics["methods"]["prediction"]["mean"]
    constant = metrics["methods"].get("constant_mean", {}).get("mean", {})
    input_bc = metrics["methods"].get("input_as_basecolor", {}).get("mean", {})

    if "--write" in sys.argv:
        return write(expected_path, ours, constant, input_bc)

    expected = json.load(open(expected_path))
    tol, overrides = expected["tolerance"], expected.get("tolerance_overrides", {})
    if expected.get("recorded_under") != kernel_pin():
        print(f"FAIL the kernels are not pinned as when the expectations were recorded: "
              f"{kernel_pin()} against {expected.get('recorded_under')} (tests/scripts/pinned_kernels.sh)")
        return 1
    expected_metrics = expected["metrics"]
    failures = []
    for key, want in sorted(expected_metrics.items()):
        got = ours.get(key)
        if want is None or got is None:
            if (want is None) != (got is None):
                failures.append(f"{key}: expected {want}, got {got}")
            continue
        t = overrides.get(key, tol)
        bound = t["abs"] + t["rel"] * abs(want)
        status = "ok" if abs(got - want) <= bound else "FAIL"
        print(f"  {key:28s} expected {want:.6g}  got {got:.6g}  |diff| {abs(got - want):.3g} <= {bound:.3g}  {status}")
        if status == "FAIL":
            failures.append(f"{key}: expected {want:.6g} +- {bound:.3g}, got {got:.6g}")

    not_beating = []
    for key in sorted(ours):
        if key in COUNT_KEYS or ours[key] is None or constant.get(key) is None:
            continue
        better = ours[key] > constant[key] if key in HIGHER_IS_BETTER else ours[key] < constant[key]
        if not better:
            not_beating.append(key)
    if input_bc.get("basecolor_mse") is not None and ours.get("basecolor_mse") is not None:
        if not ours["basecolor_mse"] < input_bc["basecolor_mse"]:
            not_beating.append("basecolor_mse (vs input as base colour)")
    print("does not beat the constant-mean baseline on: " + (", ".join(not_beating) if not_beating else "nothing"))
    for key in expected.get("must_beat", []):
        if key in not_beating:
            failures.append(f"{key}: no longer beats the constant-mean baseline ({ours[key]:.6g} vs {constant[key]:.6g})")
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
