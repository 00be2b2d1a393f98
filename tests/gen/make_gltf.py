#!/usr/bin/env python3
"""glTF test files for tests/gen/gltf.sh, written from a mesh the OFF reader has read.

usage: make_gltf.py DUMP OUT_DIR

DUMP is tests/gen/model_dump.cpp's output for a catalogue mesh (bunny00.off, fandisk.off): its
points as exact hexadecimal floats and its triangles, so the glTF files hold the very floats the
OFF reader made. Writes into OUT_DIR, each glTF file beside the OFF file ("twin") whose model it
must read to, bit for bit:

  plain.gltf (base64 data URI), plain.glb (BIN chunk), external.gltf (+ external.bin beside it):
      one node, no transform                                           twin: the original OFF
  hierarchy.gltf: default scene 1 (scene 0 holds a decoy), a root node with a matrix (a quarter
      turn about z, scale 2, a translation) over a child with T, R (half turn about x) and S (0.5);
      the positions stored as that transform's inverse, which undoes it exactly (every entry is 0,
      +-1, +-2, +-0.5 or a short binary fraction)                     twin: the original OFF
  mirror.glb: a node with scale (-1, 1, 1) over x-negated positions and faces stored clockwise
      (the spec's rule for mirroring nodes turns them back)            twin: the original OFF
  instances.gltf: one mesh under two nodes, the second translated by (2, 0, 0)   instances.off
  white.gltf: a material with baseColorFactor white: no colour information      the original OFF
  factor.gltf: baseColorFactor (0.2, 0.5, 0.8) in linear light                   factor.off
      (factor.rgb: the one sRGB colour every vertex must get)
  colour0.glb: COLOR_0 as normalized unsigned bytes (RGBA), no material           colour0.off
  colour0f.gltf: COLOR_0 as floats (RGB) times baseColorFactor (0.5, 1, 0.25)    colour0f.off
  texture.gltf: a 4x4 PNG as a data URI, wrapS REPEAT, wrapT MIRRORED_REPEAT, float UVs from
      -0.7 to 1.8                                                      texture.off
  texture.glb: the PNG in a buffer view, CLAMP_TO_EDGE, the texture on TEXCOORD_1 (normalized
      unsigned shorts; TEXCOORD_0 holds other values), times a factor (1, 0.5, 1)  texture-glb.off
  texture-file.gltf (+ texture-file.bin, texture-file.png beside it): external files  texture.off
  strip.gltf, fan.gltf: small TRIANGLE_STRIP and TRIANGLE_FAN primitives (the spec's corner order)
      beside a POINTS and a LINES primitive (skipped)                  strip.off, fan.off
and OUT_DIR/bad/: malformed files, one problem each (tests/gen/gltf.sh's table says which).
Python 3's standard library only (zlib and struct for the PNG). tests/fuzz/seeds.py imports it for
the glTF fuzzers' seeds (Doc, png, bad).
"""
import base64
import json
import math
import os
import struct
import sys
import zlib

F32, U8, U16, U32 = 5126, 5121, 5123, 5125


def f32(x):
    """X rounded to float, as a Python float (exactly representable)."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def read_dump(path):
    points, tris = [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if w[0] == "v":
                points.append(tuple(float.fromhex(x) for x in w[1:4]))
            elif w[0] == "f":
                tris.append(tuple(int(x) for x in w[1:4]))
    return points, tris


def write_off(path, points, tris, colours=None):
    """An OFF (COFF with COLOURS) whose coordinates parse back to exactly these floats."""
    with open(path, "w") as f:
        f.write("COFF\n" if colours else "OFF\n")
        f.write("%d %d 0\n" % (len(points), len(tris)))
        for i, p in enumerate(points):
            f.write("%.9g %.9g %.9g" % p)
            f.write(" %d %d %d\n" % colours[i] if colours else "\n")
        for t in tris:
            f.write("3 %d %d %d\n" % t)


# ---- colour as the reader computes it (gen/input/gltf.cpp) ----------------------------------------
def s2l(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def l2s(v):
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055


def srgb_byte(v):
    return int(math.floor(255 * l2s(min(max(v, 0.0), 1.0)) + 0.5))


def texel(s, n, wrap):
    u = s
    if wrap == 10497:
        u = s - math.floor(s)
    elif wrap == 33648:
        u = s - 2 * math.floor(s / 2)
        if u > 1:
            u = 2 - u
    return int(min(max(math.floor(u * n), 0.0), n - 1))


# ---- files ---------------------------------------------------------------------------------------
def png(w, h, rgb):
    """A truecolour 8-bit PNG of RGB rows (lists of (r, g, b))."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in rgb)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


