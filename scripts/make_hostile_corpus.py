#!/usr/bin/env python3
"""Writes tests/data/hostile/: malformed glTF/GLB files, one problem each, and
expected.json mapping each file to the phrases its phyir::Error must contain.

The files are checked in; rerun this script only to change the corpus (it rewrites the
folder). docs/robustness.md lists the files and what each must produce. Some are also
copied to fuzz/corpus/ as seeds.

Usage: scripts/make_hostile_corpus.py [output folder]
"""
import base64
import json
import os
import shutil
import struct
import sys
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "tests", "data", "hostile")

# One triangle: 3 VEC3 float positions (36 bytes) then 3 uint16 indices (6 bytes + 2 pad).
POSITIONS = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
INDICES = struct.pack("<3H", 0, 1, 2) + b"\0\0"
BIN = POSITIONS + INDICES  # 44 bytes
PNG_1x1 = bytes.fromhex(  # a valid 1x1 RGB PNG
    "89504e470d0a1a0a0000000d4948445200000001000000010802000000907753de"
    "0000000c4944415408d763f8cfc000000301010018dd8db40000000049454e44ae426082")


def data_uri(data, mime="application/octet-stream"):
    return "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())


def triangle(uri=None, indexed=True):
    """A valid one-triangle document; tests break one thing in a copy."""
    doc = {
        "asset": {"version": "2.0", "generator": "phyir hostile corpus"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "tri node"}],
        "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"byteLength": len(BIN), "uri": uri if uri is not None else data_uri(BIN)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 6},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
        ],
    }
    if indexed:
        doc["meshes"][0]["primitives"][0]["indices"] = 1
    return doc


def glb(doc, bin_chunk=BIN, json_length=None, bin_length=None, total=None, version=2,
        json_type=0x4E4F534A):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<II", len(text) if json_length is None else json_length, json_type) + text
    if bin_chunk is not None:
        padded = bin_chunk + b"\0" * (-len(bin_chunk) % 4)
        body += struct.pack("<II", len(padded) if bin_length is None else bin_length, 0x004E4942) + padded
    length = 12 + len(body) if total is None else total
    return struct.pack("<III", 0x46546C67, version, length) + body


def glb_doc():
    doc = triangle()
    del doc["buffers"][0]["uri"]
    return doc


FILES = {}     # name -> bytes
EXPECTED = {}  # name -> [phrases]


def add(name, content, *phrases):
    if isinstance(content, dict) or isinstance(content, list):
        content = json.dumps(content, indent=1).encode()
    elif isinstance(content, str):
        content = content.encode()
    FILES[name] = content
    EXPECTED[name] = list(phrases)


def edit(fn, doc=None):
    doc = doc if doc is not None else triangle()
    fn(doc)
    return doc


# --- truncated -------------------------------------------------------------------------
add("empty.gltf", b"", "invalid JSON")
add("truncated_object.gltf", json.dumps(triangle())[:200], "invalid JSON")
add("glb_header_only.glb", glb(glb_doc())[:12], "shorter than its 20-byte header")
full = glb(glb_doc())
add("glb_cut_in_bin_chunk.glb", full[:-10], "GLB header declares")
add("glb_cut_with_fixed_length.glb", glb(glb_doc(), bin_chunk=BIN, total=len(full) - 10)[:len(full) - 10],
    "GLB BIN chunk of 44 bytes runs past the end of the file")

# --- GLB container ---------------------------------------------------------------------
add("glb_json_chunk_too_long.glb", glb(glb_doc(), json_length=0x7FFFFFF0),
    "GLB JSON chunk of 2147483632 bytes runs past the end of the file")
add("glb_bin_chunk_too_long.glb", glb(glb_doc(), bin_length=0xFFFFFFF0),
    "GLB BIN chunk of 4294967280 bytes runs past the end of the file")
add("glb_version_1.glb", glb(glb_doc(), version=1), "GLB version 1 is not supported")
add("glb_first_chunk_not_json.glb", glb(glb_doc(), json_type=0x004E4942), "GLB first chunk is not JSON")
add("glb_missing_bin_chunk.glb", glb(glb_doc(), bin_chunk=None),
    "buffer 0 byteLength 44 exceeds the GLB BIN chunk (0 bytes)")

