#!/usr/bin/env python3
"""Writes the rooms of docs/scenes.md "Lights" into bench/scenes/: three furnished rooms vplkit was
never tuned on (den: 4 x 2.5 x 5 m, a green and a blue wall, a bed, a desk, a bookshelf; studio:
6 x 3 x 4 m, a yellow wall, a sofa, a table, a pillar; workshop: 5 x 2.8 x 4.5 m, a red wall, a
partition half across the room, a workbench, shelves, its bulb low and off-centre so that much of
the room is lit through a point light's side faces), each lit two ways: <room>-point.gltf (one
point light under the ceiling) and <room>-two-spots.gltf (two spots from opposite corners, light 0
warm, light 1 cool, so `--lights 0`, `--lights 1` and `--lights 0,1` differ). Boxes are instances
of room-a.gltf's unit cube (its buffer is copied), one material per colour.
    python3 bench/make_light_rooms.py      # deterministic: the same files every run
"""
import json, math, pathlib

here = pathlib.Path(__file__).resolve().parent / "scenes"
base = json.loads((here / "room-a.gltf").read_text())

def aim(direction):
    """The quaternion (x, y, z, w) that turns a spot's local -z onto `direction`."""
    d = [c / math.sqrt(sum(v * v for v in direction)) for c in direction]
    f = (0.0, 0.0, -1.0)
    axis = (f[1] * d[2] - f[2] * d[1], f[2] * d[0] - f[0] * d[2], f[0] * d[1] - f[1] * d[0])
    cos = sum(a * b for a, b in zip(f, d))
    s = math.sqrt(max(0.0, 2.0 * (1.0 + cos)))
    if s < 1e-6: return [0.0, 1.0, 0.0, 0.0]
    return [round(axis[0] / s, 7), round(axis[1] / s, 7), round(axis[2] / s, 7), round(s / 2.0, 7)]

