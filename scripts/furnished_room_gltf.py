#!/usr/bin/env python3
"""Writes a furnished room as glTF 2.0 (one file, the buffer embedded): a scene of the kind a user
brings, for trying `vplkit sweep` and `vplkit view` on something vplkit has never seen:

    scripts/furnished_room_gltf.py output/room.gltf
    build/vplkit sweep --technique rsm-radial --scene output/room.gltf --vary radius=0.125,0.25,0.5,0.75 \
        --reference rsm-brute-force --out output/room-radius

A 6 x 3 x 5 room open at the front (a floor, a ceiling, a back wall and two coloured side walls),
a table with four legs, two chairs, a sofa, a bookshelf against the back wall, a rug, a spot light
near the ceiling aimed at the table and a perspective camera at the open side. Standard library
only; one primitive per material, as vplkit's own glTF writer does.
"""
import base64
import json
import math
import struct
import sys


def box(centre, size, colour, quads):
    """Appends the six faces of an axis-aligned box (outward normals)."""
    cx, cy, cz = centre
    hx, hy, hz = size[0] / 2, size[1] / 2, size[2] / 2
    x0, x1, y0, y1, z0, z1 = cx - hx, cx + hx, cy - hy, cy + hy, cz - hz, cz + hz
    faces = [
        ((0, 0, 1), [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]),
        ((0, 0, -1), [(x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)]),
        ((1, 0, 0), [(x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)]),
        ((-1, 0, 0), [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)]),
        ((0, 1, 0), [(x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0)]),
        ((0, -1, 0), [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)]),
    ]
    for normal, corners in faces:
        quads.setdefault(colour, []).append((normal, corners))


def quad(corners, normal, colour, quads):
    quads.setdefault(colour, []).append((normal, corners))


def room():
    quads = {}
    white, red, blue = (0.75, 0.74, 0.70), (0.70, 0.15, 0.12), (0.15, 0.25, 0.65)
    wood, fabric, rug, books = (0.45, 0.28, 0.15), (0.30, 0.55, 0.30), (0.80, 0.65, 0.25), (0.55, 0.20, 0.45)
    w, h, d = 3.0, 3.0, 2.5  # half width, height, half depth
    quad([(-w, 0, d), (w, 0, d), (w, 0, -d), (-w, 0, -d)], (0, 1, 0), white, quads)      # floor
    quad([(-w, h, -d), (w, h, -d), (w, h, d), (-w, h, d)], (0, -1, 0), white, quads)     # ceiling
    quad([(-w, 0, -d), (w, 0, -d), (w, h, -d), (-w, h, -d)], (0, 0, 1), white, quads)    # back wall
    quad([(-w, 0, d), (-w, 0, -d), (-w, h, -d), (-w, h, d)], (1, 0, 0), red, quads)      # left wall
    quad([(w, 0, -d), (w, 0, d), (w, h, d), (w, h, -d)], (-1, 0, 0), blue, quads)        # right wall
    # A table and its legs.
    box((0.3, 0.75, -0.2), (1.6, 0.06, 0.9), wood, quads)
    for x in (-0.4, 1.0):
        for z in (-0.55, 0.15):
            box((x, 0.36, z), (0.08, 0.72, 0.08), wood, quads)
    # Two chairs: seat, back, legs.
    for x, z, back in ((-0.9, -0.2, -1), (1.5, -0.2, 1)):
        box((x, 0.45, z), (0.45, 0.05, 0.45), wood, quads)
        box((x + back * 0.2, 0.75, z), (0.05, 0.6, 0.45), wood, quads)
        for dx in (-0.19, 0.19):
            for dz in (-0.19, 0.19):
                box((x + dx, 0.22, z + dz), (0.05, 0.44, 0.05), wood, quads)
    # A sofa against the left wall, a bookshelf against the back wall, a rug.
    box((-2.5, 0.25, 0.9), (0.8, 0.5, 2.0), fabric, quads)
    box((-2.8, 0.65, 0.9), (0.2, 0.8, 2.0), fabric, quads)
    box((1.8, 1.0, -2.3), (1.6, 2.0, 0.35), wood, quads)
    for shelf in range(4):
        box((1.8, 0.35 + 0.45 * shelf, -2.15), (1.4, 0.3, 0.05), books, quads)
    box((0.3, 0.01, -0.2), (2.6, 0.02, 1.8), rug, quads)
    return quads