# --- wrong types -----------------------------------------------------------------------
add("root_is_array.gltf", [triangle()], "JSON root is not an object")
add("asset_version_1.gltf", edit(lambda d: d["asset"].update(version="1.0")),
    "asset.version '1.0' is not supported")
add("count_is_a_string.gltf", edit(lambda d: d["accessors"][0].update(count="three")),
    'accessors[0].count is "three": must be an integer (glTF 2.0 schema, accessor.count)')
add("nodes_not_an_array.gltf", edit(lambda d: d.update(nodes={"mesh": 0})),
    'nodes is {"mesh":0}: must be an array of objects (glTF 2.0 schema, glTF.nodes)')
add("indices_are_floats.gltf",
    edit(lambda d: (d["bufferViews"][1].update(byteLength=8), d["accessors"][1].update(componentType=5126, count=2))),
    "accessor 1 (indices of mesh 0 'tri' primitive 0)", "expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT")
add("position_is_scalar.gltf", edit(lambda d: d["accessors"][0].update(type="SCALAR", count=9, min=[0], max=[1])),
    "accessor 0 (POSITION of mesh 0 'tri' primitive 0) has type SCALAR, expected VEC3")
add("invalid_component_type.gltf", edit(lambda d: d["accessors"][0].update(componentType=1234)),
    "accessors[0].componentType is 1234: must be one of 5120, 5121, 5122, 5123, 5125, 5126 "
    "(glTF 2.0 schema, accessor.componentType)")
add("buffer_without_bytelength.gltf", edit(lambda d: d["buffers"][0].pop("byteLength")),
    "buffers[0].byteLength is missing: required (glTF 2.0 schema, buffer.byteLength)")
# tinygltf reads these as if they were absent or 0; the schema check refuses them first.
add("accessor_offset_negative.gltf", edit(lambda d: d["accessors"][0].update(byteOffset=-4)),
    "accessors[0].byteOffset is -4: must be >= 0 (glTF 2.0 schema, accessor.byteOffset)")
add("primitive_mode_7.gltf", edit(lambda d: d["meshes"][0]["primitives"][0].update(mode=7)),
    "meshes[0] ('tri').primitives[0].mode is 7: must be one of 0, 1, 2, 3, 4, 5, 6 (glTF 2.0 schema, mesh.primitive.mode)")
add("offset_written_as_decimal.gltf", edit(lambda d: d["bufferViews"][1].update(byteOffset=36.0)),
    "bufferViews[1].byteOffset is 36.0: write it as 36", "(limitation of this loader, bufferView.byteOffset)")

# --- accessor and bufferView overflow ----------------------------------------------------
add("accessor_offset_huge.gltf", edit(lambda d: d["accessors"][0].update(byteOffset=2**62)),
    "accessor 0 (POSITION of mesh 0 'tri' primitive 0) reads past the end of bufferView 0")
add("accessor_stride_overflow.gltf",
    edit(lambda d: (d["bufferViews"][0].update(byteStride=252), d["accessors"][0].update(count=2**31))),
    "reads past the end of bufferView 0")
add("bufferview_offset_wraps.gltf",
    edit(lambda d: d["bufferViews"][0].update(byteOffset=2**64 - 8, byteLength=36)),
    "bufferView 0 (byteOffset 18446744073709551608, byteLength 36) reads past the end of buffer 0 (44 bytes)")
add("bufferview_past_buffer.gltf", edit(lambda d: d["bufferViews"][1].update(byteOffset=40, byteLength=6)),
    "bufferView 1 (byteOffset 40, byteLength 6) reads past the end of buffer 0 (44 bytes)")
add("bufferview_wrong_buffer.gltf", edit(lambda d: d["bufferViews"][0].update(buffer=7)),
    "bufferView 0 refers to buffer 7, which does not exist (1 buffers)")

# --- indices out of range ----------------------------------------------------------------
big_index = struct.pack("<3I", 0, 1, 0xFFFFFFFF)
add("index_max_uint32.gltf",
    edit(lambda d: (d["buffers"].append({"byteLength": 12, "uri": data_uri(big_index)}),
                    d["bufferViews"].append({"buffer": 1, "byteLength": 12}),
                    d["accessors"][1].update(bufferView=2, componentType=5125))),
    "index 4294967295 (element 2 of accessor 1) is out of range for mesh 0 'tri' primitive 0 with 3 vertices")
