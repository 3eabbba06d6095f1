#!/usr/bin/python3
"""One PNG of rendered views: a row per render folder (phyir render --out DIR), the columns
colour (exposed so the 95th percentile of luminance maps to 0.8 before the sRGB curve),
base colour, normal (n * 0.5 + 0.5), depth (0-8 m, near = light), roughness and metalness.

    contact_sheet.py --out sheet.png [--labels "a,b,c"] [--width 384] DIR...

Needs Debian's python3-openimageio and python3-numpy (/usr/bin/python3).
"""
import argparse
import os
import sys

import numpy as np
import OpenImageIO as oiio

COLUMNS = ("color", "basecolor", "normal", "depth", "roughness", "metalness")


def read(path):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit(f"{path}: cannot read ({buf.geterror()})")
    return buf.get_pixels(oiio.FLOAT)


def srgb(linear):
    linear = np.clip(linear, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1 / 2.4) - 0.055)


def as_rgb(image):
    return np.repeat(image[..., :1], 3, axis=2) if image.shape[2] == 1 else image[..., :3]


def tile(folder, column):
    image = as_rgb(read(os.path.join(folder, f"{column}.exr")))
    if column == "color":
        luminance = image @ np.array([0.2126, 0.7152, 0.0722])
        p95 = np.percentile(luminance, 95)
        return srgb(image * (0.8 / p95 if p95 > 0 else 1.0))
    if column == "basecolor":
        return srgb(image)
    if column == "normal":
        return np.clip(image * 0.5 + 0.5, 0.0, 1.0)
    if column == "depth":
        return np.clip(1.0 - image / 8.0, 0.0, 1.0)
    return np.clip(image, 0.0, 1.0)


def resized(image, width):
    height = int(round(image.shape[0] * width / image.shape[1]))
    src = oiio.ImageBuf(oiio.ImageSpec(image.shape[1], image.shape[0], 3, oiio.FLOAT))
    src.set_pixels(oiio.ROI(), np.ascontiguousarray(image, np.float32))
    dst = oiio.ImageBufAlgo.resize(src, roi=oiio.ROI(0, width, 0, height, 0, 1, 0, 3))
    return dst.get_pixels(oiio.FLOAT)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folders", nargs="+")
    parser.add_argument("--out", required=True)
    parser.add_argument("--width", type=int, default=384, help="width of one tile in pixels")
    args = parser.parse_args()
    rows = [np.concatenate([resized(tile(f, c), args.width) for c in COLUMNS], axis=1) for f in args.folders]
    sheet = (np.concatenate(rows, axis=0) * 255.0 + 0.5).astype(np.uint8)
    out = oiio.ImageBuf(oiio.ImageSpec(sheet.shape[1], sheet.shape[0], 3, oiio.UINT8))
    out.set_pixels(oiio.ROI(), sheet)
    tmp = args.out + ".tmp.png"
    if not out.write(tmp):
        sys.exit(f"{args.out}: cannot write ({out.geterror()})")
    os.replace(tmp, args.out)
    print(f"wrote {args.out}: {len(rows)} rows x {len(COLUMNS)} columns ({', '.join(COLUMNS)})")


if __name__ == "__main__":
    main()
