#!/usr/bin/env python3
"""Writes bench/scenes/window-room.gltf: a closed room of zero-thickness quads (6 x 3 x 5, normals
inwards) with one window in its +x wall, the sun-lit ground outside it, and a sun. The scene of
docs/rsm-study.md "Beyond one RSM": one RSM sees the ground outside and the room's floor in the same
map, so every micro-linear-buffer variant leaks the ground's light through the walls.
    python3 bench/make_window_room.py      # deterministic: the same file every run
"""
import base64, json, math, struct, pathlib

quads = []  # (corners a b c d counter-clockwise seen from the normal's side, normal, albedo)
def quad(a, b, c, d, n, albedo): quads.append(((a, b, c, d), n, albedo))

white, warm, grey, ochre, blue = (0.75, 0.75, 0.75), (0.78, 0.74, 0.66), (0.5, 0.5, 0.5), (0.75, 0.55, 0.2), (0.12, 0.22, 0.7)
lx, hx, ly, hy, lz, hz = -3.0, 3.0, 0.0, 3.0, -2.5, 2.5
# Floor, ceiling, -x, -z, +z walls (inwards).
quad((lx, ly, hz), (hx, ly, hz), (hx, ly, lz), (lx, ly, lz), (0, 1, 0), warm)
quad((lx, hy, lz), (hx, hy, lz), (hx, hy, hz), (lx, hy, hz), (0, -1, 0), white)
quad((lx, ly, hz), (lx, ly, lz), (lx, hy, lz), (lx, hy, hz), (1, 0, 0), blue)
quad((lx, ly, lz), (hx, ly, lz), (hx, hy, lz), (lx, hy, lz), (0, 0, 1), white)
quad((hx, ly, hz), (lx, ly, hz), (lx, hy, hz), (hx, hy, hz), (0, 0, -1), ochre)
# The +x wall around a window z in [-1, 1], y in [0.9, 2.1] (normal -x: inwards).
wl, wh, wb, wt = -1.0, 1.0, 0.9, 2.1
def xwall(z0, z1, y0, y1): quad((hx, y0, z0), (hx, y0, z1), (hx, y1, z1), (hx, y1, z0), (-1, 0, 0), white)
xwall(lz, wl, ly, hy); xwall(wh, hz, ly, hy); xwall(wl, wh, ly, wb); xwall(wl, wh, wt, hy)
# The ground outside, around the room's footprint (up).
g = 15.0
def ground(x0, x1, z0, z1): quad((x0, 0, z1), (x1, 0, z1), (x1, 0, z0), (x0, 0, z0), (0, 1, 0), grey)
ground(hx, g, -g, g); ground(-g, lx, -g, g); ground(lx, hx, hz, g); ground(lx, hx, -g, lz)

# One primitive per albedo.
albedos = sorted(set(q[2] for q in quads))
binary, views, accessors, primitives = b"", [], [], []
for m, albedo in enumerate(albedos):
    pos, nor, idx = [], [], []
    for corners, n, a in quads:
        if a != albedo: continue
        base = len(pos)
        pos += corners; nor += [n] * 4
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    first = len(accessors)
    for data, kind in ((pos, "VEC3"), (nor, "VEC3")):
        blob = b"".join(struct.pack("<3f", *v) for v in data)
        views.append({"buffer": 0, "byteLength": len(blob), "byteOffset": len(binary), "target": 34962}); binary += blob
        acc = {"bufferView": len(views) - 1, "componentType": 5126, "count": len(data), "type": kind}
        if data is pos: acc["min"] = [min(v[i] for v in data) for i in range(3)]; acc["max"] = [max(v[i] for v in data) for i in range(3)]
        accessors.append(acc)
    blob = b"".join(struct.pack("<I", i) for i in idx)
    views.append({"buffer": 0, "byteLength": len(blob), "byteOffset": len(binary), "target": 34963}); binary += blob
    accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
    primitives.append({"attributes": {"POSITION": first, "NORMAL": first + 1}, "indices": first + 2, "material": m, "mode": 4})

def look_rotation(eye, target):
    # The quaternion turning -z to (target - eye), y staying up.
    f = [t - e for t, e in zip(target, eye)]; l = math.sqrt(sum(c * c for c in f)); f = [c / l for c in f]
    r = [-f[2], 0.0, f[0]]; l = math.sqrt(sum(c * c for c in r)); r = [c / l for c in r]
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    m = [[r[0], u[0], -f[0]], [r[1], u[1], -f[1]], [r[2], u[2], -f[2]]]
    w = math.sqrt(max(0.0, 1 + m[0][0] + m[1][1] + m[2][2])) / 2
    return [(m[2][1] - m[1][2]) / (4 * w), (m[0][2] - m[2][0]) / (4 * w), (m[1][0] - m[0][1]) / (4 * w), w]

camera_eye, camera_target = (-2.6, 1.6, 2.0), (1.5, 0.4, -0.6)
sun_from = (9.0, 7.0, 1.5)
doc = {
    "asset": {"generator": "bench/make_window_room.py", "version": "2.0"},
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 3.0}]}},
    "buffers": [{"byteLength": len(binary), "uri": "data:application/octet-stream;base64," + base64.b64encode(binary).decode()}],
    "bufferViews": views, "accessors": accessors,
    "materials": [{"name": "albedo %d" % i, "pbrMetallicRoughness": {"baseColorFactor": list(a) + [1.0], "metallicFactor": 0.0}} for i, a in enumerate(albedos)],
    "meshes": [{"name": "window-room", "primitives": primitives}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 1.1, "znear": 0.05, "zfar": 60.0}}],
    "nodes": [{"mesh": 0, "name": "window-room"},
              {"camera": 0, "name": "camera", "translation": list(camera_eye), "rotation": look_rotation(camera_eye, camera_target)},
              {"name": "light", "extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": list(sun_from), "rotation": look_rotation(sun_from, (0, 0, 0))}],
    "scene": 0, "scenes": [{"name": "window-room", "nodes": [0, 1, 2]}],
}
path = pathlib.Path(__file__).resolve().parent / "scenes" / "window-room.gltf"
path.write_text(json.dumps(doc, indent=2) + "\n")
print("wrote", path)