def room(name, size, colours, boxes, camera, point, spots):
    """size: (x, y, z) inner extent, centred on x and z, floor at y = 0. colours: name -> rgb.
    boxes: (name, colour, centre, scale). point: (position, rgb, intensity). spots: [(position,
    target, rgb, intensity)]."""
    sx, sy, sz = size
    t = 0.1
    shell = [("floor", "floor", (0, -t / 2, 0), (sx + 2 * t, t, sz + 2 * t)),
             ("ceiling", "ceiling", (0, sy + t / 2, 0), (sx + 2 * t, t, sz + 2 * t)),
             ("back wall", "back", (0, sy / 2, -sz / 2 - t / 2), (sx + 2 * t, sy, t)),
             ("front wall", "wall", (0, sy / 2, sz / 2 + t / 2), (sx + 2 * t, sy, t)),
             ("left wall", "left", (-sx / 2 - t / 2, sy / 2, 0), (t, sy, sz)),
             ("right wall", "wall", (sx / 2 + t / 2, sy / 2, 0), (t, sy, sz))]
    names = list(colours)
    materials = [{"name": n, "pbrMetallicRoughness": {"baseColorFactor": list(colours[n]) + [1.0], "metallicFactor": 0.0}} for n in names]
    meshes = [{"name": n + " cube", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": i}]} for i, n in enumerate(names)]
    geometry = [{"name": b[0], "mesh": names.index(b[1]), "translation": [round(v, 4) for v in b[2]], "scale": [round(v, 4) for v in b[3]]}
                for b in shell + boxes]
    cam_node = {"name": "camera", "camera": 0, "translation": list(camera[0]), "rotation": aim([b - a for a, b in zip(camera[0], camera[1])])}
    for variant in ("point", "two-spots"):
        nodes = geometry + [cam_node]
        if variant == "point":
            lights = [{"type": "point", "color": list(point[1]), "intensity": point[2]}]
            nodes.append({"name": "bulb", "translation": list(point[0]), "extensions": {"KHR_lights_punctual": {"light": 0}}})
        else:
            lights = []
            for k, (position, target, rgb, intensity) in enumerate(spots):
                lights.append({"type": "spot", "color": list(rgb), "intensity": intensity,
                               "spot": {"innerConeAngle": 0.55, "outerConeAngle": 0.85}})
                nodes.append({"name": "spot %d" % k, "translation": list(position),
                              "rotation": aim([b - a for a, b in zip(position, target)]),
                              "extensions": {"KHR_lights_punctual": {"light": k}}})
        gltf = {"asset": {"version": "2.0", "generator": "vplkit bench/make_light_rooms.py"},
                "extensionsUsed": ["KHR_lights_punctual"],
                "buffers": base["buffers"], "bufferViews": base["bufferViews"], "accessors": base["accessors"],
                "materials": materials, "meshes": meshes, "nodes": nodes,
                "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0471975511965976, "znear": 0.05, "zfar": 100.0}}],
                "extensions": {"KHR_lights_punctual": {"lights": lights}},
                "scenes": [{"name": name + "-" + variant, "nodes": list(range(len(nodes)))}], "scene": 0}
        (here / (name + "-" + variant + ".gltf")).write_text(json.dumps(gltf, indent=1) + "\n")

room("den", (4.0, 2.5, 5.0),
     {"floor": (0.5, 0.4, 0.3), "ceiling": (0.85, 0.85, 0.85), "wall": (0.78, 0.76, 0.7), "back": (0.2, 0.55, 0.25),
      "left": (0.15, 0.25, 0.65), "bed": (0.7, 0.3, 0.3), "wood": (0.45, 0.3, 0.18), "white": (0.9, 0.9, 0.88)},
     [("bed", "bed", (1.0, 0.25, -1.3), (1.6, 0.5, 2.0)), ("headboard", "wood", (1.0, 0.6, -2.4), (1.6, 1.2, 0.1)),
      ("desk", "wood", (-1.4, 0.72, 0.6), (1.0, 0.05, 0.6)), ("desk block", "wood", (-1.75, 0.36, 0.6), (0.3, 0.72, 0.55)),
      ("bookshelf", "white", (-1.8, 1.0, -1.6), (0.35, 2.0, 1.2))],
     ((0.4, 1.5, 2.3), (-0.3, 0.8, -1.5)),
     ((0.0, 2.2, 0.0), (1.0, 0.95, 0.85), 5.0),
     [((-1.8, 2.35, 2.3), (0.5, 0.0, -1.0), (1.0, 0.85, 0.65), 8.0), ((1.8, 2.35, 2.3), (-0.8, 0.0, -1.4), (0.6, 0.75, 1.0), 6.0)])

room("studio", (6.0, 3.0, 4.0),
     {"floor": (0.6, 0.6, 0.58), "ceiling": (0.85, 0.85, 0.85), "wall": (0.8, 0.8, 0.78), "back": (0.8, 0.7, 0.2),
      "left": (0.75, 0.75, 0.75), "sofa": (0.25, 0.35, 0.6), "wood": (0.55, 0.38, 0.2), "pillar": (0.6, 0.25, 0.2)},
     [("sofa seat", "sofa", (-1.5, 0.22, -1.5), (2.2, 0.44, 0.8)), ("sofa back", "sofa", (-1.5, 0.55, -1.85), (2.2, 1.1, 0.2)),
      ("table", "wood", (-1.4, 0.4, -0.3), (1.2, 0.06, 0.7)), ("table block", "wood", (-1.4, 0.2, -0.3), (0.4, 0.4, 0.4)),
      ("pillar", "pillar", (1.2, 1.5, 0.2), (0.4, 3.0, 0.4)), ("cabinet", "wood", (2.6, 0.6, -1.6), (0.6, 1.2, 0.6))],
     ((2.6, 1.6, 1.8), (-1.0, 0.6, -1.2)),
     ((-0.5, 2.6, -0.2), (1.0, 0.9, 0.8), 7.0),
     [((-2.8, 2.85, 1.8), (-1.2, 0.0, -1.2), (1.0, 0.85, 0.65), 9.0), ((2.8, 2.85, -1.8), (0.5, 0.0, 0.8), (0.6, 0.75, 1.0), 7.0)])

# Light Wave's own room (docs/scenes.md "Lights: Light Wave"), never tuned on: a 5 x 2.7 x 3.6 m
# kitchen with a red wall, a counter along the back, an island, a tall fridge and a table; a bulb
# over the island (lw-kitchen-point.gltf) or two spots (lw-kitchen-two-spots.gltf).
room("lw-kitchen", (5.0, 2.7, 3.6),
     {"floor": (0.55, 0.5, 0.45), "ceiling": (0.85, 0.85, 0.85), "wall": (0.8, 0.78, 0.74), "back": (0.75, 0.74, 0.7),
      "left": (0.7, 0.18, 0.15), "counter": (0.3, 0.3, 0.32), "wood": (0.5, 0.35, 0.2), "fridge": (0.88, 0.88, 0.9)},
     [("counter", "counter", (0.3, 0.45, -1.5), (3.0, 0.9, 0.6)), ("island", "wood", (0.4, 0.45, 0.1), (1.4, 0.9, 0.8)),
      ("fridge", "fridge", (2.1, 0.95, -1.45), (0.7, 1.9, 0.7)), ("table", "wood", (-1.6, 0.74, 0.9), (1.0, 0.05, 0.9)),
      ("table block", "wood", (-1.6, 0.37, 0.9), (0.3, 0.74, 0.3))],
     ((2.2, 1.6, 1.6), (-1.0, 0.7, -0.8)),
     ((0.2, 2.3, 0.3), (1.0, 0.92, 0.8), 6.0),
     [((-2.3, 2.6, 1.6), (0.3, 0.9, -1.4), (1.0, 0.85, 0.65), 8.0), ((2.3, 2.6, 1.6), (-1.6, 0.0, 0.4), (0.6, 0.75, 1.0), 6.0)])

room("workshop", (5.0, 2.8, 4.5),
     {"floor": (0.45, 0.45, 0.5), "ceiling": (0.8, 0.8, 0.8), "wall": (0.75, 0.72, 0.65), "back": (0.7, 0.2, 0.15),
      "left": (0.3, 0.5, 0.55), "bench": (0.6, 0.45, 0.25), "metal": (0.35, 0.38, 0.4), "partition": (0.85, 0.8, 0.55)},
     [("partition", "partition", (0.6, 1.1, -0.4), (0.1, 2.2, 2.4)), ("workbench", "bench", (-1.5, 0.85, -1.6), (1.6, 0.08, 0.8)),
      ("bench legs", "metal", (-1.5, 0.42, -1.6), (1.4, 0.84, 0.6)), ("shelves", "metal", (2.2, 0.9, -1.5), (0.5, 1.8, 1.2)),
      ("crate", "bench", (-0.4, 0.3, 1.0), (0.6, 0.6, 0.6))],
     ((-2.0, 1.7, 2.0), (1.0, 0.7, -1.3)),
     ((-0.6, 1.9, 0.5), (1.0, 0.92, 0.8), 4.0),
     [((-2.3, 2.65, 2.0), (0.0, 0.0, -1.0), (1.0, 0.85, 0.65), 8.0), ((2.3, 2.65, 2.0), (-0.5, 0.0, -1.5), (0.6, 0.75, 1.0), 6.0)])
