#!/usr/bin/env python3
"""Light Wave with several lights (issue 38): for every lightwave technique and both energies, on
each lw-two-spots-*.gltf scene and camera pose, renders --lights 0, --lights 1 and --lights 0,1 and
reports (1) how far the two-light indirect PFM is from the sum of the one-light PFMs (image-wide
relative difference of the sums, and the worst pixel relative to the image's mean) and (2) the
frame cost, two lights over one (the mean of the two one-light frames' "every pass" totals).

usage: bench/scenes/lw-lights-measure.py VPLKIT WORKDIR [SIZE]   (docs/scenes.md, "Lights: Light Wave")
"""
import os
import re
import struct
import subprocess
import sys

TECHNIQUES = ["lightwave-faked", "lightwave-unshadowed", "lightwave-accurate", "lightwave-integrated", "lightwave-direct"]
SCENES = {
    "lw-two-spots-study": ["0.8,1.5,2.3,-0.3,0.7,-1.2", "-1.6,1.2,2.0,1.0,0.5,-1.5", "1.7,2.2,-2.0,-1.0,0.3,1.5"],
    "lw-two-spots-hall": ["-0.6,1.7,3.3,0.4,0.6,-2.0", "1.4,2.5,0.0,-1.0,0.5,-3.0", "0.0,1.0,-3.2,0.0,1.0,3.0"],
}


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        data = f.read(4 * width * height * channels)
    fmt = ("<" if scale < 0 else ">") + "f" * (width * height * channels)
    return struct.unpack(fmt, data)


def render(vplkit, out, scene, technique, energy, lights, camera, size):
    args = [vplkit, "render", "--scene", scene, "--technique", technique, "--lights", lights, "--camera", camera, "--size", size, "--out", out]
    if technique != "lightwave-direct" and technique != "lightwave-faked":
        args += ["--vpl-energy", energy]
    text = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    # The first table is "every pass"; its total row.
    total = float(re.search(r"^\| total \| ([0-9.]+) \|", text, re.M).group(1))
    return total


def main():
    vplkit, work = sys.argv[1], sys.argv[2]
    size = sys.argv[3] if len(sys.argv) > 3 else "320x180"
    here = os.path.dirname(os.path.abspath(__file__))
    os.makedirs(work, exist_ok=True)
    print("| scene | pose | technique | energy | sum error (image) | worst pixel / mean | cost 2 lights / 1 |")
    print("|---|---|---|---|---:|---:|---:|")
    worst_sum, worst_cost, costs = 0.0, 0.0, []
    for scene, poses in SCENES.items():
        path = os.path.join(here, scene + ".gltf")
        for p, camera in enumerate(poses):
            for technique in TECHNIQUES:
                energies = ["flux", "thesis"] if technique not in ("lightwave-direct", "lightwave-faked") else ["-"]
                for energy in energies:
                    stem = os.path.join(work, "%s-%d-%s-%s" % (scene, p, technique, energy))
                    t0 = render(vplkit, stem + "-l0.png", path, technique, energy, "0", camera, size)
                    t1 = render(vplkit, stem + "-l1.png", path, technique, energy, "1", camera, size)
                    t01 = render(vplkit, stem + "-l01.png", path, technique, energy, "0,1", camera, size)
                    # lightwave-direct has no indirect light: its final image instead (PNG is not
                    # linear), so the direct technique is checked through the pipeline test only.
                    if technique == "lightwave-direct":
                        image_error, pixel_error = float("nan"), float("nan")
                    else:
                        a, b, both = (read_pfm(stem + s + "-indirect.pfm") for s in ("-l0", "-l1", "-l01"))
                        summed = sum(a) + sum(b)
                        image_error = abs(sum(both) - summed) / summed
                        mean = summed / len(a)
                        pixel_error = max(abs(x - y - z) for x, y, z in zip(both, a, b)) / mean
                        worst_sum = max(worst_sum, image_error)
                    cost = t01 / (0.5 * (t0 + t1))
                    costs.append(cost)
                    worst_cost = max(worst_cost, cost)
                    print("| %s | %d | %s | %s | %.2e | %.2e | %.2f |" % (scene, p, technique, energy, image_error, pixel_error, cost), flush=True)
    costs.sort()
    print("worst image-wide sum error %.2e; cost two lights / one: worst %.2f, median %.2f, spread %.2f-%.2f" %
          (worst_sum, worst_cost, costs[len(costs) // 2], costs[0], costs[-1]))


if __name__ == "__main__":
    main()