add("node_mesh_out_of_range.gltf", edit(lambda d: d["nodes"][0].update(mesh=2**31 - 1)),
    "node 0 'tri node' refers to mesh 2147483647, which does not exist")
add("scene_node_out_of_range.gltf", edit(lambda d: d["scenes"][0].update(nodes=[5])),
    "node 5 does not exist (1 nodes)")
add("default_scene_out_of_range.gltf", edit(lambda d: d.update(scene=3)), "default scene 3 does not exist (1 scenes)")
add("texture_source_out_of_range.gltf",
    edit(lambda d: (d.update(materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
                             textures=[{"source": 9}]),
                    d["meshes"][0]["primitives"][0].update(material=0))),
    "texture 0 (used by", "has no valid image source (source 9, 0 images)")

# --- huge counts -------------------------------------------------------------------------
add("count_2pow31_tiny_buffer.gltf", edit(lambda d: d["accessors"][0].update(count=2**31)),
    "accessor 0 (POSITION of mesh 0 'tri' primitive 0) reads past the end of bufferView 0")
add("count_2pow31_no_bufferview.gltf",
    edit(lambda d: (d["accessors"][0].pop("bufferView"), d["accessors"][0].update(count=2**31))),
    "accessor 0 (POSITION of mesh 0 'tri' primitive 0) has count 2147483648 but no bufferView")
add("count_2pow24_no_bufferview.gltf",
    edit(lambda d: (d["accessors"][0].pop("bufferView"), d["accessors"][0].update(count=2**24 + 1),
                    d["meshes"][0]["primitives"][0].pop("indices"))),
    "accessor 0 (POSITION of mesh 0 'tri' primitive 0) has count 16777217 but no bufferView")
add("sparse_count_huge.gltf",
    edit(lambda d: d["accessors"][0].update(sparse={
        "count": 2**31, "indices": {"bufferView": 1, "componentType": 5123},
        "values": {"bufferView": 0}})),
    "accessor 0 (POSITION of mesh 0 'tri' primitive 0) sparse count", "is outside [1, 3]")
add("buffer_bytelength_2pow40.gltf", edit(lambda d: d["buffers"][0].update(byteLength=2**40)),
    "buffer 0 data URI holds 44 bytes but its byteLength is 1099511627776")
add("thousand_primitives.gltf",
    edit(lambda d: d["meshes"][0].update(primitives=[{"attributes": {"POSITION": 0}, "indices": 1}] * 1000)),
    "__loads__")

# --- missing buffers and images ----------------------------------------------------------
add("buffer_without_uri.gltf", edit(lambda d: d["buffers"][0].pop("uri")), "buffer 0 has no uri")
add("buffer_file_missing.gltf", triangle(uri="absent.bin"), "buffer 0 uri 'absent.bin' not found")
add("buffer_uri_is_a_folder.gltf", triangle(uri="."), "buffer 0 uri '.' not found")
add("buffer_uri_is_a_device.gltf", triangle(uri="/dev/zero"), "buffer 0 uri '/dev/zero' not found")
add("no_buffers_at_all.gltf", edit(lambda d: d.pop("buffers")),
    "bufferView 0 refers to buffer 0, which does not exist (0 buffers)")
textured = lambda image: edit(lambda d: (
    d.update(materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
             textures=[{"source": 0}], images=[image]),
    d["meshes"][0]["primitives"][0].update(material=0)))
add("image_file_missing.gltf", textured({"uri": "textures/missing.png"}),
    "image 0 uri 'textures/missing.png' not found")
add("image_bufferview_missing.gltf", textured({"bufferView": 12, "mimeType": "image/png"}),
    "image 0 bufferView does not exist (2 bufferViews)")
add("image_not_an_image.gltf", textured({"uri": data_uri(b"this is not a PNG at all, just text", "image/png")}),
    "image 0: cannot decode image")
# A "regular file" of 128 TiB (where /proc/kcore is readable; else it is not found).
# A PNG cut inside its IDAT chunk: refused before OIIO reads it (OIIO 2.4 leaks an error
# string when libpng reads past in-memory data; found by scripts/fuzz.sh).
add("image_png_truncated.gltf", textured({"uri": data_uri(PNG_1x1[:45], "image/png")}),
    "image 0: cannot decode image: truncated in chunk")