class Doc:
    """One glTF document and its single buffer."""

    def __init__(self):
        self.bin = bytearray()
        self.j = {"asset": {"version": "2.0", "generator": "tests/gen/make_gltf.py"},
                  "buffers": [], "bufferViews": [], "accessors": [], "meshes": [], "nodes": [],
                  "scenes": [{"nodes": []}], "scene": 0}

    def view(self, data):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.j["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.j["bufferViews"]) - 1

    def accessor(self, ctype, kind, values, count, normalized=False):
        fmt = {F32: "f", U8: "B", U16: "H", U32: "I"}[ctype]
        a = {"bufferView": self.view(struct.pack("<%d%s" % (len(values), fmt), *values)),
             "componentType": ctype, "count": count, "type": kind}
        if normalized:
            a["normalized"] = True
        self.j["accessors"].append(a)
        return len(self.j["accessors"]) - 1

    def mesh(self, points, tris, extra=None, mode=None):
        attrs = {"POSITION": self.accessor(F32, "VEC3", [c for p in points for c in p], len(points))}
        attrs.update(extra or {})
        prim = {"attributes": attrs}
        if tris is not None:
            prim["indices"] = self.accessor(U32, "SCALAR", [i for t in tris for i in t], len(tris) * 3)
        if mode is not None:
            prim["mode"] = mode
        self.j["meshes"].append({"primitives": [prim]})
        return len(self.j["meshes"]) - 1

    def node(self, root=True, **kw):
        self.j["nodes"].append(kw)
        n = len(self.j["nodes"]) - 1
        if root:
            self.j["scenes"][0]["nodes"].append(n)
        return n

    def material(self, **pbr):
        self.j.setdefault("materials", []).append({"pbrMetallicRoughness": pbr})
        self.j["meshes"][-1]["primitives"][0]["material"] = len(self.j["materials"]) - 1

    def texture(self, image, wrap_s, wrap_t):
        self.j.setdefault("images", []).append(image)
        self.j.setdefault("samplers", []).append({"wrapS": wrap_s, "wrapT": wrap_t})
        self.j.setdefault("textures", []).append({"source": len(self.j["images"]) - 1, "sampler": len(self.j["samplers"]) - 1})
        return len(self.j["textures"]) - 1

    def _buffer(self, uri):
        b = {"byteLength": len(self.bin)}
        if uri:
            b["uri"] = uri
        self.j["buffers"] = [b]

    def gltf(self, path, bin_name=None):
        if bin_name:
            self._buffer(bin_name)
            with open(os.path.join(os.path.dirname(path), bin_name), "wb") as f:
                f.write(self.bin)
        else:
            self._buffer("data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode())
        with open(path, "w") as f:
            json.dump(self.j, f, indent=1)

    def glb(self, path):
        self._buffer(None)
        write_glb(path, json.dumps(self.j).encode(), bytes(self.bin))


def write_glb(path, js, binary, tail=b""):
    js += b" " * (-len(js) % 4)
    binary += b"\0" * (-len(binary) % 4)
    body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(binary), b"BIN\0") + binary + tail
    with open(path, "wb") as f:
        f.write(b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body)


def main():
    points, tris = read_dump(sys.argv[1])
    out = sys.argv[2]
    os.makedirs(out + "/bad", exist_ok=True)
    n = len(points)
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    write_off(out + "/original.off", points, tris)

    def plain():
        d = Doc()
        d.node(mesh=d.mesh(points, tris))
        return d
    plain().gltf(out + "/plain.gltf")
    plain().glb(out + "/plain.glb")
    plain().gltf(out + "/external.gltf", "external.bin")

    # hierarchy: world = T(tA) Rz(90) S(2) * T(tB) Rx(180) S(0.5) = P, the signed permutation
    # (x, y, z) -> (y, x, -z), whose inverse is itself
    d = Doc()
    decoy = d.mesh([(50.0, 50.0, 50.0), (51.0, 50.0, 50.0), (50.0, 51.0, 50.0)], [(0, 1, 2)])
    d.node(mesh=decoy)  # scenes[0]: not the default scene
    stored = [(p[1], p[0], -p[2]) for p in points]
    mesh = d.mesh(stored, tris)
    d.node(root=False, name="unrelated")
    child = d.node(root=False, mesh=mesh, translation=[0.75, 0.125, -1.5], rotation=[1, 0, 0, 0], scale=[0.5, 0.5, 0.5])
    root = d.node(root=False, children=[child], matrix=[0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 2, 0, 0.25, -1.5, 3.0, 1])
    d.j["scenes"].append({"nodes": [root]})
    d.j["scene"] = 1
    d.gltf(out + "/hierarchy.gltf")

    d = Doc()
    d.node(mesh=d.mesh([(-p[0], p[1], p[2]) for p in points], [(a, c, b) for a, b, c in tris]), scale=[-1, 1, 1])
    d.glb(out + "/mirror.glb")

    d = Doc()
    m = d.mesh(points, tris)
    d.node(mesh=m)
    d.node(mesh=m, translation=[2.0, 0.0, 0.0])
    d.gltf(out + "/instances.gltf")
    write_off(out + "/instances.off", points + [(f32(p[0] + 2.0), p[1], p[2]) for p in points],
              tris + [(a + n, b + n, c + n) for a, b, c in tris])

    d = plain()
    d.material(baseColorFactor=[1, 1, 1, 1])
    d.gltf(out + "/white.gltf")

    factor = [0.2, 0.5, 0.8]
    d = plain()
    d.material(baseColorFactor=factor + [1])
    d.gltf(out + "/factor.gltf")
    rgb = tuple(srgb_byte(f) for f in factor)
    write_off(out + "/factor.off", points, tris, [rgb] * n)
    with open(out + "/factor.rgb", "w") as f:
        f.write("%d %d %d\n" % rgb)

    # COLOR_0 as bytes: linear values, so the file's 128 is not sRGB's 128
    c8 = [(37 * i % 256, 91 * i % 256, 173 * i % 256, 255) for i in range(n)]
    d = Doc()
    d.node(mesh=d.mesh(points, tris, {"COLOR_0": d.accessor(U8, "VEC4", [c for q in c8 for c in q], n, True)}))
    d.glb(out + "/colour0.glb")
    write_off(out + "/colour0.off", points, tris, [tuple(srgb_byte(c / 255.0) for c in q[:3]) for q in c8])

    cf = [tuple(f32(((k + 1) * 0.37 * i) % 1.0) for k in range(3)) for i in range(n)]
    factor = [0.5, 1.0, 0.25]
    d = Doc()
    d.node(mesh=d.mesh(points, tris, {"COLOR_0": d.accessor(F32, "VEC3", [c for q in cf for c in q], n)}))
    d.material(baseColorFactor=factor + [1])
    d.gltf(out + "/colour0f.gltf")
    write_off(out + "/colour0f.off", points, tris, [tuple(srgb_byte(factor[k] * q[k]) for k in range(3)) for q in cf])

    # textures: 4x4 texels of distinct colours
    tex = [[((64 * x + 17) % 256, (64 * y + 40) % 256, (29 * (x + 4 * y)) % 256) for x in range(4)] for y in range(4)]
    image = png(4, 4, tex)
    uv = [(f32((p[0] - lo[0]) / (hi[0] - lo[0]) * 2.5 - 0.7), f32((p[1] - lo[1]) / (hi[1] - lo[1]) * 2.5 - 0.7)) for p in points]

    def textured(image_ref, bin_name=None, path=None):
        d = Doc()
        d.node(mesh=d.mesh(points, tris, {"TEXCOORD_0": d.accessor(F32, "VEC2", [c for q in uv for c in q], n)}))
        if image_ref is None:
            image_ref = {"uri": "data:image/png;base64," + base64.b64encode(image).decode()}
        d.material(baseColorTexture={"index": d.texture(image_ref, 10497, 33648)})
        d.gltf(path, bin_name)
    textured(None, path=out + "/texture.gltf")
    with open(out + "/texture-file.png", "wb") as f:
        f.write(image)
    textured({"uri": "texture-file.png"}, "texture-file.bin", out + "/texture-file.gltf")
    write_off(out + "/texture.off", points, tris,
              [tex[texel(t, 4, 33648)][texel(s, 4, 10497)] for s, t in uv])

    uv16 = [(int(min(max((p[0] - lo[0]) / (hi[0] - lo[0]), 0), 1) * 65535 + 0.5),
             int(min(max((p[2] - lo[2]) / (hi[2] - lo[2]), 0), 1) * 65535 + 0.5)) for p in points]
    factor = [1.0, 0.5, 1.0]
    d = Doc()
    other = d.accessor(F32, "VEC2", [0.99, 0.99] * n, n)
    d.node(mesh=d.mesh(points, tris, {"TEXCOORD_0": other,
                                      "TEXCOORD_1": d.accessor(U16, "VEC2", [c for q in uv16 for c in q], n, True)}))
    t = d.texture({"bufferView": d.view(image), "mimeType": "image/png"}, 33071, 33071)
    d.material(baseColorTexture={"index": t, "texCoord": 1}, baseColorFactor=factor + [1])
    d.glb(out + "/texture.glb")
    write_off(out + "/texture-glb.off", points, tris,
              [tuple(srgb_byte(factor[k] * s2l(tex[texel(b / 65535.0, 4, 33071)][texel(a / 65535.0, 4, 33071)][k] / 255.0))
                     for k in range(3)) for a, b in uv16])

    # strips and fans, beside points and lines primitives that are skipped
    sq = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0), (0.0, 2.0, 0.5)]
    for name, mode, want in (("strip", 5, [(0, 1, 2), (1, 3, 2), (2, 3, 4)]),
                             ("fan", 6, [(1, 2, 0), (2, 3, 0), (3, 4, 0)])):
        d = Doc()
        d.node(mesh=d.mesh(sq, None, mode=mode))
        d.node(mesh=d.mesh(sq, None, mode=0))
        d.node(mesh=d.mesh(sq, [(0, 1, 2)], mode=1))
        d.gltf(out + "/%s.gltf" % name)
        write_off(out + "/%s.off" % name, sq, want)

    bad(out + "/bad", points, tris)


