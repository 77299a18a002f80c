#!/usr/bin/env python3
"""synthetic_scenes.py - three scenes of the classes the shared ones lack, as a new user's
would be: a stairwell (a closed shaft of box walls, four flights of nine box steps, landings
and railing posts, a 0.6 x 0.6 lamp 0.3 below the ceiling), an office (40 desks on thin legs,
open chair shells, shelves, a lamp under the ceiling) and a forest (12 trees of 1,500 leaf
quads each over a ground quad, a large light high to one side); with --foliage also a dense
tree (60,000 leaf quads in a 4 m crown: 120k triangles) and a big forest (60 trees of 8,000
leaf quads: 960k triangles, 34 MB), the scenes of docs/wedges-time.md ("Dense foliage").
Written as glTF 2.0 binaries
with a views.json beside them in the shared scenes' format, so that

    penumbra render DIR/stairwell.glb --views DIR/views.json --view stairwell --algo mcsm ...

renders them as docs/algorithms/mcsm.md ("Stacked solids: exact rays") measured them. Python 3
standard library only; the same files on every run (a fixed seed).

usage: tools/synthetic_scenes.py DIR [--foliage]
"""
import json
import math
import os
import random
import struct
import sys


def write_glb(path, objs):
    """objs: (positions [(x, y, z)], indices [int]) per mesh; one node per mesh."""
    data = bytearray()
    views, accs, meshes, nodes = [], [], [], []
    for pos, idx in objs:
        off = len(data)
        for p in pos:
            data += struct.pack('<3f', *p)
        pv = len(views)
        views.append({"buffer": 0, "byteOffset": off, "byteLength": len(pos) * 12})
        mn = [min(p[i] for p in pos) for i in range(3)]
        mx = [max(p[i] for p in pos) for i in range(3)]
        pa = len(accs)
        accs.append({"bufferView": pv, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": mn, "max": mx})
        while len(data) % 4:
            data.append(0)
        off = len(data)
        for i in idx:
            data += struct.pack('<I', i)
        iv = len(views)
        views.append({"buffer": 0, "byteOffset": off, "byteLength": len(idx) * 4})
        ia = len(accs)
        accs.append({"bufferView": iv, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        meshes.append({"primitives": [{"attributes": {"POSITION": pa}, "indices": ia}]})
        nodes.append({"mesh": len(meshes) - 1})
    while len(data) % 4:
        data.append(0)
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes,
           "meshes": meshes, "accessors": accs, "bufferViews": views, "buffers": [{"byteLength": len(data)}]}
    j = json.dumps(doc).encode()
    while len(j) % 4:
        j += b' '
    out = struct.pack('<III', 0x46546C67, 2, 12 + 8 + len(j) + 8 + len(data))
    out += struct.pack('<II', len(j), 0x4E4F534A) + j + struct.pack('<II', len(data), 0x004E4942) + bytes(data)
    with open(path, 'wb') as f:
        f.write(out)


def box(x0, y0, z0, x1, y1, z1):
    """A closed box wound outward: vertex xi * 4 + yi * 2 + zi."""
    pos = [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    idx = []
    for a, b, c, d in ((0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)):
        idx += [a, b, c, a, c, d]
    return pos, idx


def merge(parts):
    pos, idx = [], []
    for p, i in parts:
        o = len(pos)
        pos += p
        idx += [o + k for k in i]
    return pos, idx


def quad(c, u, v):
    """An open quad (a sheet) centred at c with half-edges u and v."""
    pos = [tuple(c[k] - u[k] - v[k] for k in range(3)), tuple(c[k] + u[k] - v[k] for k in range(3)),
           tuple(c[k] + u[k] + v[k] for k in range(3)), tuple(c[k] - u[k] + v[k] for k in range(3))]
    return pos, [0, 1, 2, 0, 2, 3]


def stairwell():
    w, h, d, t = 4, 10, 4, 0.2
    objs = [box(-t, -t, -t, w + t, 0, d + t), box(-t, h, -t, w + t, h + t, d + t), box(-t, 0, -t, 0, h, d + t),
            box(w, 0, -t, w + t, h, d + t), box(0, 0, -t, w, h, 0), box(0, 0, d, w, h, d + t)]
    for f in range(4):
        steps = []
        for s in range(9):
            y = f * 2.5 + s * 0.25
            if f % 2 == 0:
                steps.append(box(0.2 + s * 0.35, y, 0.2, 0.2 + s * 0.35 + 0.35, y + 0.25, 1.6))
            else:
                steps.append(box(3.8 - s * 0.35 - 0.35, y, 2.4, 3.8 - s * 0.35, y + 0.25, 3.8))
        objs.append(merge(steps))
        # the landing above the flight; above the last one a 1 cm cube in the corner instead
        objs.append(box(0.2, f * 2.5 + 2.25, 1.6, 3.8, f * 2.5 + 2.5, 2.4) if f < 3 else box(0, 0, 0, 0.01, 0.01, 0.01))
        for s in range(0, 9, 2):
            objs.append(box(0.2 + s * 0.35 + 0.15, f * 2.5 + s * 0.25 + 0.25, 1.55, 0.2 + s * 0.35 + 0.2,
                            f * 2.5 + s * 0.25 + 1.2, 1.6))
    return objs


def leaf(rng, cx, cy, cz, r, s):
    """A leaf quad of size s at distance r (drawn first by the caller) from (cx, cy, cz)."""
    a, b = rng.uniform(0, 6.283), rng.uniform(-1, 1)
    c = (cx + r * math.cos(a) * math.sqrt(1 - b * b), cy + r * b, cz + r * math.sin(a) * math.sqrt(1 - b * b))
    u = (s * rng.uniform(-1, 1), s * rng.uniform(-0.3, 0.3), s * rng.uniform(-1, 1))
    v = (-u[2] * 0.5, s * 0.8, u[0] * 0.5)
    return quad(c, u, v)


def forest(rng):
    objs = [quad((0, 0, 0), (20, 0, 0), (0, 0, 20))]
    for _ in range(12):
        cx = rng.uniform(-15, 15)
        cz = rng.uniform(-15, 15)
        h = rng.uniform(4, 7)
        objs.append(box(cx - 0.2, 0, cz - 0.2, cx + 0.2, h, cz + 0.2))
        objs.append(merge([leaf(rng, cx, h + 1.5, cz, rng.uniform(0, 2.5), 0.12) for _ in range(1500)]))
    return objs


def densetree(rng):
    objs = [quad((0, 0, 0), (12, 0, 0), (0, 0, 12)), box(-0.3, 0, -0.3, 0.3, 5, 0.3)]
    objs.append(merge([leaf(rng, 0, 7, 0, 4 * rng.random() ** 0.5, 0.07) for _ in range(60000)]))
    return objs


def bigforest(rng):
    objs = [quad((0, 0, 0), (40, 0, 0), (0, 0, 40))]
    for _ in range(60):
        cx, cz, h = rng.uniform(-35, 35), rng.uniform(-35, 35), rng.uniform(4, 8)
        objs.append(box(cx - 0.25, 0, cz - 0.25, cx + 0.25, h, cz + 0.25))
        objs.append(merge([leaf(rng, cx, h + 2, cz, rng.uniform(0, 3), 0.1) for _ in range(8000)]))
    return objs


def office():
    objs = [box(-0.2, -0.2, -0.2, 20.2, 0, 12.2), box(-0.2, 3, -0.2, 20.2, 3.2, 12.2), box(-0.2, 0, -0.2, 0, 3, 12.2),
            box(20, 0, -0.2, 20.2, 3, 12.2), box(0, 0, -0.2, 20, 3, 0), box(0, 0, 12, 20, 3, 12.2)]
    for i in range(8):
        for j in range(5):
            x, z = 1.5 + i * 2.3, 1.5 + j * 2.1
            parts = [box(x, 0.72, z, x + 1.4, 0.75, z + 0.7)]
            for lx, lz in ((x, z), (x + 1.37, z), (x, z + 0.67), (x + 1.37, z + 0.67)):
                parts.append(box(lx, 0, lz, lx + 0.03, 0.72, lz + 0.03))
            objs.append(merge(parts))
            # a chair shell: seat and back as open sheets
            objs.append(merge([quad((x + 0.7, 0.45, z + 1.0), (0.22, 0, 0), (0, 0, 0.22)),
                               quad((x + 0.7, 0.75, z + 1.22), (0.22, 0, 0), (0, 0.3, 0.02))]))
    for k in range(6):
        objs.append(merge([box(0.0, 0.4 + k * 0.45, 3 + s * 2.0, 0.35, 0.42 + k * 0.45, 4.5 + s * 2.0) for s in range(3)]))
    return objs


VIEWS = {
    "stairwell": {"size": [512, 512], "eye": [3.6, 6.5, 3.6], "target": [1.0, 3.0, 1.2], "up": [0, 1, 0], "fov": 70,
                  "light_center": [2, 9.7, 2], "light_u": [0.3, 0, 0], "light_v": [0, 0, 0.3], "ground": False},
    "office": {"size": [512, 512], "eye": [19, 2.4, 11.5], "target": [8, 0.4, 4], "up": [0, 1, 0], "fov": 65,
               "light_center": [10, 2.9, 6], "light_u": [0.4, 0, 0], "light_v": [0, 0, 0.4], "ground": False},
    "forest": {"size": [512, 512], "eye": [26, 16, 26], "target": [0, 3, 0], "up": [0, 1, 0], "fov": 55,
               "light_center": [-25, 40, 20], "light_u": [2, 0, 2], "light_v": [-1.6, -1.9, 1.6], "ground": False},
    "densetree": {"size": [256, 256], "eye": [14, 9, 14], "target": [0, 4, 0], "up": [0, 1, 0], "fov": 55,
                  "light_center": [-10, 20, 6], "light_u": [1.5, 0, 1.5], "light_v": [-1.2, -1.4, 1.2], "ground": False},
    "bigforest": {"size": [512, 512], "eye": [60, 35, 60], "target": [0, 3, 0], "up": [0, 1, 0], "fov": 55,
                  "light_center": [-40, 60, 30], "light_u": [3, 0, 3], "light_v": [-2.4, -2.9, 2.4], "ground": False},
}


def main():
    if len(sys.argv) not in (2, 3) or (len(sys.argv) == 3 and sys.argv[2] != '--foliage'):
        sys.exit(__doc__.strip().splitlines()[-1])
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    rng = random.Random(7)
    write_glb(os.path.join(out, 'stairwell.glb'), stairwell())
    write_glb(os.path.join(out, 'forest.glb'), forest(rng))
    write_glb(os.path.join(out, 'office.glb'), office())
    names = ['stairwell', 'office', 'forest']
    if len(sys.argv) == 3:
        write_glb(os.path.join(out, 'densetree.glb'), densetree(random.Random(5)))
        write_glb(os.path.join(out, 'bigforest.glb'), bigforest(random.Random(11)))
        names += ['densetree', 'bigforest']
    with open(os.path.join(out, 'views.json'), 'w') as f:
        json.dump({n: VIEWS[n] for n in names}, f, indent=2)
    print('wrote', ', '.join(n + '.glb' for n in names), 'and views.json to', out)


if __name__ == '__main__':
    main()
