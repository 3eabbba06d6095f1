#!/usr/bin/python3
"""Load one view of a phyir dataset into numpy arrays (docs/python.md).

    /usr/bin/python3 scripts/load_dataset_example.py DATA [--split train] [--view 0] [--save view.npz]

Reads DATA/manifest.json, picks a split, loads one view's maps and light probes as float32
arrays (H x W x C, as the files hold them), checks each file's SHA-256 against the manifest,
reshapes the probe mosaic into [H, W, h, w, 3] and prints what it loaded. Needs Debian's
python3-openimageio and python3-numpy, which load only in /usr/bin/python3.
"""
import argparse
import sys
from pathlib import Path

import numpy as np

from phyir_view import MANIFEST_FILE, MAPS, check_files, input_exposure_stops, map_file, read_image, read_manifest, read_probes


def load_view(root, manifest, view, check=True):
    """Every array of one view (a manifest entry); with `check`, sizes and checksums first."""
    folder = root / view["dir"]
    if check:
        check_files(root, view)
    sample = {name: read_image(folder / map_file(name)) for name in MAPS}
    for name, channels in MAPS.items():
        if sample[name].shape[2] != channels:
            raise ValueError(f"{folder / map_file(name)}: {sample[name].shape[2]} channels, expected {channels}")
    sample["input"] = read_image(folder / view["input"]["file"])  # the network's LDR input
    if manifest["settings"]["probes"]:  # null when the dataset was made with --no-probes
        sample["probes"], sample["probe_mask"] = read_probes(folder)  # [H, W, h, w, 3], [H, W, 1]: 1 = valid
    return sample


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("data", type=Path, help="dataset folder holding manifest.json")
    parser.add_argument("--split", default="train", help="train, val or test ('' = all views)")
    parser.add_argument("--view", type=int, default=0, help="index of the view within the split")
    parser.add_argument("--save", type=Path, help="also save the arrays to this .npz file")
    args = parser.parse_args()

    try:
        manifest = read_manifest(args.data)
    except IOError as error:
        sys.exit(str(error))
    manifest_path = args.data / MANIFEST_FILE
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
          f"exposure {input_exposure_stops(view):+.2f} stops, camera {view['viewpoint']['position']})")
    for name, array in sample.items():
        print(f"  {name:17s} {str(array.shape):22s} {array.dtype}  min {array.min():.4g}  max {array.max():.4g}")
    if args.save:
        np.savez(args.save, **sample)
        print(f"wrote {args.save}")


if __name__ == "__main__":
    main()
