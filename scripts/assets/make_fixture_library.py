#!/usr/bin/python3
"""The tiny furniture libraries of the asset tests (tests/data/assets), in Sweet Home 3D's
.sh3f format: zip archives holding PluginFurnitureCatalog.properties (Latin-1), LICENSE.TXT
and OBJ/MTL models with PNG textures. Deterministic: the same script writes the same bytes.

    /usr/bin/python3 scripts/assets/make_fixture_library.py [OUT_DIR]   (default tests/data/assets)

fixture/PhyirFixture.sh3f: five models made here (public domain):
  table  Kitchen, 120 x 75 x 80 cm; OBJ in other units, no normals and no "s" (flat normals);
         map_Kd written as a foreign absolute Windows path in other case (resolved by file name)
  chair  Living room; authored Z-up, front towards -Y, with modelRotation; vn normals given;
         legs with Pm/Pr (explicit metal-roughness)
  lamp   Lights; smooth cylinder without normals (s 1) and flat caps (s off); glass shade
         (d 0.3, Ni 1.5); gold coloured Ks; two light sources
  window Doors and windows; doorOrWindow keys, two sashes, cut-out shape, wall thickness and
         distance; glass pane with illum 4
  plant  Miscellaneous; two crossed leaves with an RGBA PNG (alpha cut-out)
  The catalog exercises \\uXXXX escapes, raw Latin-1 bytes, "\\:" and "\\=" escapes, a line
  continuation, ':' and ' ' separators, '!' comments and CRLF line ends.
broken/: archives that must be refused or must load with warnings:
  no_catalog.sh3f, missing_model.sh3f, bad_number.sh3f, broken_models.sh3f (lines only, a
  face with out-of-range indices, a missing MTL, a missing texture; and a sheet made
  double-sided by twin triangles, which loads with its twins dropped).
"""
import struct
import sys
import zlib
import zipfile
from pathlib import Path

DATE = (2024, 1, 1, 0, 0, 0)  # fixed, so the archives are byte-identical run to run


# ---- files ---------------------------------------------------------------------------------

def png(width, height, pixels, alpha):
    """pixels: rows of (r, g, b[, a]) tuples; 8-bit RGB (colour type 2) or RGBA (6)."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in pixels)
    header = struct.pack(">IIBBBBB", width, height, 8, 6 if alpha else 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) +
            chunk(b"IEND", b""))


def wood_png():
    return png(4, 4, [[(150 + 20 * ((x + y) % 2), 100, 60) for x in range(4)] for y in range(4)], alpha=False)


def leaf_png():
    # A diamond-shaped leaf: opaque green inside, transparent outside.
    size = 8
    rows = []
    for y in range(size):
        row = []
        for x in range(size):
            inside = abs(x - 3.5) + abs(y - 3.5) <= 3.5
            row.append((40, 140, 50, 255 if inside else 0))
        rows.append(row)
    return png(size, size, rows, alpha=True)


def write_zip(path, files):
    path.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in files:
            info = zipfile.ZipInfo(name, DATE)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            archive.writestr(info, data)


# ---- geometry (OBJ text) -------------------------------------------------------------------

class Obj:
    def __init__(self, mtllib):
        self.lines = ["# PhyIR asset test fixture", f"mtllib {mtllib}"]
        self.nv = 0
        self.nvn = 0
        self.nvt = 0

    def box(self, lo, hi, material, normals=False, uv=False):
        """Six outward, counter-clockwise quads."""
        corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
        base = self.nv
        for c in corners:
            self.lines.append("v %g %g %g" % c)
        self.nv += 8
        idx = lambda i, j, k: base + 1 + 4 * i + 2 * j + k  # corner (x i, y j, z k), 1-based
        faces = [((0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0), (-1, 0, 0)),
                 ((1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1), (1, 0, 0)),
                 ((0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1), (0, -1, 0)),
                 ((0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0), (0, 1, 0)),
                 ((0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0), (0, 0, -1)),
                 ((0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (0, 0, 1))]
        if uv:
            for t in ((0, 0), (1, 0), (1, 1), (0, 1)):
                self.lines.append("vt %g %g" % t)
            self.nvt += 4
        self.lines.append(f"usemtl {material}")
        for *quad, normal in faces:
            if normals:
                self.lines.append("vn %g %g %g" % normal)
                self.nvn += 1
            refs = []
            for n, q in enumerate(quad):
                ref = str(idx(*q))
                if uv:
                    ref += f"/{self.nvt - 3 + n}"
                if normals:
                    ref += ("/" if uv else "//") + str(self.nvn)
                refs.append(ref)
            self.lines.append("f " + " ".join(refs))

    def raw(self, *lines):
        self.lines.extend(lines)

    def text(self):
        return ("\n".join(self.lines) + "\n").encode("ascii")


def table_obj():
    # Authored in "inches": 48 x 30 x 32 units (x, y up, z), scaled to 120 x 75 x 80 cm.
    obj = Obj("table.mtl")
    obj.box((-24, 28, -16), (24, 30, 16), "wood", uv=True)
    for x in (-22, 20):
        for z in (-14, 12):
            obj.box((x, 0, z), (x + 2, 28, z + 2), "wood")
    return obj.text()


TABLE_MTL = b"""# table
newmtl wood
Ns 96.078431
Ka 0 0 0
Kd 0.64 0.64 0.64
Ks 0.5 0.5 0.5
Ni 1.000000
d 1.000000
illum 2
map_Kd C:\\Users\\artist\\My Textures\\Wood.PNG
"""


def chair_obj():
    # Z-up, front towards -Y (a seat 44 x 44 at z 42-45, the back at +Y), normals given.
    obj = Obj("chair.mtl")
    obj.raw("o seat", "s 1")
    obj.box((-22, -22, 42), (22, 22, 45), "fabric", normals=True)
    obj.raw("o back")
    obj.box((-22, 19, 45), (22, 22, 90), "fabric", normals=True)
    obj.raw("o legs")
    for x in (-21, 19):
        for y in (-21, 19):
            obj.box((x, y, 0), (x + 2, y + 2, 42), "steel", normals=True)
    return obj.text()


CHAIR_MTL = b"""newmtl fabric
Kd 0.8 0.1 0.1
Ks 0.1 0.1 0.1
Ns 10
illum 2