add("image_uri_proc_kcore.gltf", textured({"uri": "/proc/kcore"}), "image 0 uri '/proc/kcore'")
add("image_without_source.gltf", textured({"name": "nothing"}),
    "images[0] ('nothing') has neither uri nor bufferView: exactly one of them is required (glTF 2.0 schema, image)")
# A PNG whose header claims 1,000,000 x 1,000,000 pixels (the libpng maximum), then ends.
huge_png = bytearray(PNG_1x1)
huge_png[16:24] = struct.pack(">II", 1000000, 1000000)
huge_png[29:33] = struct.pack(">I", zlib.crc32(bytes(huge_png[12:29])))  # a valid IHDR CRC
add("image_huge_dimensions.gltf", textured({"uri": data_uri(bytes(huge_png), "image/png")}),
    "image 0 is 1000000 x 1000000 pixels x 3 channels, more than a texture may hold")

# --- cyclic node graphs ------------------------------------------------------------------
add("node_is_its_own_child.gltf", edit(lambda d: d["nodes"][0].update(children=[0])),
    "node 0 'tri node' is reached twice from the scene")
add("node_cycle_in_scene.gltf",
    edit(lambda d: (d["nodes"].append({"children": [0]}), d["nodes"][0].update(children=[1]))),
    "node 0 'tri node' is reached twice")
add("node_cycle_without_scene.gltf",
    edit(lambda d: (d.pop("scene"), d.pop("scenes"), d["nodes"].append({"children": [0]}),
                    d["nodes"][0].update(children=[1]))), "node 0 'tri node' is on a cycle of children")
add("node_two_parents.gltf",
    edit(lambda d: (d["nodes"].extend([{"children": [0]}, {"children": [0]}]),
                    d["scenes"][0].update(nodes=[1, 2]))), "node 0 'tri node' is reached twice")

# --- NaN / Inf values --------------------------------------------------------------------
inf_text = json.dumps(edit(lambda d: d["nodes"][0].update(translation=[0, 0, 12345.5])))
# JSON has no NaN or Inf: 1e999 overflows double, so the JSON itself is refused.
add("node_translation_inf.gltf", inf_text.replace("12345.5", "1e999"), "invalid JSON", "number overflow")
# Finite in JSON, but the transformed vertices overflow 32-bit floats.
add("node_scale_overflow.gltf", edit(lambda d: d["nodes"][0].update(scale=[1e300, 1e300, 1e300])),
    "mesh 0 'tri' primitive 0 placed by node 0 'tri node' has vertex 1", "overflow 32-bit floats")
add("base_color_factor_huge.gltf",
    edit(lambda d: (d.update(materials=[{"pbrMetallicRoughness": {"baseColorFactor": [1, 1e300, 1, 1]}}]),
                    d["meshes"][0]["primitives"][0].update(material=0))),
    "materials[0].pbrMetallicRoughness.baseColorFactor[1] is 1e+300: must be in [0, 1]",
    "(glTF 2.0 schema, material.pbrMetallicRoughness.baseColorFactor)")
add("camera_values_huge.gltf",
    edit(lambda d: (d.update(cameras=[{"type": "perspective", "perspective": {
        "yfov": 1.0, "znear": 1e300, "zfar": 1e308, "aspectRatio": 1e300}}]),
                    d["nodes"].append({"camera": 0}), d["scenes"][0]["nodes"].append(1))), "__loads__")
add("node_matrix_projective.gltf", edit(lambda d: d["nodes"][0].update(matrix=[1] * 15 + [2.5])), "__loads__")
add("base_color_factor_inf.gltf",
    json.dumps(edit(lambda d: (d.update(materials=[{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 777.25]}}]),
                               d["meshes"][0]["primitives"][0].update(material=0)))).replace("777.25", "-1e999"),
    "invalid JSON", "number overflow")
nan_positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, float("nan"), 1, 0) + INDICES
add("position_nan.glb", glb(glb_doc(), bin_chunk=nan_positions),
    "accessor 0 (POSITION of mesh 0 'tri' primitive 0) element 2 is not finite")