def main():
    if len(sys.argv) != 2 or not sys.argv[1].endswith(".gltf"):
        sys.exit("usage: furnished_room_gltf.py OUT.gltf")
    quads = room()
    data, accessors, views, primitives, materials = bytearray(), [], [], [], []

    def add_view(payload, target):
        while len(data) % 4:
            data.append(0)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(payload), "target": target})
        data.extend(payload)
        return len(views) - 1

    for colour, faces in quads.items():
        positions, normals, indices = [], [], []
        for normal, corners in faces:
            base = len(positions)
            positions.extend(corners)
            normals.extend([normal] * 4)
            indices.extend([base, base + 1, base + 2, base, base + 2, base + 3])
        lows = [min(p[i] for p in positions) for i in range(3)]
        highs = [max(p[i] for p in positions) for i in range(3)]
        position_view = add_view(b"".join(struct.pack("<3f", *p) for p in positions), 34962)
        normal_view = add_view(b"".join(struct.pack("<3f", *n) for n in normals), 34962)
        index_view = add_view(b"".join(struct.pack("<I", i) for i in indices), 34963)
        accessors += [
            {"bufferView": position_view, "componentType": 5126, "count": len(positions), "type": "VEC3", "min": lows, "max": highs},
            {"bufferView": normal_view, "componentType": 5126, "count": len(normals), "type": "VEC3"},
            {"bufferView": index_view, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
        ]
        materials.append({"pbrMetallicRoughness": {"baseColorFactor": [*colour, 1.0], "metallicFactor": 0.0}})
        primitives.append({"attributes": {"POSITION": len(accessors) - 3, "NORMAL": len(accessors) - 2}, "indices": len(accessors) - 1,
                           "material": len(materials) - 1, "mode": 4})

    def look_at(eye, target):
        """The rotation quaternion of a node at `eye` whose -Z looks at `target`, +Y up."""
        f = [t - e for t, e in zip(target, eye)]
        n = math.sqrt(sum(c * c for c in f))
        f = [c / n for c in f]
        z = [-c for c in f]
        x = [z[2], 0.0, -z[0]]  # up x z with up = +Y
        n = math.sqrt(sum(c * c for c in x))
        x = [c / n for c in x]
        y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]]
        m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]
        trace = m[0][0] + m[1][1] + m[2][2]
        if trace > 0:
            s = 0.5 / math.sqrt(trace + 1.0)
            return [(m[2][1] - m[1][2]) * s, (m[0][2] - m[2][0]) * s, (m[1][0] - m[0][1]) * s, 0.25 / s]
        i = max(range(3), key=lambda k: m[k][k])
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * math.sqrt(1.0 + m[i][i] - m[j][j] - m[k][k])
        q = [0.0, 0.0, 0.0, (m[k][j] - m[j][k]) / s]
        q[i], q[j], q[k] = 0.25 * s, (m[j][i] + m[i][j]) / s, (m[k][i] + m[i][k]) / s
        return q

    light_at, light_to = (-1.2, 2.8, 1.2), (0.6, 0.0, -0.6)
    camera_at, camera_to = (0.0, 1.6, 5.2), (0.0, 0.9, -0.5)
    document = {
        "asset": {"version": "2.0", "generator": "vplkit scripts/furnished_room_gltf.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "color": [1.0, 0.95, 0.85], "intensity": 30.0,
                                                           "spot": {"innerConeAngle": 0.55, "outerConeAngle": 0.8}}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"mesh": 0, "name": "room"},
            {"camera": 0, "translation": list(camera_at), "rotation": look_at(camera_at, camera_to), "name": "camera"},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": list(light_at), "rotation": look_at(light_at, light_to), "name": "light"},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.05, "zfar": 50.0, "aspectRatio": 1.0}}],
        "meshes": [{"primitives": primitives, "name": "furnished room"}],
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(data)).decode()}],
    }
    with open(sys.argv[1], "w") as out:
        json.dump(document, out)
    print("wrote", sys.argv[1], sum(len(f) for f in quads.values()) * 2, "triangles")


if __name__ == "__main__":
    main()
