"""The view folder's on-disk contract in Python (docs/conventions.md, "View folders"): the
file names, the probe mosaic's layout, the exposure records and the manifest's views. The
names are read from the toolkit's C++ view module (view/include/phyir/view/), the one
definition, so a Python reader never spells a file name or a record key of its own.

Needs Debian's python3-openimageio and python3-numpy (they load only in /usr/bin/python3).
"""
import hashlib
import json
import os
import re
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

# The maps of a view folder and their channels (as `phyir render` writes them).
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

def _header_constants(*headers):
    """The string constants (`inline constexpr const char* kName = "value";`) of the view
    module's C++ headers: the one definition of the contract, read rather than copied."""
    root = Path(os.environ.get("PHYIR_SOURCE_ROOT", Path(__file__).resolve().parent.parent))
    folder = root / "view" / "include" / "phyir" / "view"
    constants = {}
    for header in headers:
        path = folder / header
        if not path.is_file():
            raise ImportError(f"{path}: missing (phyir_view.py reads the file names from the toolkit's sources: "
                              "keep it in the checkout's scripts/ or set PHYIR_SOURCE_ROOT)")
        constants.update(re.findall(r'inline constexpr const char\* (k\w+) = "([^"]*)";', path.read_text()))
    return constants


_C = _header_constants("view_files.h", "input_exposure.h", "view_record.h")
PROBES_FILE = _C["kProbesFile"]
PROBE_MASK_FILE = _C["kProbeMaskFile"]
COLOR_PREVIEW_FILE = _C["kColorPreviewFile"]
INPUT_FILE = _C["kInputFile"]
RENDER_RECORD_FILE = _C["kRenderRecordFile"]
VIEW_RECORD_FILE = _C["kViewRecordFile"]
MANIFEST_FILE = _C["kManifestFile"]
EXPOSURE_STOPS_KEY = _C["kExposureStopsKey"]


def map_file(name):
    """The file of a map of MAPS: 'depth' -> 'depth.exr'."""
    return f"{name}.exr"


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


def read_probes(folder):
    """probes.exr + probe_mask.exr: probe (i, j) is the h x w block at rows i h.., columns j w..
    of the mosaic, the grid H x W is probe_mask.exr's size. Returns ([H, W, h, w, 3], the mask
    H x W x 1: 1 = a valid label)."""
    folder = Path(folder)
    mosaic = read_image(folder / PROBES_FILE)[..., :3]
    mask = read_image(folder / PROBE_MASK_FILE)[..., :1]
    H, W = mask.shape[:2]
    if mosaic.shape[0] % H or mosaic.shape[1] % W:
        raise ValueError(f"{folder / PROBES_FILE}: {mosaic.shape[1]}x{mosaic.shape[0]} is not a whole number "
                         f"of probes of the {W}x{H} grid of {PROBE_MASK_FILE}")
    h, w = mosaic.shape[0] // H, mosaic.shape[1] // W
    return mosaic.reshape(H, h, W, w, 3).transpose(0, 2, 1, 3, 4), mask


def input_exposure_stops(view):
    """The input image's exposure in stops from a view record (view.json or a manifest entry);
    input.png = sRGB(clip(2^stops x color.exr))."""
    return view["input"][EXPOSURE_STOPS_KEY]


def preview_exposure_stops(folder):
    """color.png's exposure in stops, from the folder's render.json."""
    return json.loads((Path(folder) / RENDER_RECORD_FILE).read_text())["color_png"][EXPOSURE_STOPS_KEY]


def read_manifest(root):
    """The dataset's manifest.json; IOError when the run that writes it has not finished."""
    path = Path(root) / MANIFEST_FILE
    if not path.is_file():
        raise IOError(f"{path}: missing (the dataset is not finished: run the same "
                      "'phyir dataset generate' command again)")
    return json.loads(path.read_text())


def check_files(root, view):
    """Every file of a view against the manifest's size and SHA-256."""
    folder = Path(root) / view["dir"]
    for f in view["files"]:
        path = folder / f["path"]
        if path.stat().st_size != f["size"] or sha256(path) != f["sha256"]:
            raise IOError(f"{path}: does not match the manifest (run 'phyir dataset verify {root}')")
