#!/usr/bin/python3
"""A FutureHouse reader written from the conventions of the published loader
(github.com/LZleejean/FutureHouse, DataSet.py, KePanoMaterial / KePanoLighting), used to check
that `phyir dataset export-futurehouse` writes what code written for FutureHouse expects.

    futurehouse_reader.py EXPORT DATASET

reads every view of EXPORT's split.json as that loader would (OpenImageIO instead of OpenCV:
OpenCV hands over BGR and the loader reverses it, OpenImageIO hands over RGB directly) and
compares it with the phyir DATASET it was exported from. Exit status 0 when every map agrees
to the precision of its file, 1 otherwise (the differences are printed).
"""
import json
import os
import pathlib
import sys

import numpy as np
import OpenImageIO as oiio

MAX_DEPTH = 10.0  # the loader's depth range; files hold depth / (MAX_DEPTH / 2)


def read(path):
    """H x W x C float32, channels in file order."""
    buf = oiio.ImageBuf(str(path))
    if buf.has_error:
        raise RuntimeError(f"{path}: {buf.geterror()}")
    return np.asarray(buf.get_pixels(oiio.FLOAT), dtype=np.float32)


def plan_views(root, plan):
    """How many views the loader finds in a plan: files / 7, or none when not a multiple."""
    folder = root / "KePanoData" / plan / "ue4_result" / "CubemapData"
    if not folder.is_dir():
        return 0
    count = len(os.listdir(folder))
    return count // 7 if count % 7 == 0 else 0


def load_view(root, plan, i, probe_hw):
    folder = root / "KePanoData" / plan / "ue4_result" / "CubemapData"
    def rgb(name):
        return read(folder / f"{i}_{name}.hdr")[..., 0:3]
    def one(name):  # OpenCV's channel 0 of a BGR image: the file's blue channel
        return read(folder / f"{i}_{name}.hdr")[..., 2:3]
    view = {
        "image": rgb("image"),
        "albedo": rgb("albedo"),
        "roughness": one("roughness"),
        "metallic": one("metallic"),
        "mask": one("mask"),
        "normal": rgb("normal") * 2.0 - 1.0,
        "depth": one("depth") * MAX_DEPTH / 2.0,
    }
    d = view["depth"]
    view["depth_mask"] = (d > 0) & (d <= MAX_DEPTH) & ~np.isnan(d)
    light = root / "KePanoLight" / plan / "ue4_result" / "LightProbeData" / f"{i}_light.exr"
    if light.exists():
        mosaic = read(light)[..., 0:3]
        ph, pw = probe_hw
        gh, gw = mosaic.shape[0] // ph, mosaic.shape[1] // pw
        # (3, probe h, probe w, grid h, grid w): the loader's probe tensor before it folds
        # the first three axes into channels.
        view["light"] = mosaic.reshape(gh, ph, gw, pw, 3).transpose(4, 1, 3, 0, 2)
    return view


def close(name, theirs, ours, relative, absolute=1e-6):
    """RGBE keeps 8 bits of the largest channel: |a - b| <= max channel / 128."""
    scale = np.max(np.abs(ours), axis=-1, keepdims=True)
    bad = np.abs(theirs - ours) > relative * scale + absolute
    if bad.any():
        print(f"{name}: {int(bad.sum())} values differ, largest {float(np.abs(theirs - ours).max()):.3g}")
        return False
    return True


def check(export, dataset):
    manifest = json.loads((dataset / "manifest.json").read_text())
    split = json.loads((export / "split.json").read_text())
    probes = manifest["settings"]["probes"]
    probe_hw = tuple(probes["resolution"]) if probes else (16, 32)
    ours = {}
    for v in manifest["views"]:
        ours.setdefault(v["scene"]["name"], []).append(v)
    ok, seen = True, 0
    for mode in ("train", "val", "test"):
        for plan in split.get(mode, []):
            views = ours[plan]
            if views[0]["split"] != mode:
                print(f"{plan}: in {mode}, ours is in {views[0]['split']}")
                ok = False
            if plan_views(export, plan) != len(views):
                print(f"{plan}: the loader finds {plan_views(export, plan)} views, the dataset has {len(views)}")
                ok = False
                continue
            for i, v in enumerate(views):
                fh = load_view(export, plan, i, probe_hw)
                d = dataset / v["dir"]
                geometry = read(d / "mask_geometry.exr")[..., 0:1] > 0.5
                keep = geometry & (read(d / "mask_emissive.exr")[..., 0:1] <= 0.5) & \
                    (read(d / "mask_transparent.exr")[..., 0:1] <= 0.5)
                name = f"{plan} view {i}"
                ok &= close(name + " image", fh["image"], read(d / "color.exr")[..., 0:3], 1 / 128)
                ok &= close(name + " albedo", fh["albedo"], read(d / "basecolor.exr")[..., 0:3], 1 / 128)
                ok &= close(name + " roughness", fh["roughness"], read(d / "roughness.exr"), 1 / 128)
                ok &= close(name + " metallic", fh["metallic"], read(d / "metalness.exr"), 1 / 128)
                ok &= close(name + " depth", fh["depth"], read(d / "depth.exr"), 1 / 128)
                ok &= close(name + " mask", fh["mask"], keep.astype(np.float32), 0)
                n = read(d / "normal.exr")
                # (n + 1) / 2 through RGBE: 2 / 128 per component at most
                ok &= close(name + " normal", fh["normal"] * geometry, n * geometry, 0, 2 / 128 + 1e-6)
                if "light" in fh:
                    mosaic = read(d / "probes.exr")[..., 0:3]
                    ph, pw = probe_hw
                    block = mosaic[ph:2 * ph, 2 * pw:3 * pw]  # probe (1, 2)
                    ok &= close(name + " light", fh["light"][:, :, :, 1, 2].transpose(1, 2, 0), block, 0)
                seen += 1
    print(f"read {seen} views as the published loader would: {'OK' if ok else 'DIFFERENCES'}")
    return ok


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(0 if check(pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])) else 1)
