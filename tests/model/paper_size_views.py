# A dataset for measuring the training reader at the paper's sizes (docs/model-scale.md
# "Streaming"): ROOT/source, one synthetic view folder (panorama 512x256, a 128x256 grid of 16x32
# probes, smooth content), and ROOT/views/v0000... N folders linking to its files (the page
# cache is shared, each view's decoding is real). Usage: /usr/bin/python3 paper_size_views.py ROOT N
import os, sys, json, numpy as np, OpenImageIO as oiio
root, n = sys.argv[1], int(sys.argv[2])
src = os.path.join(root, "source")
os.makedirs(src, exist_ok=True)
H, W, gh, gw, ph, pw = 256, 512, 128, 256, 16, 32
y, x = np.mgrid[0:H, 0:W].astype(np.float32)
def write(name, arr, fmt=oiio.FLOAT):
    arr = np.ascontiguousarray(arr.astype(np.float32))
    if arr.ndim == 2: arr = arr[..., None]
    spec = oiio.ImageSpec(arr.shape[1], arr.shape[0], arr.shape[2], fmt)
    if name.endswith(".exr"): spec.attribute("compression", "zip")
    out = oiio.ImageOutput.create(os.path.join(src, name))
    out.open(os.path.join(src, name), spec); out.write_image(arr); out.close()
col = np.stack([0.5 + 0.4*np.sin(x/40), 0.5 + 0.4*np.cos(y/30), 0.5 + 0.2*np.sin((x+y)/50)], -1)
write("color.exr", col * 1.5)
write("input.png", np.clip(col, 0, 1) ** (1/2.2), oiio.UINT8)
write("depth.exr", 2 + np.sin(x/60))
n3 = np.stack([np.sin(x/80), np.cos(y/90), np.ones_like(x)], -1); n3 /= np.linalg.norm(n3, axis=-1, keepdims=True)
write("normal.exr", n3)
write("basecolor.exr", col * 0.8)
write("roughness.exr", 0.5 + 0.3*np.sin(y/20))
write("metalness.exr", (np.sin(x/70) > 0.5).astype(np.float32))
write("mask_geometry.exr", np.ones((H, W)))
write("mask_emissive.exr", np.zeros((H, W)))
write("mask_transparent.exr", np.zeros((H, W)))
py, px = np.mgrid[0:gh*ph, 0:gw*pw].astype(np.float32)
write("probes.exr", np.stack([1 + 0.5*np.sin(px/97), 1 + 0.5*np.cos(py/53), 1 + 0.3*np.sin((px+py)/71)], -1))
write("probe_mask.exr", np.ones((gh, gw)))
json.dump({"input": {"exposure_stops": -0.5, "view": "Standard"}}, open(os.path.join(src, "view.json"), "w"))
views = os.path.join(root, "views")
os.makedirs(views, exist_ok=True)
for i in range(n):
    d = os.path.join(views, "v%04d" % i)
    os.makedirs(d, exist_ok=True)
    for f in os.listdir(src):
        if not os.path.exists(os.path.join(d, f)): os.symlink(os.path.join(src, f), os.path.join(d, f))
print("ok", n)
