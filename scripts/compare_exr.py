#!/usr/bin/python3
"""Compares every EXR under BEFORE with the file of the same relative path under AFTER, pixel
for pixel (scripts/bit_identity.sh). Prints the files that differ, with their largest absolute
difference, relative RMSE (RMSE / mean |before|) and how many values differ; exits 1 if any
file differs or is missing, 0 if all are bit-identical.

    /usr/bin/python3 scripts/compare_exr.py BEFORE AFTER
"""
import glob
import os
import sys

import numpy as np
import OpenImageIO as oiio


def read(path):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit(f"compare_exr.py: {path}: {buf.geterror()}")
    return buf.get_pixels(oiio.FLOAT)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    before, after = sys.argv[1], sys.argv[2]
    files = sorted(glob.glob(os.path.join(before, "**", "*.exr"), recursive=True))
    if not files:
        sys.exit(f"compare_exr.py: no EXR files under {before}")
    differ = 0
    for path in files:
        rel = os.path.relpath(path, before)
        other = os.path.join(after, rel)
        if not os.path.exists(other):
            print(f"MISSING {rel}")
            differ += 1
            continue
        a, b = read(path), read(other)
        if a.shape != b.shape:
            print(f"DIFFERS {rel}: shape {a.shape} vs {b.shape}")
            differ += 1
        elif not np.array_equal(a, b, equal_nan=True):
            d = np.abs(a.astype(np.float64) - b)
            rel_rmse = np.sqrt(np.mean(d * d)) / max(float(np.mean(np.abs(a))), 1e-30)
            print(f"DIFFERS {rel}: largest {d.max():.3g}, relative RMSE {rel_rmse:.3g}, "
                  f"{np.count_nonzero(d)} of {d.size} values")
            differ += 1
    print(f"{len(files)} files, {differ} differ" + ("" if differ else ": bit-identical"))
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