inf_normals = struct.pack("<9f", 0, 0, 1, 0, 0, float("inf"), 0, 0, 1)
add("normal_inf.gltf",
    edit(lambda d: (d["buffers"].append({"byteLength": 36, "uri": data_uri(inf_normals)}),
                    d["bufferViews"].append({"buffer": 1, "byteLength": 36}),
                    d["accessors"].append({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"}),
                    d["meshes"][0]["primitives"][0]["attributes"].update(NORMAL=2))),
    "accessor 2 (NORMAL of mesh 0 'tri' primitive 0) element 1 is not finite")

# --- extensions --------------------------------------------------------------------------
add("required_extension_unknown.gltf",
    edit(lambda d: d.update(extensionsUsed=["EXT_phyir_from_the_future"],
                            extensionsRequired=["EXT_phyir_from_the_future"])),
    "required extension EXT_phyir_from_the_future is not supported")
add("required_extension_not_a_string.gltf", edit(lambda d: d.update(extensionsRequired=[42])),
    "extensionsRequired[0] is 42: must be a string (glTF 2.0 schema, glTF.extensionsRequired)")

# --- bad data URIs -----------------------------------------------------------------------
add("data_uri_not_base64.gltf", triangle(uri="data:application/octet-stream;base64,@@@@*&^%$#!~~"),
    "buffer 0 data URI is not valid base64")
add("data_uri_bad_characters.gltf", triangle(uri="data:application/octet-stream;base64," + "@" * 59 + "="),
    "tinygltf: Failed to decode 'uri'")
add("data_uri_without_base64_marker.gltf", triangle(uri="data:application/octet-stream," + "A" * 60),
    "buffer 0 data URI is not valid base64")
add("data_uri_without_comma.gltf", triangle(uri="data:application/octet-stream;base64"),
    "buffer 0 data URI is not valid base64")
add("data_uri_short.gltf", triangle(uri=data_uri(BIN[:20])),
    "buffer 0 data URI holds 20 bytes but its byteLength is 44")
add("data_uri_bad_padding.gltf", triangle(uri="data:application/octet-stream;base64,AAA===="),
    "buffer 0 data URI is not valid base64")


# --- fuzz seeds: valid, self-contained files that reach every loader stage ----------------
SEEDS = {}


def seed_textured():
    """Positions, normals, UVs, tangents, a PNG in a bufferView, every texture slot."""
    doc = glb_doc()
    uv = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
    normals = struct.pack("<9f", 0, 0, 1, 0, 0, 1, 0, 0, 1)
    tangents = struct.pack("<12f", 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1)
    png = PNG_1x1 + b"\0" * (-len(PNG_1x1) % 4)
    binary = BIN + uv + normals + tangents + png
    doc["buffers"][0]["byteLength"] = len(binary)
    offset = len(BIN)
    for data in (uv, normals, tangents):
        doc["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": len(data)})
        offset += len(data)
    doc["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": len(PNG_1x1)})
    doc["accessors"] += [{"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
                         {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3"},
                         {"bufferView": 4, "componentType": 5126, "count": 3, "type": "VEC4"}]
    doc["meshes"][0]["primitives"][0]["attributes"].update(TEXCOORD_0=2, NORMAL=3, TANGENT=4)
    doc["meshes"][0]["primitives"][0]["material"] = 0
    doc["images"] = [{"bufferView": 5, "mimeType": "image/png"}]
    doc["samplers"] = [{"magFilter": 9728, "wrapS": 33648, "wrapT": 33071}]
    doc["textures"] = [{"source": 0, "sampler": 0}]
    tex = {"index": 0, "texCoord": 0,
           "extensions": {"KHR_texture_transform": {"offset": [0.5, 0], "rotation": 0.3, "scale": [2, 2]}}}
    doc["materials"] = [{"name": "all slots", "pbrMetallicRoughness": {
        "baseColorTexture": tex, "metallicRoughnessTexture": {"index": 0}, "baseColorFactor": [1, 0.5, 0.5, 1]},
        "normalTexture": {"index": 0, "scale": 0.5}, "emissiveTexture": {"index": 0},
        "occlusionTexture": {"index": 0}, "emissiveFactor": [1, 1, 1], "alphaMode": "MASK", "alphaCutoff": 0.3,
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4},
                       "KHR_materials_transmission": {"transmissionFactor": 0.5, "transmissionTexture": {"index": 0}},
                       "KHR_materials_ior": {"ior": 1.33}}}]
    doc["extensionsUsed"] = ["KHR_texture_transform", "KHR_materials_emissive_strength",
                             "KHR_materials_transmission", "KHR_materials_ior"]
    return glb(doc, bin_chunk=binary)


