#!/usr/bin/python3
"""Load one view of a phyir dataset into numpy arrays (docs/python.md).

    /usr/bin/python3 scripts/load_dataset_example.py DATA [--split train] [--view 0] [--save view.npz]

Reads DATA/manifest.json, picks a split, loads one view's maps and light probes as float32
arrays (H x W x C, as the files hold them), checks each file's SHA-256 against the manifest,
reshapes the probe mosaic into [H, W, h, w, 3] and prints what it loaded. Needs Debian's
python3-openimageio and python3-numpy, which load only in /usr/bin/python3.
"""
import argparse
import hashlib
import json
import sys
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

# The maps of a view folder (docs/conventions.md) and their channels.
MAPS = {
    "color": 3,             # HDR radiance, linear Rec.709
    "depth": 1,             # Euclidean distance, metres (0: nothing seen)
    "normal": 3,            # world space, unit length, +Y up
    "basecolor": 3,         # linear
    "roughness": 1,         # perceptual roughness (GGX alpha = R^2)
    "metalness": 1,
    "mask_geometry": 1,     # 1: a surface is seen
    "mask_emissive": 1,     # 1: an emitter is seen
    "mask_transparent": 1,  # 1: a transmissive surface is seen
}


def read_image(path):
    """H x W x C float32. PNGs arrive in [0, 1], still sRGB-encoded; EXRs as stored."""
    image = oiio.ImageInput.open(str(path))
    if image is None:
        raise IOError(f"{path}: {oiio.geterror()}")
    try:
        spec = image.spec()
        pixels = image.read_image("float")
    finally:
        image.close()
    if pixels is None:
        raise IOError(f"{path}: cannot decode")
    return np.asarray(pixels, dtype=np.float32).reshape(spec.height, spec.width, spec.nchannels)


def sha256(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def probes_from_mosaic(mosaic, grid, resolution):
    """probes.exr holds probe (i, j) as the h x w block at rows i h.., columns j w..:
    [H h, W w, 3] -> [H, W, h, w, 3]."""
    (H, W), (h, w) = grid, resolution
    if mosaic.shape[:2] != (H * h, W * w):
        raise ValueError(f"probe mosaic is {mosaic.shape[1]}x{mosaic.shape[0]}, expected {W * w}x{H * h}")
    return mosaic[:, :, :3].reshape(H, h, W, w, 3).transpose(0, 2, 1, 3, 4)


def load_view(root, manifest, view, check=True):
    """Every array of one view (a manifest entry); with `check`, sizes and checksums first."""
    folder = root / view["dir"]
    for f in view["files"] if check else []:  # the manifest's record of each file
        path = folder / f["path"]
        if path.stat().st_size != f["size"] or sha256(path) != f["sha256"]:
            raise IOError(f"{path}: does not match the manifest (run 'phyir dataset verify {root}')")
    sample = {name: read_image(folder / f"{name}.exr") for name in MAPS}
    for name, channels in MAPS.items():
        if sample[name].shape[2] != channels:
            raise ValueError(f"{folder / name}.exr: {sample[name].shape[2]} channels, expected {channels}")
    sample["input"] = read_image(folder / view["input"]["file"])  # the network's LDR input
    probes = manifest["settings"]["probes"]
    if probes:  # null when the dataset was made with --no-probes
        sample["probes"] = probes_from_mosaic(read_image(folder / "probes.exr"), probes["grid"],
                                              probes["resolution"])
        sample["probe_mask"] = read_image(folder / "probe_mask.exr")  # H x W x 1: 1 = valid probe
    return sample


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("data", type=Path, help="dataset folder holding manifest.json")
    parser.add_argument("--split", default="train", help="train, val or test ('' = all views)")
    parser.add_argument("--view", type=int, default=0, help="index of the view within the split")
    parser.add_argument("--save", type=Path, help="also save the arrays to this .npz file")
    args = parser.parse_args()

    manifest_path = args.data / "manifest.json"
    if not manifest_path.is_file():
        sys.exit(f"{manifest_path}: missing (the dataset is not finished: run the same "
                 "'phyir dataset generate' command again)")
    manifest = json.loads(manifest_path.read_text())
    # Read the view list from the manifest, not by scanning folders: only it knows the splits
    # and it never lists a half-written view.
    views = [v for v in manifest["views"] if not args.split or v["split"] == args.split]
    counts = {s: sum(v["split"] == s for v in manifest["views"]) for s in ("train", "val", "test")}
    print(f"{manifest_path}: {len(manifest['views'])} views "
          + ", ".join(f"{s} {n}" for s, n in counts.items()))
    if not 0 <= args.view < len(views):
        sys.exit(f"{manifest_path}: split '{args.split}' has {len(views)} views; --view {args.view} is out of range")
    view = views[args.view]
    sample = load_view(args.data, manifest, view)
    print(f"view {view['id']} (split {view['split']}, seed {view['seed']}, "
          f"exposure {view['input']['exposure_stops']:+.2f} stops, camera {view['viewpoint']['position']})")
    for name, array in sample.items():
        print(f"  {name:17s} {str(array.shape):22s} {array.dtype}  min {array.min():.4g}  max {array.max():.4g}")
    if args.save:
        np.savez(args.save, **sample)
        print(f"wrote {args.save}")


if __name__ == "__main__":
    main()
