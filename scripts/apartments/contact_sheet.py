#!/usr/bin/python3
"""One PNG of rendered views: a row per render folder (phyir render --out DIR), the columns
colour (the render's own color.png: OpenColorIO, with the exposure render.json records),
base colour, normal (n * 0.5 + 0.5), depth (0-8 m, near = light), roughness and metalness,
and with --probes N a last tile of N light probes (phyir render --probes) from the grid's
lower middle row, left to right, with color.png's exposure.

    contact_sheet.py --out sheet.png [--width 384] [--probes 4] DIR...

Needs Debian's python3-openimageio and python3-numpy (/usr/bin/python3).
"""
import argparse
import os
import sys

import numpy as np
import OpenImageIO as oiio

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from phyir_view import COLOR_PREVIEW_FILE, RENDER_RECORD_FILE, map_file, preview_exposure_stops, read_probes  # noqa: E402

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
    if column == "color":
        return as_rgb(read(os.path.join(folder, COLOR_PREVIEW_FILE)))  # OIIO gives 8-bit as [0, 1]
    image = as_rgb(read(os.path.join(folder, map_file(column))))
    if column == "basecolor":
        return srgb(image)
    if column == "normal":
        return np.clip(image * 0.5 + 0.5, 0.0, 1.0)
    if column == "depth":
        return np.clip(1.0 - image / 8.0, 0.0, 1.0)
    return np.clip(image, 0.0, 1.0)


def probe_tile(folder, count, colour_scale):
    """`count` probes of the grid row at 60% of its height, evenly across, in a 2-row mosaic."""
    probes, mask = read_probes(folder)
    grid_h, grid_w, h, w = probes.shape[:4]
    i = int(grid_h * 0.6)
    picked = []
    for k in range(count):
        j = int((k + 0.5) * grid_w / count)
        block = probes[i, j] if mask[i, j, 0] > 0 else np.zeros((h, w, 3))
        picked.append(srgb(block * colour_scale))
    rows = [np.concatenate(picked[r::2], axis=1) for r in range(2)] if count > 1 else picked
    return np.concatenate(rows, axis=0)


def colour_scale(folder):
    """color.png's exposure (render.json), as a factor on linear radiance."""
    try:
        stops = preview_exposure_stops(folder)
    except (OSError, ValueError, KeyError) as error:
        sys.exit(f"{os.path.join(folder, RENDER_RECORD_FILE)}: no color_png exposure ({error})")
    return 2.0 ** stops


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
    parser.add_argument("--probes", type=int, default=0, help="light probes shown per row (even; 0: none)")
    args = parser.parse_args()
    rows = []
    for f in args.folders:
        tiles = [resized(tile(f, c), args.width) for c in COLUMNS]
        if args.probes > 0:
            mosaic = probe_tile(f, args.probes, colour_scale(f))
            tiles.append(resized(mosaic, tiles[0].shape[0] * mosaic.shape[1] // mosaic.shape[0]))
        rows.append(np.concatenate(tiles, axis=1))
    # Resizing filters overshoot past [0, 1] at sharp edges: clip before the 8-bit cast wraps.
    sheet = (np.clip(np.concatenate(rows, axis=0), 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)
    out = oiio.ImageBuf(oiio.ImageSpec(sheet.shape[1], sheet.shape[0], 3, oiio.UINT8))
    out.set_pixels(oiio.ROI(), sheet)
    tmp = args.out + ".tmp.png"
    if not out.write(tmp):
        sys.exit(f"{args.out}: cannot write ({out.geterror()})")
    os.replace(tmp, args.out)
    columns = list(COLUMNS) + ([f"{args.probes} probes"] if args.probes else [])
    print(f"wrote {args.out}: {len(rows)} rows x {len(columns)} columns ({', '.join(columns)})")


if __name__ == "__main__":
    main()
