#!/usr/bin/env python3
"""Writes bench/scenes/fg-studio.gltf and bench/scenes/fg-hall.gltf: two furnished rooms for the
final-gathering measurements of docs/scenes.md ("Final gathering in the user's scene"), made
after the techniques were built and never used to tune them. Each is what an authoring tool
exports: boxes (one unit-cube mesh per material) placed by node TRS, a KHR_lights_punctual spot
aimed by its node's rotation, a perspective camera, named nodes.
Light variants of each room (the same geometry and camera; the final-gathering measurements with
a point light and with two lights, issue 38):
  fg-studio-point: a bulb (point light) under the studio's ceiling instead of the spot;
  fg-studio-two:   the spot and the bulb;
  fg-hall-point, fg-hall-two: the same for the hall.
  fg-studio: 3.4 x 2.5 x 4.2, a green wall, a bed, a desk and a shelf, a warm spot in a corner
             aimed down across the room; a node "vase" on the desk (for --object-node).
  fg-hall:   8 x 3.6 x 6, a blue floor, a yellow wall, two columns and a bench, a cold spot high
             on the long wall aimed at the floor's middle.
    python3 bench/make_fg_rooms.py      # deterministic: the same files every run
"""
import base64, json, math, pathlib, struct

def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]

def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

def look_rotation(eye, target):
    """The quaternion (x, y, z, w) that turns a node's -Z towards target - eye with +Y up."""
    f = normalize([t - e for t, e in zip(target, eye)])
    up = [0.0, 1.0, 0.0] if abs(f[1]) < 0.99 else [0.0, 0.0, -1.0]
    r = normalize(cross(f, up))
    u = cross(r, f)
    z = [-c for c in f]
    # Columns r, u, z of the rotation matrix.
    m = [[r[0], u[0], z[0]], [r[1], u[1], z[1]], [r[2], u[2], z[2]]]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 0.5 / math.sqrt(trace + 1.0)
        return [(m[2][1] - m[1][2]) * s, (m[0][2] - m[2][0]) * s, (m[1][0] - m[0][1]) * s, 0.25 / s]
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * math.sqrt(1.0 + m[i][i] - m[j][j] - m[k][k])
    q = [0.0] * 4
    q[i] = 0.25 * s
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    q[3] = (m[k][j] - m[j][k]) / s
    return q

def unit_cube():
    """24 vertices (4 per face, outward normals) and 36 indices, counter-clockwise from outside."""
    pos, nor, idx = [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]; n[axis] = sign
            a, b = (axis + 1) % 3, (axis + 2) % 3
            corners = []
            for (s, t) in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]; p[axis] = 0.5 * sign; p[a] = 0.5 * s; p[b] = 0.5 * t
                corners.append(p)
            if sign < 0: corners.reverse()
            base = len(pos)
            pos += corners; nor += [n] * 4
            idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nor, idx

def light_json(light):
    """A KHR_lights_punctual light: a spot (cone angles in degrees) or a point light."""
    out = {"type": light["type"], "color": light["color"], "intensity": light["intensity"]}
    if light["type"] == "spot":
        out["spot"] = {"innerConeAngle": math.radians(light["inner"]), "outerConeAngle": math.radians(light["outer"])}
    return out