def bad(out, points, tris):
    """One problem per file; tests/gen/gltf.sh holds the expected place and message of each."""
    n = len(points)

    def small():
        d = Doc()
        d.node(mesh=d.mesh(points[:8], [(0, 1, 2), (2, 3, 4), (4, 5, 6), (5, 6, 7)]))
        return d

    plain = Doc()
    plain.node(mesh=plain.mesh(points, tris))
    plain.glb(out + "/truncated.glb")
    with open(out + "/truncated.glb", "rb") as f:
        data = f.read()
    with open(out + "/truncated.glb", "wb") as f:
        f.write(data[:len(data) // 2])

    text = json.dumps(small().j, indent=1).split("\n")
    text.insert(2, '  "oops" 1,')  # line 3: a member without its colon
    with open(out + "/badjson.gltf", "w") as f:
        f.write("\n".join(text))

    d = small()
    idx = d.j["accessors"][d.j["meshes"][0]["primitives"][0]["indices"]]
    view = d.j["bufferViews"][idx["bufferView"]]
    d.bin[view["byteOffset"] + 4 * 5:view["byteOffset"] + 4 * 6] = struct.pack("<I", 8)  # element 5: index 8 of 8
    d.gltf(out + "/index-range.gltf")

    d = small()
    d.j["accessors"][0]["count"] = 9
    d.gltf(out + "/beyond.gltf")

    d = small()
    prim = d.j["meshes"][0]["primitives"][0]
    prim["attributes"] = {"POSITON": prim["attributes"]["POSITION"]}
    d.gltf(out + "/noposition.gltf")

    d = small()
    d.j["extensionsUsed"] = d.j["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    d.gltf(out + "/extreq.gltf")

    d = Doc()
    pts = list(points[:8])
    pts[7] = (float("nan"), pts[7][1], pts[7][2])
    d.node(mesh=d.mesh(pts, [(0, 1, 2)]))
    d.glb(out + "/nonfinite.glb")

    d = small()
    d.j["nodes"].append({"children": [0]})
    d.j["nodes"][0]["children"] = [1]
    d.gltf(out + "/cycle.gltf")

    d = small()
    d.j["nodes"] += [{"children": [0]}, {"children": [0]}]
    d.j["scenes"][0]["nodes"] = [1, 2]
    d.gltf(out + "/dag.gltf")

    small().gltf(out + "/missing-bin.gltf", "missing-bin.bin")
    os.remove(out + "/missing-bin.bin")

    d = small()
    d.j["accessors"][0].update(componentType=U16, normalized=False)
    d.gltf(out + "/postype.gltf")

    d = small()
    d.j["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": 1, "componentType": U32},
                                     "values": {"bufferView": 0}}
    d.gltf(out + "/sparse.gltf")

    def with_image(name, data):
        d = Doc()
        d.node(mesh=d.mesh(points[:3], [(0, 1, 2)], {"TEXCOORD_0": d.accessor(F32, "VEC2", [0.5] * 6, 3)}))
        d.material(baseColorTexture={"index": d.texture(
            {"uri": "data:image/png;base64," + base64.b64encode(data).decode()}, 10497, 10497)})
        d.gltf(out + "/" + name)
    with_image("notimage.gltf", b"GIF89a" + bytes(40))
    ihdr = lambda w, h: png(1, 1, [[(1, 2, 3)]]).replace(struct.pack(">II", 1, 1), struct.pack(">II", w, h), 1)
    with_image("hugepng.gltf", ihdr(9000, 9000))
    with_image("lyingpng.gltf", ihdr(4000, 4000))

    d = small()
    d.j["asset"]["version"] = "1.0"
    d.gltf(out + "/version1.gltf")

    d = small()
    deep = {}
    for _ in range(100):
        deep = {"a": [deep]}
    d.j["nodes"][0]["extras"] = deep
    d.gltf(out + "/deep.gltf")

    d = small()
    d.j["meshes"][0]["primitives"][0]["material"] = -1
    d.gltf(out + "/neg-index.gltf")

    d = small()
    d.j["meshes"][0]["primitives"][0]["indices"] = 4294967296
    d.gltf(out + "/int-range.gltf")

    d = small()
    d.j["meshes"][0]["primitives"][0]["mode"] = 9
    d.gltf(out + "/mode.gltf")

    d = small()
    d.j["nodes"][0]["matrix"] = [1e999] + [0] * 15
    with open(out + "/huge-number.gltf", "w") as f:
        f.write(json.dumps(d.j).replace("Infinity", "1e999"))

    small().glb(out + "/badmagic.glb")
    with open(out + "/badmagic.glb", "r+b") as f:
        f.write(b"glTX")

    # a BIN chunk whose length counts its own 8-byte header, and a buffer that long: 8 bytes past
    # the file (tinygltf 2.7's own check lets it through and copies them)
    d = small()
    binary = bytes(d.bin) + b"\0" * (-len(d.bin) % 4)
    d.j["buffers"] = [{"byteLength": len(binary) + 8}]
    js = json.dumps(d.j).encode()
    js += b" " * (-len(js) % 4)
    body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(binary) + 8, b"BIN\0") + binary
    with open(out + "/binpast.glb", "wb") as f:
        f.write(b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body)

    # a texture's PNG in a buffer view that claims bytes past its buffer (tinygltf 2.7's own image
    # loader hands stb_image that range unchecked)
    d = Doc()
    d.node(mesh=d.mesh(points[:3], [(0, 1, 2)], {"TEXCOORD_0": d.accessor(F32, "VEC2", [0.5] * 6, 3)}))
    image = png(8, 8, [[(x, y, 9) for x in range(8)] for y in range(8)])
    view = d.view(image[:len(image) // 2])
    d.j["bufferViews"][view]["byteLength"] = len(image)
    d.material(baseColorTexture={"index": d.texture({"bufferView": view, "mimeType": "image/png"}, 10497, 10497)})
    d.glb(out + "/imageview.glb")

    d = small()
    d.j["buffers"] = [{"byteLength": 0}]
    write_glb(out + "/emptybuffer.glb", json.dumps(d.j).encode(), bytes(d.bin))

    small().gltf(out + "/json-named-glb.glb")
    small().glb(out + "/glb-named-gltf.gltf")
    with open(out + "/no-asset.gltf", "w") as f:
        f.write("{}\n")

    # a few hundred bytes that claim four billion vertices (tests/gen/gltf.sh runs it under ulimit -v)
    d = small()
    d.j["accessors"][0]["count"] = 4000000000
    d.gltf(out + "/absurd-count.gltf")


if __name__ == "__main__":
    main()