def seed_scene_graph():
    doc = triangle()
    doc["nodes"] = [
        {"name": "root", "children": [1, 2, 3], "translation": [1, 2, 3], "rotation": [0, 0.7071, 0, 0.7071],
         "scale": [2, 2, -2]},
        {"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1]},
        {"camera": 0, "translation": [0, 1.6, 3], "extras": {"note": "viewpoint"}},
        {"mesh": 0, "children": [4]}, {"mesh": 0, "scale": [1e-3, 1e-3, 1e-3]}]
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 1.2, "znear": 0.01, "aspectRatio": 2}}]
    doc["scenes"] = [{"nodes": [0], "extras": {"phyir": {"candidate_viewpoints": [[0, 1.6, 0], [1, 1.6, 1]]}}},
                     {"nodes": [3]}]
    doc["materials"] = [{"doubleSided": True, "alphaMode": "BLEND", "pbrMetallicRoughness": {"metallicFactor": 0.5}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    return doc


def seed_sparse():
    doc = triangle()
    moved = struct.pack("<H", 2) + b"\0\0" + struct.pack("<3f", 0, 2, 0)
    doc["buffers"].append({"byteLength": len(moved), "uri": data_uri(moved)})
    doc["bufferViews"] += [{"buffer": 1, "byteOffset": 0, "byteLength": 2},
                           {"buffer": 1, "byteOffset": 4, "byteLength": 12}]
    doc["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": 2, "componentType": 5123},
                                     "values": {"bufferView": 3}}
    doc["accessors"].append({"componentType": 5126, "count": 3, "type": "VEC3",
                             "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5123},
                                        "values": {"bufferView": 3}}})
    doc["meshes"].append({"primitives": [{"attributes": {"POSITION": 2}, "mode": 4}]})
    doc["nodes"].append({"mesh": 1})
    doc["scenes"][0]["nodes"].append(1)
    return doc


def add_seeds():
    SEEDS["triangle.gltf"] = json.dumps(triangle(), indent=1).encode()
    SEEDS["triangle_unindexed.gltf"] = json.dumps(triangle(indexed=False)).encode()
    SEEDS["triangle.glb"] = glb(glb_doc())
    SEEDS["textured.glb"] = seed_textured()
    SEEDS["scene_graph.gltf"] = json.dumps(seed_scene_graph(), indent=1).encode()
    SEEDS["sparse.gltf"] = json.dumps(seed_sparse(), indent=1).encode()
    for name in ("index_max_uint32.gltf", "glb_bin_chunk_too_long.glb", "node_cycle_in_scene.gltf",
                 "data_uri_short.gltf", "required_extension_unknown.gltf"):
        SEEDS["hostile_" + name] = FILES[name]


add_seeds()


def write_seeds(folder):
    if os.path.isdir(folder):
        shutil.rmtree(folder)
    os.makedirs(folder)
    for name, content in SEEDS.items():
        with open(os.path.join(folder, name), "wb") as f:
            f.write(content)
    print("%d seeds in %s" % (len(SEEDS), folder))


def main():
    write_seeds(os.path.join(ROOT, "fuzz", "corpus"))
    if os.path.isdir(OUT):
        shutil.rmtree(OUT)
    os.makedirs(OUT)
    for name, content in FILES.items():
        with open(os.path.join(OUT, name), "wb") as f:
            f.write(content)
    with open(os.path.join(OUT, "expected.json"), "w") as f:
        json.dump({"_comment": "file -> phrases its phyir::Error must contain ('__loads__': must load). "
                               "Written by scripts/make_hostile_corpus.py.",
                   "files": EXPECTED}, f, indent=1, sort_keys=True)
        f.write("\n")
    print("%d files in %s" % (len(FILES), OUT))


if __name__ == "__main__":
    main()