def write_room(path, materials, boxes, lights, camera, note):
    pos, nor, idx = unit_cube()
    binary = b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", *n) for n in nor) + b"".join(struct.pack("<H", i) for i in idx)
    names = list(materials)
    gltf = {
        "asset": {"version": "2.0", "generator": "vplkit bench/make_fg_rooms.py (" + note + ")"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "buffers": [{"byteLength": len(binary), "uri": "data:application/octet-stream;base64," + base64.b64encode(binary).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 288, "target": 34962},
                        {"buffer": 0, "byteOffset": 288, "byteLength": 288, "target": 34962},
                        {"buffer": 0, "byteOffset": 576, "byteLength": 72, "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 24, "type": "VEC3", "min": [-0.5] * 3, "max": [0.5] * 3},
                      {"bufferView": 1, "componentType": 5126, "count": 24, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5123, "count": 36, "type": "SCALAR"}],
        "materials": [{"name": n, "pbrMetallicRoughness": {"baseColorFactor": list(materials[n]) + [1.0], "metallicFactor": 0.0}} for n in names],
        "meshes": [{"name": n + " cube", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": m}]}
                   for m, n in enumerate(names)],
        "cameras": [{"type": "perspective", "perspective": {"yfov": math.radians(60.0), "znear": 0.05, "zfar": 100.0}}],
        "extensions": {"KHR_lights_punctual": {"lights": [light_json(light) for light in lights]}},
        "nodes": [], "scenes": [{"nodes": []}], "scene": 0,
    }
    nodes = gltf["nodes"]
    for name, material, centre, size in boxes:
        nodes.append({"name": name, "mesh": names.index(material), "translation": list(centre), "scale": list(size)})
    nodes.append({"name": "camera", "camera": 0, "translation": camera[0], "rotation": look_rotation(camera[0], camera[1])})
    for k, light in enumerate(lights):
        node = {"name": "spot" if light["type"] == "spot" else "bulb", "translation": light["at"]}
        if light["type"] == "spot": node["rotation"] = look_rotation(light["at"], light["target"])
        node["extensions"] = {"KHR_lights_punctual": {"light": k}}
        nodes.append(node)
    gltf["scenes"][0]["nodes"] = list(range(len(nodes)))
    pathlib.Path(path).write_text(json.dumps(gltf, indent=1) + "\n")

def shell(w, h, d, t, floor, ceiling, walls):
    """Floor, ceiling and four walls of thickness t around [-w/2, w/2] x [0, h] x [-d/2, d/2]."""
    return [("floor", floor, (0, -t / 2, 0), (w + 2 * t, t, d + 2 * t)),
            ("ceiling", ceiling, (0, h + t / 2, 0), (w + 2 * t, t, d + 2 * t)),
            ("back wall", walls[0], (0, h / 2, -d / 2 - t / 2), (w + 2 * t, h, t)),
            ("front wall", walls[1], (0, h / 2, d / 2 + t / 2), (w + 2 * t, h, t)),
            ("left wall", walls[2], (-w / 2 - t / 2, h / 2, 0), (t, h, d)),
            ("right wall", walls[3], (w / 2 + t / 2, h / 2, 0), (t, h, d))]

here = pathlib.Path(__file__).resolve().parent / "scenes"

studio = {"oak floor": (0.5, 0.36, 0.22), "plaster": (0.82, 0.8, 0.76), "green wall": (0.18, 0.55, 0.25), "linen": (0.85, 0.82, 0.7),
          "walnut": (0.32, 0.2, 0.12), "ceramic": (0.75, 0.3, 0.55)}
w, h, d = 3.4, 2.5, 4.2
boxes = shell(w, h, d, 0.1, "oak floor", "plaster", ["plaster", "plaster", "green wall", "plaster"])
boxes += [("bed", "linen", (0.95, 0.25, -1.0), (1.4, 0.5, 2.0)),
          ("headboard", "walnut", (0.95, 0.55, -2.03), (1.4, 1.1, 0.1)),
          ("desk top", "walnut", (-1.3, 0.75, 0.6), (0.7, 0.04, 1.3)),
          ("desk side", "walnut", (-1.3, 0.365, 1.2), (0.7, 0.73, 0.04)),
          ("shelf", "walnut", (-1.5, 1.0, -1.7), (0.35, 2.0, 0.9)),
          ("vase", "ceramic", (-1.3, 0.9, 0.4), (0.16, 0.26, 0.16))]
spot = {"type": "spot", "color": [1.0, 0.9, 0.75], "intensity": 7.0, "inner": 40.0, "outer": 60.0, "at": [1.4, 2.35, 1.8],
        "target": [-0.6, 0.0, -0.8]}
# A warm bulb under the ceiling, off the middle towards the desk (W/sr: about the spot's light on the floor).
bulb = {"type": "point", "color": [1.0, 0.85, 0.7], "intensity": 2.5, "at": [-0.5, 2.2, -0.3]}
camera = ([0.9, 1.5, 1.9], [-0.4, 0.9, -0.4])
write_room(here / "fg-studio.gltf", studio, boxes, [spot], camera, "a small studio")
write_room(here / "fg-studio-point.gltf", studio, boxes, [bulb], camera, "a small studio lit by a bulb")
write_room(here / "fg-studio-two.gltf", studio, boxes, [spot, bulb], camera, "a small studio lit by a spot and a bulb")

hall = {"blue floor": (0.15, 0.25, 0.55), "white": (0.85, 0.85, 0.85), "yellow wall": (0.8, 0.7, 0.15), "stone": (0.55, 0.52, 0.5),
        "grey wall": (0.6, 0.6, 0.62), "red bench": (0.65, 0.12, 0.1)}
w, h, d = 8.0, 3.6, 6.0
boxes = shell(w, h, d, 0.15, "blue floor", "white", ["yellow wall", "grey wall", "grey wall", "grey wall"])
boxes += [("column 0", "stone", (-1.5, h / 2, -0.5), (0.45, h, 0.45)),
          ("column 1", "stone", (1.5, h / 2, -0.5), (0.45, h, 0.45)),
          ("bench", "red bench", (0.0, 0.22, 1.6), (2.4, 0.44, 0.5))]
spot = {"type": "spot", "color": [0.8, 0.9, 1.0], "intensity": 30.0, "inner": 45.0, "outer": 70.0, "at": [-3.5, 3.3, 2.5],
        "target": [0.5, 0.0, -0.5]}
# A cold lamp high over the far half of the hall, behind the right column as seen from the spot.
bulb = {"type": "point", "color": [0.9, 0.95, 1.0], "intensity": 8.0, "at": [2.5, 3.2, -1.5]}
camera = ([2.5, 1.8, 2.7], [-0.5, 1.0, -1.0])
write_room(here / "fg-hall.gltf", hall, boxes, [spot], camera, "a hall with columns")
write_room(here / "fg-hall-point.gltf", hall, boxes, [bulb], camera, "a hall with columns lit by a lamp")
write_room(here / "fg-hall-two.gltf", hall, boxes, [spot, bulb], camera, "a hall with columns lit by a spot and a lamp")