newmtl steel
Kd 0.6 0.6 0.6
Pm 1.0
Pr 0.3
"""


def lamp_obj():
    import math
    obj = Obj("lamp.mtl")
    segments = 12
    # Base: a smooth cylinder (radius 6, height 4) without normals, flat caps.
    ring = lambda y: [(6 * math.cos(2 * math.pi * i / segments), y, -6 * math.sin(2 * math.pi * i / segments))
                      for i in range(segments)]
    for p in ring(0) + ring(4):
        obj.raw("v %.6f %.6f %.6f" % p)
    obj.raw("usemtl brass", "s 1")
    for i in range(segments):
        j = (i + 1) % segments
        obj.raw(f"f {i + 1} {j + 1} {segments + j + 1} {segments + i + 1}")
    obj.raw("s off")
    obj.raw("f " + " ".join(str(segments + i + 1) for i in range(segments)))       # top, facing +y
    obj.raw("f " + " ".join(str(i + 1) for i in reversed(range(segments))))        # bottom, facing -y
    obj.nv += 2 * segments
    obj.box((-1, 4, -1), (1, 40, 1), "brass")                                       # stem
    obj.box((-15, 40, -15), (15, 60, 15), "glass")                                  # shade
    return obj.text()


LAMP_MTL = b"""newmtl brass
Kd 0.2 0.15 0.01
Ks 0.9 0.7 0.2
Ns 200
illum 2

newmtl glass
Kd 0.9 0.9 0.9
Ks 0.5 0.5 0.5
Ns 500
Ni 1.5
d 0.3
illum 2
"""


def window_obj():
    # Frame 100 x 120 x 10, glass pane in the middle; front at +Z.
    obj = Obj("window.mtl")
    obj.box((0, 0, 0), (100, 6, 10), "frame")
    obj.box((0, 114, 0), (100, 120, 10), "frame")
    obj.box((0, 6, 0), (6, 114, 10), "frame")
    obj.box((94, 6, 0), (100, 114, 10), "frame")
    obj.box((6, 6, 4.5), (94, 114, 5.5), "pane")
    return obj.text()


WINDOW_MTL = b"""newmtl frame
Kd 0.9 0.9 0.88
Ks 0.2 0.2 0.2
Ns 50
illum 2

newmtl pane
Kd 0.95 0.95 0.95
Ks 1 1 1
Ns 900
Ni 1.52
Tr 0.9
illum 4
"""


def plant_obj():
    obj = Obj("plant.mtl")
    obj.box((-5, 0, -5), (5, 8, 5), "pot")
    # Two crossed leaves, textured quads, no normals.
    obj.raw("v -6 8 0", "v 6 8 0", "v 6 30 0", "v -6 30 0",
            "v 0 8 -6", "v 0 8 6", "v 0 30 6", "v 0 30 -6",
            "vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1",
            "usemtl leaf",
            "f 9/1 10/2 11/3 12/4", "f 13/1 14/2 15/3 16/4")
    return obj.text()


PLANT_MTL = b"""newmtl pot
Kd 0.5 0.25 0.1
Ks 0 0 0
illum 1

