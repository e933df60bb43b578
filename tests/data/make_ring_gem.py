#!/usr/bin/python3
"""Writes the ring-holding-a-gem test asset (tests/data/): ring-gem.glb, a glTF 2.0 binary of
two nodes, "ring" (a torus standing in the xy plane, at the origin) and "gem" (a faceted
stone translated onto the ring's top), and two scenes rendering it the same way:
ring-gem.json (the meshes read from ring-gem.glb by node) and ring-gem-inline.json (the
same triangles written inline, the gem's node translation as the object's transform).
The file is a whole glTF scene too (`refract import`, docs/gltf.md): its materials (gold,
metallic; the gem a dielectric by KHR_materials_transmission, _ior, _volume and
_dispersion), a camera and a KHR_lights_punctual point light; ring-gem-gltf.json is that
scene written by hand.
Standard library only. Coordinates are single-precision values (glTF stores float32), each
mesh's vertices listed in the order its triangles first use them, without -0, so that the
two scenes hold the same numbers. Run: python3 tests/data/make_ring_gem.py"""
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0] + 0.0  # float32 value, -0 -> +0


def oriented(verts, tris):
    """Triangles wound counter-clockwise seen from outside (positive volume)."""
    vol = 0.0
    for a, b, c in tris:
        A, B, C = verts[a], verts[b], verts[c]
        vol += (A[0] * (B[1] * C[2] - B[2] * C[1]) - A[1] * (B[0] * C[2] - B[2] * C[0]) +
                A[2] * (B[0] * C[1] - B[1] * C[0]))
    return tris if vol > 0 else [(a, c, b) for a, b, c in tris]


def first_use_order(verts, tris):
    order, index = [], {}
    for t in tris:
        for v in t:
            if v not in index:
                index[v] = len(order)
                order.append(v)
    return [verts[v] for v in order], [tuple(index[v] for v in t) for t in tris]


def torus(R=1.0, r=0.12, nu=48, nv=12):
    verts = []
    for i in range(nu):
        u = 2 * math.pi * i / nu
        for j in range(nv):
            v = 2 * math.pi * j / nv
            verts.append(tuple(f32(x) for x in ((R + r * math.cos(v)) * math.cos(u),
                                                 (R + r * math.cos(v)) * math.sin(u), r * math.sin(v))))
    tris = []
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
            tris += [(a, b, c), (a, c, d)]
    return first_use_order(verts, oriented(verts, tris))


def gem(n=8, girdle=0.3, table=0.17, crown=0.1, pavilion=0.26):
    """A stone of n-fold symmetry: table polygon, girdle polygon, culet point (axis y)."""
    verts = [(0.0, f32(crown), 0.0)]  # table centre
    verts += [(f32(table * math.cos(2 * math.pi * k / n)), f32(crown), f32(table * math.sin(2 * math.pi * k / n)))
              for k in range(n)]
    verts += [(f32(girdle * math.cos(2 * math.pi * (k + 0.5) / n)), 0.0, f32(girdle * math.sin(2 * math.pi * (k + 0.5) / n)))
              for k in range(n)]
    verts.append((0.0, f32(-pavilion), 0.0))  # culet
    verts = [tuple(x + 0.0 for x in v) for v in verts]
    T, G, C = 1, 1 + n, 1 + 2 * n
    tris = []
    for k in range(n):
        k1 = (k + 1) % n
        tris.append((0, T + k1, T + k))             # table
        tris.append((T + k, T + k1, G + k))         # crown, table edge
        tris.append((G + k, T + k1, G + k1))        # crown, girdle edge
        tris.append((G + k1, C, G + k))             # pavilion
    tris = [tuple(t) for t in tris]
    return first_use_order(verts, oriented(verts, tris))


GEM_AT = [0.0, 1.375, 0.0]  # the gem node's translation (exact in float32)


# The glTF scene: the gem's Abbe number V_d as KHR_materials_dispersion's 20/V_d, a faint
# yellow absorption (attenuation colour after a distance), a camera 2.5 in front of the ring
# turned half a turn about y (glTF's camera looks along its -z) and a point light.
ND, VD = 2.417, 55.3
ATTENUATION, DISTANCE = [0.9, 0.95, 1.0], 2.0
CAMERA_AT, VFOV_DEG = [0.0, 1.25, -2.5], 35
LIGHT_AT = [2.0, 5.0, -4.0]
MATERIALS = [
    {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [0.95, 0.75, 0.3, 1.0], "metallicFactor": 1.0,
                                              "roughnessFactor": 0.0}},
    {"name": "diamond", "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.0},
     "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": ND},
                    "KHR_materials_volume": {"thicknessFactor": 0.5, "attenuationColor": ATTENUATION,
                                             "attenuationDistance": DISTANCE},
                    "KHR_materials_dispersion": {"dispersion": 20 / VD}}}]


