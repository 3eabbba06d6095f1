#!/usr/bin/python3
"""The Blender-exported lit room against Cycles: variants, mean radiance, block z-scores, figures.

    lit_room_agreement.py variants --gltf lit_room.gltf --out RUNS/scenes
    lit_room_agreement.py downsample --dir RUNS/phyir/<variant>_s<seed> --factor K
    lit_room_agreement.py report --runs RUNS [--figures docs/figures] [--name cycles_lit_room]
        [--block 8] [--variants lit_room,no_spot,spot_only,...]

`variants` writes copies of the room (same JSON, same buffers and textures, copied beside
them) in which some lights' nodes lose their KHR_lights_punctual reference, so those lights
are declared but placed nowhere: `no_spot.gltf` (point and sun), `spot_only.gltf` (spot).

`report` reads RUNS/phyir/<variant>_s<seed>/color.exr and RUNS/cycles/<variant>_s<seed>.exr
(two seeds each, made by compare_lit_room.sh) and, per variant:
- the mean radiance (R, G, B over all pixels) of each renderer, both seeds averaged, and
  the ratio phyir / Cycles;
- block statistics: the image is cut into BxB-pixel blocks; per block and renderer the mean
  of the two seeds and its variance, estimated from the two seeds' pixel differences: the sum
  over the block's pixels of (a1 - a2)^2 / 4, over the pixel count squared (pixels are
  independent in both renderers, so the estimate has up to B^2 degrees of freedom, not the
  one of the block's own two means); z = (mean_phyir - mean_cycles) / sqrt(var_phyir +
  var_cycles) on the block's channel mean (R + G + B) / 3. Reported: the fraction of blocks
  with |z| > 3, the largest |z| and its block's direction, the relative RMSE of the block
  means (sqrt(mean((p - c)^2)) / mean(c), over blocks and channels) and what noise alone would
  give (sqrt(mean(var_p + var_c)) / mean(c)). Fireflies make the noise heavy-tailed, so z is
  not Gaussian even without any bias: the same statistic is computed for a null test,
  ((phyir 1 - Cycles 1) - (phyir 2 - Cycles 2)) / 2, which has the same noise as the
  difference of the two-seed averages and no bias whatever the renderers disagree on;
- for the spot variants, the falloff each renderer should have (glTF t^2 against Cycles
  3.4's cos(theta) smoothstep, docs/cycles-comparison-blender-exports.md) at every pixel's first hit (from
  phyir's depth AOV), and the image ratio Cycles / phyir binned by that angle.
Writes FIGURES/NAME.png (difference and z maps), FIGURES/NAME.json and FIGURES/NAME.csv.
"""
import argparse
import csv
import json
import math
import os
import shutil
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare import camera_position, node_matrix, read_exr  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Which lights each variant keeps (by light name in the extension's list).
VARIANT_LIGHTS = {"no_spot": {"lamp_point", "sun"}, "spot_only": {"spot"}}


# --- supersampled phyir renders ------------------------------------------------------------------

def write_exr(path, image, channels):
    import OpenImageIO as oiio
    spec = oiio.ImageSpec(image.shape[1], image.shape[0], image.shape[2], oiio.FLOAT)
    spec.channelnames = channels
    tmp = path + ".tmp.exr"
    out = oiio.ImageOutput.create(tmp)
    if out is None or not out.open(tmp, spec) or not out.write_image(np.ascontiguousarray(image, np.float32)):
        sys.exit(f"{path}: cannot write ({oiio.geterror()})")
    out.close()
    os.replace(tmp, path)


def downsample(args):
    """DIR/supersampled/ (a render at FACTOR x the size) -> DIR/: colour averaged over each
    FACTOR x FACTOR block (a box filter, as the pixel filter of both renderers), depth and
    metalness taken from the sample at the block's centre (they only classify surfaces)."""
    k, src = args.factor, os.path.join(args.dir, "supersampled")
    colour = read_exr(os.path.join(src, "color.exr"))
    h, w = colour.shape[0] // k, colour.shape[1] // k
    write_exr(os.path.join(args.dir, "color.exr"), colour.reshape(h, k, w, k, 3).mean(axis=(1, 3)), ("R", "G", "B"))
    for name in ("depth", "metalness"):
        aov = read_exr(os.path.join(src, f"{name}.exr"), channels=("Y",))
        write_exr(os.path.join(args.dir, f"{name}.exr"), aov[k // 2::k, k // 2::k], ("Y",))
    shutil.copy(os.path.join(src, "render.json"), os.path.join(args.dir, "render.json"))


# --- variants ------------------------------------------------------------------------------------

def write_variants(gltf_path, out):
    with open(gltf_path) as f:
        gltf = json.load(f)
    names = [light.get("name", f"light {i}")
             for i, light in enumerate(gltf["extensions"]["KHR_lights_punctual"]["lights"])]
    os.makedirs(out, exist_ok=True)
    source_dir = os.path.dirname(os.path.abspath(gltf_path))
    uris = [b["uri"] for b in gltf.get("buffers", []) if "uri" in b] + \
           [i["uri"] for i in gltf.get("images", []) if "uri" in i]
    for uri in uris:
        if uri.startswith("data:"):
            continue
        target = os.path.join(out, uri)
        if not os.path.exists(target):
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copyfile(os.path.join(source_dir, uri), target)
    for variant, keep in VARIANT_LIGHTS.items():
        copy = json.loads(json.dumps(gltf))
        kept = []
        for node in copy["nodes"]:
            ref = node.get("extensions", {}).get("KHR_lights_punctual")
            if ref is None:
                continue
            if names[ref["light"]] in keep:
                kept.append(names[ref["light"]])
            else:
                del node["extensions"]["KHR_lights_punctual"]
                if not node["extensions"]:
                    del node["extensions"]
        if sorted(kept) != sorted(keep):
            sys.exit(f"{gltf_path}: variant {variant} should keep lights {sorted(keep)}, found {sorted(kept)}")
        path = os.path.join(out, variant + ".gltf")
        with open(path, "w") as f:
            json.dump(copy, f, indent=2)
        print(f"{path}: lights {', '.join(sorted(kept))}")



# --- the spot's falloff: glTF (phyir) against Cycles 3.4 ----------------------------------------

def spot_light(gltf_path):
    """Position, unit direction (node -Z), inner and outer cone angles of the scene's spot."""
    with open(gltf_path) as f:
        gltf = json.load(f)
    lights = gltf["extensions"]["KHR_lights_punctual"]["lights"]
    for node in gltf["nodes"]:  # the room's light nodes are scene roots
        ref = node.get("extensions", {}).get("KHR_lights_punctual")
        if ref is not None and lights[ref["light"]]["type"] == "spot":
            m = node_matrix(node)
            axis = m[:3, :3] @ np.array([0.0, 0.0, -1.0])
            spot = lights[ref["light"]].get("spot", {})
            return {"position": m[:3, 3], "axis": axis / np.linalg.norm(axis),
                    "inner": spot.get("innerConeAngle", 0.0), "outer": spot.get("outerConeAngle", math.pi / 4)}
    return None


def falloff_gltf(theta, inner, outer):
    """KHR_lights_punctual's ramp, as phyir renders it: t^2, t = clamp((cos - cos outer) / (cos inner - cos outer))."""
    t = np.clip((np.cos(theta) - math.cos(outer)) / max(1e-3, math.cos(inner) - math.cos(outer)), 0.0, 1.0)
    return t * t


def falloff_cycles(theta, inner, outer):
    """Cycles 3.4's spot with the importer's spot_size = 2 outer, spot_blend = 1 - inner / outer:
    cos(theta) x smoothstep(x), x = (cos - cos outer) / ((1 - cos outer) spot_blend)."""
    blend = 1.0 - inner / outer
    x = (np.cos(theta) - math.cos(outer)) / ((1.0 - math.cos(outer)) * blend)
    x = np.clip(x, 0.0, 1.0)
    return np.cos(theta) * x * x * (3.0 - 2.0 * x) * (np.cos(theta) > math.cos(outer))


def spot_power_ratio(inner, outer, n=200000):
    """Power into the cone, Cycles / glTF: integral of the falloff over solid angle."""
    theta = (np.arange(n) + 0.5) / n * outer
    w = np.sin(theta)
    return float(np.sum(falloff_cycles(theta, inner, outer) * w) / np.sum(falloff_gltf(theta, inner, outer) * w))


def pixel_directions(width, height):
    """Unit directions of the pixel centres (docs/conventions.md, equirectangular mapping)."""
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    phi = 2.0 * math.pi * (u - 0.5)
    theta = math.pi * v
    d = np.empty((height, width, 3))
    d[..., 0] = np.sin(theta)[:, None] * np.sin(phi)[None, :]
    d[..., 1] = np.cos(theta)[:, None] * np.ones(width)[None, :]
    d[..., 2] = -np.sin(theta)[:, None] * np.cos(phi)[None, :]
    return d


def spot_angles(depth_path, camera, spot):
    """Angle from the spot's axis (radians) of every pixel's first hit; NaN where the ray escapes."""
    depth = read_exr(depth_path, channels=("Y",))[..., 0].astype(np.float64)
    h, w = depth.shape
    hit = np.asarray(camera)[None, None, :] + depth[..., None] * pixel_directions(w, h)
    to_hit = hit - spot["position"][None, None, :]
    cos = np.einsum("ijk,k->ij", to_hit, spot["axis"]) / np.linalg.norm(to_hit, axis=2)
    angles = np.arccos(np.clip(cos, -1.0, 1.0))
    angles[~(np.isfinite(depth) & (depth > 0) & (depth < 1e3))] = np.nan
    return angles


# --- the specular lobe: our BRDF's terms against Cycles' ---------------------------------------

def specular_albedo(roughness, f0=0.04, n=200000, seed=1):
    """Albedo of a dielectric's GGX lobe (F0 = 0.04) under uniform light, ours against Cycles'.

    Ours (docs/brdf.md): Schlick-Smith G1 with k = (R + 1)^2 / 8 and the spherical-Gaussian
    Schlick Fresnel. Cycles 3.4's GGX with the Principled BSDF of metallic 1 and base colour
    0.04 that render_cycles.py --materials ue4 builds: separable exact Smith G1 (alpha = R^2)
    and the dielectric Fresnel of IOR 1.5 (Principled v1 interpolates to it from F0 = 0.04).
    Returns the directional albedo at cos(theta_o) 0.2, 0.5, 0.9 and the cosine-weighted
    hemispherical mean (the albedo seen by diffuse interreflection), for each.
    """
    rng = np.random.default_rng(seed)
    a2 = roughness ** 4
    k = (roughness + 1.0) ** 2 / 8.0

    def directional(mu_o):
        u1, u2 = rng.random(n), rng.random(n)
        ct = np.sqrt((1.0 - u1) / (1.0 + (a2 - 1.0) * u1))  # GGX-distributed half vectors
        st, ph = np.sqrt(1.0 - ct * ct), 2.0 * math.pi * u2
        h = np.stack([st * np.cos(ph), st * np.sin(ph), ct], axis=1)
        v = np.array([math.sqrt(1.0 - mu_o * mu_o), 0.0, mu_o])
        vh = h @ v
        nl = (2.0 * vh[:, None] * h - v)[:, 2]
        ok = (nl > 0) & (vh > 0)
        nl, vh_c = np.clip(nl, 1e-9, 1.0), np.clip(vh, 0.0, 1.0)
        weight = np.where(ok, vh_c / (mu_o * ct), 0.0)  # f cos / pdf, without F G
        g1_ours = lambda x: x / (x * (1.0 - k) + k)
        g1_cycles = lambda x: 2.0 / (1.0 + np.sqrt(1.0 + a2 * (1.0 - x * x) / (x * x)))
        f_ours = f0 + (1.0 - f0) * np.exp2((-5.55473 * vh_c - 6.98316) * vh_c)
        g = np.sqrt(1.5 ** 2 - 1.0 + vh_c ** 2)  # dielectric Fresnel, IOR 1.5
        f_cycles = 0.5 * ((g - vh_c) / (g + vh_c)) ** 2 * (1.0 + ((vh_c * (g + vh_c) - 1.0) / (vh_c * (g - vh_c) + 1.0)) ** 2)
        return (float(np.mean(weight * f_ours * g1_ours(mu_o) * g1_ours(nl))),
                float(np.mean(weight * f_cycles * g1_cycles(mu_o) * g1_cycles(nl))))

    out = {f"cos_o_{mu}": dict(zip(("ours", "cycles"), directional(mu))) for mu in (0.2, 0.5, 0.9)}
    nodes, weights = np.polynomial.legendre.leggauss(12)
    mus = 0.5 * (nodes + 1.0)
    values = np.array([directional(mu) for mu in mus])
    mean = (weights * mus) @ values  # 2 * integral of A(mu) mu dmu over [0, 1]
    out["hemispherical"] = {"ours": float(mean[0]), "cycles": float(mean[1])}
    return out


# --- statistics ----------------------------------------------------------------------------------

def block_sums(image, block):
    h, w = image.shape[:2]
    return image.reshape(h // block, block, w // block, block, -1).sum(axis=(1, 3))


def block_stats(p1, p2, c1, c2, block):
    """Block means of the two seeds' average and their variance, per renderer.

    The variance of a block's mean is estimated from the two seeds' pixel differences,
    sum over the block's pixels of (a1 - a2)^2 / 4, divided by the pixel count squared:
    pixels are independent in both renderers, so this has up to B^2 degrees of freedom
    (the block's own two-seed difference would have one). Channel mean (R + G + B) / 3.
    """
    n = block * block
    out = {}
    for key, a1, a2 in (("p", p1, p2), ("c", c1, c2)):
        g1, g2 = a1.mean(axis=2, keepdims=True), a2.mean(axis=2, keepdims=True)
        out[key + "_mean"] = block_sums(0.5 * (g1 + g2), block)[..., 0] / n
        out[key + "_var"] = block_sums(0.25 * (g1 - g2) ** 2, block)[..., 0] / n ** 2
        out[key + "_half_diff"] = block_sums(0.5 * (g1 - g2), block)[..., 0] / n  # (s1 - s2) / 2
        out[key + "_rgb"] = block_sums(0.5 * (a1 + a2), block) / n
        out[key + "_var_rgb"] = block_sums(0.25 * (a1 - a2) ** 2, block) / n ** 2
    sigma = np.sqrt(out["p_var"] + out["c_var"])
    with np.errstate(divide="ignore", invalid="ignore"):
        out["z"] = np.where(sigma > 0, (out["p_mean"] - out["c_mean"]) / sigma, np.nan)
        # Null test: (phyir 1 - Cycles 1) - (phyir 2 - Cycles 2), halved, has the same noise as
        # the difference of the averages and no bias whatever the renderers disagree on.
        out["z_null"] = np.where(sigma > 0, (out["p_half_diff"] - out["c_half_diff"]) / sigma, np.nan)
    return out


def z_summary(z, label):
    valid = np.isfinite(z)
    a = np.abs(np.where(valid, z, 0.0))
    j, i = np.unravel_index(int(np.argmax(a)), a.shape)
    return {f"{label}_blocks": int(valid.sum()),
            f"{label}_fraction_above_3": float((a[valid] > 3).mean()) if valid.any() else float("nan"),
            f"{label}_fraction_above_2": float((a[valid] > 2).mean()) if valid.any() else float("nan"),
            f"{label}_max_abs": float(a.max()), f"{label}_max_at_block": [int(j), int(i)]}


def analyse_variant(runs, variant, seeds, block, camera, spot):
    p = [read_exr(os.path.join(runs, "phyir", f"{variant}_s{s}", "color.exr")).astype(np.float64) for s in seeds]
    c = [read_exr(os.path.join(runs, "cycles", f"{variant}_s{s}.exr")).astype(np.float64) for s in seeds]
    if len(seeds) != 2:
        sys.exit("lit_room_agreement.py: two seeds are needed (the noise comes from their difference)")
    h, w = p[0].shape[:2]
    if h % block or w % block:
        sys.exit(f"lit_room_agreement.py: {w}x{h} is not a multiple of --block {block}")
    p_avg, c_avg = 0.5 * (p[0] + p[1]), 0.5 * (c[0] + c[1])
    r = {"variant": variant, "width": w, "height": h, "block": block}
    r["phyir_mean"] = p_avg.mean(axis=(0, 1)).tolist()
    r["cycles_mean"] = c_avg.mean(axis=(0, 1)).tolist()
    r["phyir_seed_means"] = [x.mean(axis=(0, 1)).tolist() for x in p]
    r["cycles_seed_means"] = [x.mean(axis=(0, 1)).tolist() for x in c]
    r["ratio"] = (p_avg.mean(axis=(0, 1)) / c_avg.mean(axis=(0, 1))).tolist()
    r["ratio_channel_mean"] = float(p_avg.mean() / c_avg.mean())
    # Standard error of the ratio from the seed halves: each mean's error is |m1 - m2| / 2.
    ep, ec = abs(p[0].mean() - p[1].mean()) / 2, abs(c[0].mean() - c[1].mean()) / 2
    r["ratio_standard_error"] = float(r["ratio_channel_mean"] * math.hypot(ep / p_avg.mean(), ec / c_avg.mean()))
    r["pixel_relative_rmse"] = float(np.sqrt(np.mean((p_avg - c_avg) ** 2)) / np.mean(np.abs(c_avg)))
    r["pixel_relative_rmse_noise"] = float(np.sqrt(np.mean(((p[0] - p[1]) ** 2 + (c[0] - c[1]) ** 2) / 4))
                                          / np.mean(np.abs(c_avg)))
    b = block_stats(p[0], p[1], c[0], c[1], block)
    cm = float(c_avg.mean())
    r["block_relative_rmse"] = float(np.sqrt(np.mean((b["p_rgb"] - b["c_rgb"]) ** 2)) / cm)
    r["block_relative_rmse_noise"] = float(np.sqrt(np.mean(b["p_var_rgb"] + b["c_var_rgb"])) / cm)
    r.update(z_summary(b["z"], "z"))
    r.update(z_summary(b["z_null"], "z_null"))
    r["z_max_at_direction"] = block_direction(r["z_max_at_block"], block, w, h)
    # Is the difference one scale factor? z again with phyir scaled to Cycles' mean, per channel.
    scale = c_avg.mean(axis=(0, 1)) / p_avg.mean(axis=(0, 1))
    b_scaled = block_stats(p[0] * scale, p[1] * scale, c[0], c[1], block)
    r.update(z_summary(b_scaled["z"], "z_scaled"))
    r["z_scaled_max_at_direction"] = block_direction(r["z_scaled_max_at_block"], block, w, h)
    b["z_scaled"] = b_scaled["z"]
    for key in ("phyir", "cycles"):
        r[key + "_timings"] = timings(runs, variant, seeds, key)
    r["by_surface"] = surface_ratios(runs, variant, seeds[0], camera, p_avg, c_avg)
    arrays = {"p": p_avg, "c": c_avg, "blocks": b}
    if spot is not None and variant == "spot_only_direct":
        depth = os.path.join(runs, "phyir", f"{variant}_s{seeds[0]}", "depth.exr")
        if os.path.exists(depth):
            theta = spot_angles(depth, camera, spot)
            arrays["theta"] = theta
            r["spot"] = spot_prediction(p_avg, c_avg, theta, spot)
    return r, arrays


def surface_ratios(runs, variant, seed, camera, p_avg, c_avg):
    """phyir / Cycles and the light Cycles has more (per channel) by the surface of the first
    hit, found from phyir's depth and metalness AOVs: the room's inner faces (ceiling y = 2.7,
    floor y = 0, walls |x| = 2.5 or |z| = 2), the metals, and the rest (furniture)."""
    base = os.path.join(runs, "phyir", f"{variant}_s{seed}")
    if not os.path.exists(os.path.join(base, "depth.exr")):
        return None
    depth = read_exr(os.path.join(base, "depth.exr"), channels=("Y",))[..., 0].astype(np.float64)
    metal = read_exr(os.path.join(base, "metalness.exr"), channels=("Y",))[..., 0]
    h, w = depth.shape
    x = np.asarray(camera)[None, None, :] + depth[..., None] * pixel_directions(w, h)
    hit = np.isfinite(depth) & (depth > 0) & (depth < 1e3)
    ceiling = hit & (np.abs(x[..., 1] - 2.7) < 0.01)
    floor = hit & (np.abs(x[..., 1]) < 0.01)
    walls = hit & ((np.abs(np.abs(x[..., 0]) - 2.5) < 0.01) | (np.abs(np.abs(x[..., 2]) - 2.0) < 0.01)) & ~ceiling & ~floor
    metals = hit & (metal > 0.5) & ~(ceiling | floor | walls)
    rest = hit & ~(ceiling | floor | walls | metals)
    out = {}
    for name, m in (("ceiling", ceiling), ("walls", walls), ("floor", floor), ("metals", metals), ("furniture", rest)):
        if not m.any() or c_avg[m].sum() <= 0:
            continue
        out[name] = {"pixels": int(m.sum()), "share_of_cycles": float(c_avg[m].sum() / c_avg.sum()),
                     "ratio": float(p_avg[m].sum() / c_avg[m].sum()),
                     "ratio_rgb": (p_avg[m].sum(axis=0) / c_avg[m].sum(axis=0)).tolist(),
                     "cycles_minus_phyir_rgb": (c_avg[m] - p_avg[m]).mean(axis=0).tolist()}
    return out


def block_direction(block_index, block, w, h):
    """Centre of a block as a glTF direction and as (azimuth from -Z towards +X, elevation), degrees."""
    j, i = block_index
    u, v = (i + 0.5) * block / w, (j + 0.5) * block / h
    return {"azimuth_deg": round(360.0 * (u - 0.5), 1), "elevation_deg": round(90.0 - 180.0 * v, 1)}


def spot_prediction(p_avg, c_avg, theta, spot):
    """Per pixel: Cycles' falloff over glTF's at the pixel's first hit, and the images' ratio."""
    inner, outer = spot["inner"], spot["outer"]
    fg, fc = falloff_gltf(theta, inner, outer), falloff_cycles(theta, inner, outer)
    with np.errstate(divide="ignore", invalid="ignore"):
        predicted = np.where(fg > 0, fc / fg, np.nan)
    pm, cm = p_avg.mean(axis=2), c_avg.mean(axis=2)
    # Bins of 0.25 degrees inside the cone (the ramp of each is 21.25-25 and 23-25 degrees).
    edges = np.radians(np.arange(0.0, math.degrees(outer) + 0.25, 0.25))
    bins = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        sel = np.isfinite(theta) & (theta >= lo) & (theta < hi)
        if sel.sum() < 4 or pm[sel].sum() <= 0:
            continue
        mid = np.linspace(lo, hi, 9)
        bins.append({"theta_deg": [round(math.degrees(lo), 2), round(math.degrees(hi), 2)], "pixels": int(sel.sum()),
                     "measured": float(cm[sel].sum() / pm[sel].sum()),
                     "predicted": float(np.mean(falloff_cycles(mid, inner, outer)) / max(1e-12, np.mean(falloff_gltf(mid, inner, outer))))})
    # The whole image: phyir times the predicted ratio where the spot lights the first hit
    # directly; elsewhere (light from other surfaces only) the spot's power ratio.
    power = spot_power_ratio(inner, outer)
    lit = np.isfinite(predicted)
    scaled = np.where(lit, pm * np.nan_to_num(predicted), pm * power)
    return {"inner_deg": math.degrees(inner), "outer_deg": math.degrees(outer), "power_ratio_cycles_over_gltf": power,
            "pixels_in_cone": int(lit.sum()), "bins": bins,
            "in_cone_measured_ratio_cycles_over_phyir": float(cm[lit].sum() / pm[lit].sum()) if lit.any() else None,
            "in_cone_predicted_ratio": float(scaled[lit].sum() / pm[lit].sum()) if lit.any() else None,
            "outside_cone_measured_ratio_cycles_over_phyir": float(cm[~lit].sum() / pm[~lit].sum()) if (~lit).any() and pm[~lit].sum() > 0 else None}


def timings(runs, variant, seeds, key):
    out = []
    for s in seeds:
        entry = {"seed": s}
        if key == "phyir":
            report = load_json_if(os.path.join(runs, "phyir", f"{variant}_s{s}", "render.json"))
            if report:
                entry["spp"] = report.get("settings", {}).get("spp", report.get("spp"))
                entry["color_seconds"] = report.get("timings", {}).get("color_seconds")
                entry["punctual_lights"] = report.get("scene", {}).get("punctual_lights")
                entry["effects_punctual_lights"] = report.get("effects", {}).get("punctual_lights")
                entry["nonfinite_samples_caught"] = report.get("counters", {}).get("nonfinite_samples_caught")
            t = load_json_if(os.path.join(runs, "phyir", f"{variant}_s{s}.time.json"))
        else:
            report = load_json_if(os.path.join(runs, "cycles", f"{variant}_s{s}.json"))
            if report:
                entry["spp"] = report.get("samples")
                entry["render_seconds"] = report.get("timings", {}).get("render_seconds")
                entry["render_call_cpu_seconds"] = report.get("timings", {}).get("render_call_cpu_seconds")
                entry["lights"] = [(l["object"], l["type"], l.get("radius_imported", l.get("angle_imported")))
                                   for l in report.get("lights", [])]
                entry["max_bounces"] = report.get("settings", {}).get("max_bounces")
            t = load_json_if(os.path.join(runs, "cycles", f"{variant}_s{s}.time.json"))
        if t:
            entry["process_wall_seconds"] = t["wall_seconds"]
            entry["process_cpu_seconds"] = t["user_seconds"] + t["system_seconds"]
        out.append(entry)
    return out


def load_json_if(path):
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


# --- figures -------------------------------------------------------------------------------------

def srgb(image, scale):
    x = np.clip(image / scale, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def figure(results, arrays, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import TwoSlopeNorm
    rows = len(results)
    fig, axes = plt.subplots(rows, 5, figsize=(19, 2.2 * rows + 0.4), squeeze=False)
    for row, (r, a) in enumerate(zip(results, arrays)):
        scale = float(np.percentile(a["c"].mean(axis=2), 99.0))
        b = a["blocks"]
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = (b["p_mean"] - b["c_mean"]) / b["c_mean"]
        h, w = a["p"].shape[:2]
        ext = [-180, 180, -90, 90]
        axes[row, 0].imshow(srgb(a["p"], scale), extent=ext)
        axes[row, 0].set_title(f"{r['variant']}: phyir, mean {np.mean(r['phyir_mean']):.4f}", fontsize=9)
        axes[row, 1].imshow(srgb(a["c"], scale), extent=ext)
        axes[row, 1].set_title(f"Cycles, mean {np.mean(r['cycles_mean']):.4f} (phyir / Cycles {r['ratio_channel_mean']:.4f})", fontsize=9)
        im = axes[row, 2].imshow(rel, cmap="RdBu_r", vmin=-0.15, vmax=0.15, extent=ext, interpolation="nearest")
        axes[row, 2].set_title(f"(phyir - Cycles) / Cycles, {r['block']}x{r['block']} blocks", fontsize=9)
        fig.colorbar(im, ax=axes[row, 2], fraction=0.025, pad=0.02)
        im = axes[row, 3].imshow(np.nan_to_num(b["z"]), cmap="RdBu_r", norm=TwoSlopeNorm(0, -5, 5), extent=ext,
                                 interpolation="nearest")
        axes[row, 3].set_title(f"z: {100 * r['z_fraction_above_3']:.1f}% |z|>3 (null test {100 * r['z_null_fraction_above_3']:.1f}%),"
                               f" max {r['z_max_abs']:.1f}", fontsize=9)
        fig.colorbar(im, ax=axes[row, 3], fraction=0.025, pad=0.02)
        im = axes[row, 4].imshow(np.nan_to_num(b["z_scaled"]), cmap="RdBu_r", norm=TwoSlopeNorm(0, -5, 5), extent=ext,
                                 interpolation="nearest")
        axes[row, 4].set_title(f"z, phyir scaled to Cycles' mean: {100 * r['z_scaled_fraction_above_3']:.1f}% |z|>3,"
                               f" max {r['z_scaled_max_abs']:.1f}", fontsize=9)
        fig.colorbar(im, ax=axes[row, 4], fraction=0.025, pad=0.02)
        for ax in axes[row]:
            ax.set_xticks([-180, -90, 0, 90, 180])
            ax.set_yticks([-90, 0, 90])
            ax.tick_params(labelsize=7)
    fig.text(0.5, 0.005, "azimuth (degrees, 0 = glTF -Z, +90 = +X) / elevation; images sRGB, same scale per row",
             ha="center", fontsize=8)
    fig.tight_layout(rect=(0, 0.015, 1, 1))
    save_small(fig, path)


def save_small(fig, path):
    """A PNG with a 256-colour palette: a third of the size, no visible loss for these plots."""
    import io
    import matplotlib.pyplot as plt
    from PIL import Image
    buffer = io.BytesIO()
    fig.savefig(buffer, dpi=72, format="png")
    plt.close(fig)
    buffer.seek(0)
    Image.open(buffer).convert("RGB").quantize(256).save(path, optimize=True)


def spot_figure(result, arrays, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    s = result["spot"]
    inner, outer = math.radians(s["inner_deg"]), math.radians(s["outer_deg"])
    theta = np.radians(np.linspace(0.0, s["outer_deg"] + 0.5, 600))
    fig, (a0, a1, a2) = plt.subplots(1, 3, figsize=(15, 3.6))
    a0.plot(np.degrees(theta), falloff_gltf(theta, inner, outer), label="glTF / phyir: t^2")
    a0.plot(np.degrees(theta), falloff_cycles(theta, inner, outer), label="Cycles 3.4: cos(theta) smoothstep(x)")
    a0.set_xlabel("angle from the spot's axis (degrees)")
    a0.set_ylabel("I / I0")
    a0.legend(fontsize=8)
    a0.set_title("spot falloff", fontsize=10)
    th = np.radians(np.linspace(0.0, s["outer_deg"] - 0.05, 600))
    with np.errstate(divide="ignore", invalid="ignore"):
        predicted = falloff_cycles(th, inner, outer) / falloff_gltf(th, inner, outer)
    bins = [b for b in s["bins"] if b["theta_deg"][1] <= s["outer_deg"] + 1e-6]
    mids = [0.5 * sum(b["theta_deg"]) for b in bins]
    for ax, lo, hi, log in ((a1, 0.0, 21.5, False), (a2, 20.0, s["outer_deg"], True)):
        plot = ax.semilogy if log else ax.plot
        plot(np.degrees(th), predicted, "k-", lw=1, label="predicted: Cycles / glTF falloff")
        plot(mids, [b["measured"] for b in bins], "o", ms=3, label="measured: Cycles / phyir, pixels binned")
        plot(mids, [b["predicted"] for b in bins], "+", ms=6, label="predicted, averaged over the bin")
        ax.set_xlim(lo, hi)
        ax.set_xlabel("angle of the pixel's first hit from the spot's axis (degrees)", fontsize=8)
    a1.set_ylim(0.9, 1.1)
    a1.set_title(f"{result['variant']}: inside the inner cone", fontsize=10)
    a1.legend(fontsize=7)
    a2.set_ylim(0.8, 12)
    a2.set_title("in the ramp (log scale)", fontsize=10)
    fig.tight_layout()
    save_small(fig, path)


def report(args):
    seeds = [int(s) for s in args.seeds.split(",")]
    variants = [v for v in args.variants.split(",") if v]
    room = os.path.join(ROOT, "tests/data/gltf/blender_lit_room/lit_room.gltf")
    camera = camera_position(room)
    spot = spot_light(room)
    results, arrays = [], []
    for variant in variants:
        r, a = analyse_variant(args.runs, variant, seeds, args.block, camera, spot)
        for extra in (16, 8):  # the other block size, for the table
            if extra != args.block and r["width"] % extra == 0 and r["height"] % extra == 0:
                b = block_stats(*[read_exr(os.path.join(args.runs, k, f"{variant}_s{s}" + t)).astype(np.float64)
                                  for k, t in (("phyir", "/color.exr"), ("cycles", ".exr")) for s in seeds],
                                extra)
                r[f"block{extra}"] = {**z_summary(b["z"], "z"), **z_summary(b["z_null"], "z_null"),
                                      "block_relative_rmse": float(np.sqrt(np.mean((b["p_rgb"] - b["c_rgb"]) ** 2)) / np.mean(a["c"])),
                                      "block_relative_rmse_noise": float(np.sqrt(np.mean(b["p_var_rgb"] + b["c_var_rgb"])) / np.mean(a["c"]))}
        results.append(r)
        arrays.append(a)
        print(f"{variant}: phyir {fmt(r['phyir_mean'])}, Cycles {fmt(r['cycles_mean'])}, ratio {fmt(r['ratio'])} "
              f"(+- {r['ratio_standard_error']:.4f}); blocks {args.block}: rel. RMSE {r['block_relative_rmse']:.4f} "
              f"(noise {r['block_relative_rmse_noise']:.4f}), |z|>3 {100 * r['z_fraction_above_3']:.1f}% "
              f"(null {100 * r['z_null_fraction_above_3']:.1f}%), max |z| {r['z_max_abs']:.2f} at {r['z_max_at_direction']}; "
              f"scaled to equal means: |z|>3 {100 * r['z_scaled_fraction_above_3']:.1f}%, max {r['z_scaled_max_abs']:.2f} "
              f"at {r['z_scaled_max_at_direction']}")
        for name, x in (r["by_surface"] or {}).items():
            print(f"  {name}: {x['pixels']} pixels, {100 * x['share_of_cycles']:.1f}% of Cycles' light, phyir / Cycles "
                  f"{x['ratio']:.4f} {fmt(x['ratio_rgb'])}, Cycles - phyir {fmt(x['cycles_minus_phyir_rgb'])}")
        if "spot" in r:
            s = r["spot"]
            print(f"  spot: in-cone Cycles/phyir {s['in_cone_measured_ratio_cycles_over_phyir']:.4f} "
                  f"(predicted {s['in_cone_predicted_ratio']:.4f}), power ratio {s['power_ratio_cycles_over_gltf']:.4f}")
    by_name = {r["variant"]: r for r in results}
    if all(v in by_name for v in ("spot_only", "spot_only_direct", "no_spot", "no_spot_direct")):
        by_name["spot_only"]["spot_prediction"] = predict_spot_only(by_name)
        print(f"  spot_only predicted Cycles / phyir: {by_name['spot_only']['spot_prediction']['predicted_cycles_over_phyir']:.4f}, "
              f"measured {by_name['spot_only']['spot_prediction']['measured_cycles_over_phyir']:.4f}")
    os.makedirs(args.figures, exist_ok=True)
    base = os.path.join(args.figures, args.name)
    main_rows = [i for i, v in enumerate(variants) if not v.endswith("_direct")] or list(range(len(variants)))
    figure([results[i] for i in main_rows], [arrays[i] for i in main_rows], base + ".png")
    direct_rows = [i for i, v in enumerate(variants) if v.endswith("_direct")]
    if direct_rows:
        figure([results[i] for i in direct_rows], [arrays[i] for i in direct_rows], base + "_direct.png")
    for r, a in zip(results, arrays):
        if "spot" in r and r["variant"].endswith("_direct"):
            spot_figure(r, a, base + "_spot.png")
    lobes = {f"roughness_{r}": specular_albedo(r) for r in (0.45, 0.7, 0.9)}
    for name, lobe in lobes.items():
        print(f"  specular albedo, {name}: ours {lobe['hemispherical']['ours']:.4f}, Cycles {lobe['hemispherical']['cycles']:.4f}")
    with open(base + ".json", "w") as f:
        json.dump({"runs": os.path.abspath(args.runs), "camera": list(map(float, camera)), "seeds": seeds,
                   "block": args.block, "variants": results, "specular_albedo_f0_0.04": lobes}, f, indent=1)
    with open(base + ".csv", "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["variant", "spp", "phyir_R", "phyir_G", "phyir_B", "cycles_R", "cycles_G", "cycles_B",
                      "ratio_R", "ratio_G", "ratio_B", "ratio_channel_mean", "ratio_standard_error",
                      "block", "block_relative_rmse", "block_relative_rmse_noise", "fraction_abs_z_above_3",
                      "null_fraction_abs_z_above_3", "max_abs_z", "max_abs_z_azimuth_deg", "max_abs_z_elevation_deg",
                      "scaled_fraction_abs_z_above_3", "scaled_max_abs_z"])
        for r in results:
            out.writerow([r["variant"], r["phyir_timings"][0].get("spp")] + [f"{x:.5f}" for x in r["phyir_mean"]]
                         + [f"{x:.5f}" for x in r["cycles_mean"]] + [f"{x:.4f}" for x in r["ratio"]]
                         + [f"{r['ratio_channel_mean']:.4f}", f"{r['ratio_standard_error']:.4f}", r["block"],
                            f"{r['block_relative_rmse']:.4f}", f"{r['block_relative_rmse_noise']:.4f}",
                            f"{r['z_fraction_above_3']:.4f}", f"{r['z_null_fraction_above_3']:.4f}", f"{r['z_max_abs']:.2f}",
                            r["z_max_at_direction"]["azimuth_deg"], r["z_max_at_direction"]["elevation_deg"],
                            f"{r['z_scaled_fraction_above_3']:.4f}", f"{r['z_scaled_max_abs']:.2f}"])
    print(f"wrote {base}.png, {base}.json, {base}.csv")


def predict_spot_only(by_name):
    """Cycles / phyir for the spot alone with every bounce, from its parts (channel means):
    direct light as Cycles rendered it (spot_only_direct), plus phyir's indirect light scaled
    by the spot's power ratio (Cycles' falloff over glTF's, integrated over the cone) and by
    the indirect ratio of the spot-free room (what the renderers' materials alone give)."""
    m = lambda r, key: float(np.mean(r[key]))
    direct, full = by_name["spot_only_direct"], by_name["spot_only"]
    ns, nsd = by_name["no_spot"], by_name["no_spot_direct"]
    materials = (m(ns, "cycles_mean") - m(nsd, "cycles_mean")) / (m(ns, "phyir_mean") - m(nsd, "phyir_mean"))
    power = direct["spot"]["power_ratio_cycles_over_gltf"]
    indirect_phyir = m(full, "phyir_mean") - m(direct, "phyir_mean")
    predicted = (m(direct, "cycles_mean") + indirect_phyir * power * materials) / m(full, "phyir_mean")
    return {"indirect_ratio_no_spot_cycles_over_phyir": materials, "power_ratio_cycles_over_gltf": power,
            "direct_ratio_cycles_over_phyir": m(direct, "cycles_mean") / m(direct, "phyir_mean"),
            "indirect_ratio_cycles_over_phyir": (m(full, "cycles_mean") - m(direct, "cycles_mean")) / indirect_phyir,
            "predicted_cycles_over_phyir": predicted,
            "measured_cycles_over_phyir": m(full, "cycles_mean") / m(full, "phyir_mean")}


def fmt(v):
    return "(" + ", ".join(f"{x:.5f}" for x in v) + ")"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    v = sub.add_parser("variants", help="write the variant glTFs")
    v.add_argument("--gltf", default=os.path.join(ROOT, "tests/data/gltf/blender_lit_room/lit_room.gltf"))
    v.add_argument("--out", required=True)
    r = sub.add_parser("report", help="compare the renders of compare_lit_room.sh")
    r.add_argument("--runs", required=True)
    r.add_argument("--variants", default="lit_room,no_spot,spot_only,no_spot_direct,spot_only_direct")
    r.add_argument("--seeds", default="1,2")
    r.add_argument("--block", type=int, default=8, help="block size in pixels (default 8)")
    r.add_argument("--figures", default=os.path.join(ROOT, "docs", "figures"))
    r.add_argument("--name", default="cycles_lit_room")
    d = sub.add_parser("downsample", help="box-filter DIR/supersampled/ (FACTOR x the size) into DIR/")
    d.add_argument("--dir", required=True)
    d.add_argument("--factor", type=int, required=True)
    args = p.parse_args()
    if args.command == "variants":
        write_variants(args.gltf, args.out)
    elif args.command == "downsample":
        downsample(args)
    else:
        report(args)


if __name__ == "__main__":
    main()