newmtl leaf
Kd 0.8 0.8 0.8
Ks 0.1 0.1 0.1
Ns 20
illum 2
map_Kd leaf.png
"""

CATALOG = (
    "# PluginFurnitureCatalog.properties of the PhyIR asset test fixture (public domain)\r\n"
    "! a comment in Java's other style\r\n"
    "id=PhyIR#Fixture\r\n"
    "name=PhyIR fixture\r\n"
    "license=Public domain (CC0 1.0)\r\n"
    "\r\n"
    "id#1=PhyIR#table\r\n"
    "name#1=Table \\u00e9l\\u00e9gante\r\n"
    "category#1=Kitchen\r\n"
    "creator#1=Fixture Maker\r\n"
    "tags#1=Wood, Dining ,  Table\r\n"
    "description#1=Ratio 3\\:2, key\\=value\r\n"
    "icon#1=/fixture/table.png\r\n"
    "model#1=/fixture/table/table.obj\r\n"
    "multiPartModel#1=true\r\n"
    "width#1=120\r\n"
    "depth#1=80\r\n"
    "height#1=75\r\n"
    "dropOnTopElevation#1=74\r\n"
    "movable#1=true\r\n"
    "doorOrWindow#1=false\r\n"
    "\r\n"
    "id#2 = PhyIR#chair\r\n"
    "name#2 : Chaise d\xe9cor\xe9e\r\n"
    "category#2 Living room\r\n"
    "creator#2=Fixture Maker\r\n"
    "tags#2=Seat, \\\r\n"
    "        Chair\r\n"
    "model#2=/fixture/chair/chair.obj\r\n"
    "multiPartModel#2=true\r\n"
    "width#2=46\r\n"
    "depth#2=50\r\n"
    "height#2=92.5\r\n"
    "modelRotation#2=1 0 0 0 0 1 0 -1 0\r\n"
    "movable#2=true\r\n"
    "doorOrWindow#2=false\r\n"
    "\r\n"
    "id#3=PhyIR#lamp\r\n"
    "name#3=Lamp\r\n"
    "category#3=Lights\r\n"
    "creator#3=Fixture Maker\r\n"
    "model#3=/fixture/lamp/lamp.obj\r\n"
    "multiPartModel#3=true\r\n"
    "width#3=30\r\n"
    "depth#3=30\r\n"
    "height#3=60\r\n"
    "elevation#3=75\r\n"
    "lightSourceX#3=15 10\r\n"
    "lightSourceY#3=15 20\r\n"
    "lightSourceZ#3=50 40\r\n"
    "lightSourceColor#3=#FFE0B0 #808080\r\n"
    "lightSourceDiameter#3=5 3\r\n"
    "movable#3=true\r\n"
    "doorOrWindow#3=false\r\n"
    "\r\n"
    "id#4=PhyIR#window\r\n"
    "name#4=Double casement window\r\n"
    "category#4=Doors and windows\r\n"
    "creator#4=Fixture Maker\r\n"
    "model#4=/fixture/window/window.obj\r\n"
    "multiPartModel#4=true\r\n"
    "width#4=100\r\n"
    "depth#4=10\r\n"
    "height#4=120\r\n"
    "elevation#4=90\r\n"
    "movable#4=false\r\n"
    "doorOrWindow#4=true\r\n"
    "doorOrWindowWallThickness#4=8\r\n"
    "doorOrWindowWallDistance#4=1\r\n"
    "doorOrWindowCutOutShape#4=M0,0 v1 h1 v-1 z\r\n"
    "doorOrWindowSashXAxis#4=6 94\r\n"
    "doorOrWindowSashYAxis#4=5 5\r\n"
    "doorOrWindowSashWidth#4=44 44\r\n"
    "doorOrWindowSashStartAngle#4=0 180\r\n"
    "doorOrWindowSashEndAngle#4=90 90\r\n"
    "\r\n"
    "id#5=PhyIR#plant\r\n"
    "name#5=Plant\r\n"
    "category#5=Miscellaneous\r\n"
    "creator#5=Fixture Maker\r\n"
    "model#5=/fixture/plant/plant.obj\r\n"
    "width#5=12\r\n"
    "depth#5=12\r\n"
    "height#5=30\r\n"
    "dropOnTopElevation#5=-1\r\n"
    "movable#5=true\r\n"
    "doorOrWindow#5=false\r\n"
).encode("latin-1")

LICENSE = b"The PhyIR asset test fixture: made by scripts/assets/make_fixture_library.py.\n" \
          b"Public domain (CC0 1.0).\n"


def fixture_files():
    return [
        ("LICENSE.TXT", LICENSE),
        ("PluginFurnitureCatalog.properties", CATALOG),
        ("fixture/table/table.obj", table_obj()),
        ("fixture/table/table.mtl", TABLE_MTL),
        ("fixture/table/wood.png", wood_png()),
        ("fixture/chair/chair.obj", chair_obj()),
        ("fixture/chair/chair.mtl", CHAIR_MTL),
        ("fixture/lamp/lamp.obj", lamp_obj()),
        ("fixture/lamp/lamp.mtl", LAMP_MTL),
        ("fixture/window/window.obj", window_obj()),
        ("fixture/window/window.mtl", WINDOW_MTL),
        ("fixture/plant/plant.obj", plant_obj()),
        ("fixture/plant/plant.mtl", PLANT_MTL),
        ("fixture/plant/leaf.png", leaf_png()),
    ]


def small_catalog(entries):
    """entries: (index, id, model, width) -> a minimal catalog."""
    lines = ["name=Broken", "license=Public domain (CC0 1.0)"]
    for index, ident, model, width in entries:
        lines += [f"id#{index}={ident}", f"name#{index}={ident}", f"category#{index}=Miscellaneous",
                  f"model#{index}={model}", f"width#{index}={width}", f"depth#{index}=10",
                  f"height#{index}=10", f"movable#{index}=true", f"doorOrWindow#{index}=false"]
    return ("\n".join(lines) + "\n").encode("latin-1")


def broken_archives():
    cube = Obj("cube.mtl")
    cube.box((0, 0, 0), (1, 1, 1), "white")
    cube_mtl = b"newmtl white\nKd 1 1 1\n"
    lines_only = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2 3\n"
    bad_indices = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nf 1 2 3\nf 1 2 99\nf 1 3 4\n"
    no_mtl = b"mtllib absent.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 1\nusemtl gone\nf 1 2 3\n"
    no_texture = b"mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 1\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl t\nf 1/1 2/2 3/3\n"
    # A quad and its copy wound the other way (vertex 5 repeats vertex 3's position), and a
    # copy of its first triangle in another material.
    twins = (b"mtllib twins.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 1 0\n"
             b"usemtl a\nf 1 2 3\nf 1 3 4\nf 5 2 1\nf 4 3 1\nusemtl b\nf 1 2 3\n")
    return {
        "no_catalog.sh3f": [("LICENSE.TXT", LICENSE), ("cube/cube.obj", cube.text())],
        "missing_model.sh3f": [
            ("PluginFurnitureCatalog.properties",
             small_catalog([(1, "Broken#cube", "/cube/cube.obj", 10), (2, "Broken#ghost", "/ghost/ghost.obj", 10)])),
            ("cube/cube.obj", cube.text()), ("cube/cube.mtl", cube_mtl)],
        "bad_number.sh3f": [
            ("PluginFurnitureCatalog.properties",
             small_catalog([(1, "Broken#cube", "/cube/cube.obj", 10), (2, "Broken#cube2", "/cube/cube.obj", "abc")])),
            ("cube/cube.obj", cube.text()), ("cube/cube.mtl", cube_mtl)],
        "broken_models.sh3f": [
            ("PluginFurnitureCatalog.properties",
             small_catalog([(1, "Broken#lines", "/m/lines.obj", 10), (2, "Broken#indices", "/m/indices.obj", 10),
                            (3, "Broken#nomtl", "/m/nomtl.obj", 10), (4, "Broken#notexture", "/m/notexture.obj", 10),
                            (5, "Broken#twins", "/m/twins.obj", 10)])),
            ("m/lines.obj", lines_only), ("m/indices.obj", bad_indices), ("m/nomtl.obj", no_mtl),
            ("m/notexture.obj", no_texture), ("m/tex.mtl", b"newmtl t\nKd 0.5 0.5 0.5\nmap_Kd missing.jpg\n"),
            ("m/twins.obj", twins), ("m/twins.mtl", b"newmtl a\nKd 1 1 1\n\nnewmtl b\nKd 0.5 0.5 0.5\n")],
    }


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parents[2] / "tests/data/assets"
    write_zip(out / "fixture/PhyirFixture.sh3f", fixture_files())
    for name, files in broken_archives().items():
        write_zip(out / "broken" / name, files)
    print(f"wrote {out}/fixture/PhyirFixture.sh3f and {len(broken_archives())} archives in {out}/broken")


if __name__ == "__main__":
    main()