def write_glb(path, meshes):
    bin_ = bytearray()
    views, accessors, gmeshes, nodes = [], [], [], []
    for material, (name, (verts, tris), translation) in enumerate(meshes):
        pos = b"".join(struct.pack("<3f", *v) for v in verts)
        idx = b"".join(struct.pack("<3I", *t) for t in tris)
        for data, target in ((pos, 34962), (idx, 34963)):
            views.append({"buffer": 0, "byteOffset": len(bin_), "byteLength": len(data), "target": target})
            bin_ += data
            while len(bin_) % 4:
                bin_ += b"\0"
        accessors.append({"bufferView": len(views) - 2, "componentType": 5126, "count": len(verts), "type": "VEC3",
                          "min": [min(v[c] for v in verts) for c in range(3)],
                          "max": [max(v[c] for v in verts) for c in range(3)]})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": 3 * len(tris), "type": "SCALAR"})
        gmeshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                      "indices": len(accessors) - 1, "mode": 4,
                                                      "material": material}]})
        node = {"name": name, "mesh": len(gmeshes) - 1}
        if translation:
            node["translation"] = translation
        nodes.append(node)
    nodes.append({"name": "camera", "camera": 0, "translation": CAMERA_AT, "rotation": [0.0, 1.0, 0.0, 0.0]})
    nodes.append({"name": "light", "translation": LIGHT_AT, "extensions": {"KHR_lights_punctual": {"light": 0}}})
    doc = {"asset": {"version": "2.0", "generator": "refract tests/data/make_ring_gem.py"},
           "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": gmeshes,
           "materials": MATERIALS,
           "cameras": [{"type": "perspective", "extras": {"width": 64, "height": 48},
                        "perspective": {"yfov": math.radians(VFOV_DEG), "aspectRatio": 4 / 3, "znear": 0.01}}],
           "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1.0, 1.0, 1.0],
                                                              "intensity": 1.0}]}},
           "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_dispersion", "KHR_materials_ior",
                              "KHR_materials_transmission", "KHR_materials_volume"],
           "accessors": accessors, "bufferViews": views, "buffers": [{"byteLength": len(bin_)}]}
    js = json.dumps(doc, separators=(",", ":")).encode()
    while len(js) % 4:
        js += b" "
    total = 12 + 8 + len(js) + 8 + len(bin_)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, total))
        f.write(struct.pack("<I4s", len(js), b"JSON") + js)
        f.write(struct.pack("<I4s", len(bin_), b"BIN\0") + bytes(bin_))


def scene(objects):
    return {"description": "A gold ring holding a dispersive gem (tests/data/make_ring_gem.py)",
            "camera": {"location": [0.4, 1.9, -2.6], "look_at": [0, 1.2, 0], "angle": 40, "width": 64, "height": 48},
            "background": [0.55, 0.7, 0.9],
            "materials": {"gold": {"type": "metal", "color": [0.95, 0.75, 0.3]},
                          "diamond": {"type": "dielectric", "dispersion": "diamond"}},
            "objects": objects,
            "lights": [{"position": [2, 5, -4], "color": [1, 1, 1]}],
            "render": {"max_depth": 8, "spectral": {"step": 30}}}


def main():
    ring, stone = torus(), gem()
    write_glb(os.path.join(HERE, "ring-gem.glb"), [("ring", ring, None), ("gem", stone, GEM_AT)])
    by_file = [{"type": "mesh", "name": "ring", "file": "ring-gem.glb", "node": "ring", "material": "gold"},
               {"type": "mesh", "name": "gem", "file": "ring-gem.glb", "node": "gem", "material": "diamond"}]
    inline = [{"type": "mesh", "name": "ring", "vertices": [list(v) for v in ring[0]],
               "triangles": [list(t) for t in ring[1]], "material": "gold"},
              {"type": "mesh", "name": "gem", "vertices": [list(v) for v in stone[0]],
               "triangles": [list(t) for t in stone[1]], "material": "diamond",
               "transform": {"translate": GEM_AT}}]
    for name, objs in (("ring-gem.json", by_file), ("ring-gem-inline.json", inline)):
        with open(os.path.join(HERE, name), "w") as f:
            f.write(json.dumps(scene(objs), indent=1) + "\n")
    # The glTF scene by hand, as refract's scene format says it (docs/gltf.md's mapping):
    # glTF is right-handed, refract's camera POV-Ray's left-handed one, so the import mirrors
    # z (a point (x, y, z) of the file is (x, y, -z) in the scene; the meshes by a transform).
    def mirrored(p):
        return [p[0], p[1], -p[2] if p[2] else 0.0]
    gltf_scene = {
        "description": "ring-gem.glb's glTF scene written by hand (tests/data/make_ring_gem.py)",
        "camera": {"location": mirrored(CAMERA_AT), "look_at": [0, 1.25, 0], "vfov": VFOV_DEG, "width": 64,
                   "height": 48},
        "materials": {"gold": {"type": "metal", "color": [0.95, 0.75, 0.3]},
                      "diamond": {"type": "dielectric", "dispersion": {"model": "abbe", "nd": ND, "Vd": VD},
                                  "absorption": {"transmittance": ATTENUATION, "thickness": DISTANCE}}},
        "objects": [dict(o, transform={"scale": [1, 1, -1]}) for o in by_file],
        "lights": [{"position": mirrored(LIGHT_AT), "color": [1, 1, 1]}]}
    with open(os.path.join(HERE, "ring-gem-gltf.json"), "w") as f:
        f.write(json.dumps(gltf_scene, indent=1) + "\n")


if __name__ == "__main__":
    main()
