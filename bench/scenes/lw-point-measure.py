#!/usr/bin/env python3
"""Light Wave with a point light (issue 38; docs/scenes.md, "Lights: Light Wave").

  lw-point-measure.py indirect VPLKIT WORKDIR [SIZE] [SAMPLES]
      for each room with a point light (den-point, studio-point, lw-kitchen-point) and three
      camera poses each: the Monte Carlo reference (two seeds, their mean), then every Light Wave
      technique with VPLs (both energies) and the faked one; prints the image-wide mean ratio of
      each technique's -indirect.pfm to the reference's, and the worst and the spread per technique.
  lw-point-measure.py direct VPLKIT WORKDIR [SIZE] [SAMPLES]
      the same poses: lightwave-direct's -direct.pfm against the reference's ray-traced
      -direct.pfm (bench/light_sums.py direct: mean ratio, share within +-7 %, share darker than half).
  lw-point-measure.py cost VPLKIT WORKDIR [SIZE] [RUNS]
      per technique, den: a spot (den-two-spots --lights 0), the point light (den-point), both
      spots (--lights 0,1); RUNS interleaved runs each (3 by default), the least "every pass"
      total kept; prints point / spot and two spots / one spot.
"""
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOMS = {
    "den-point": ["0.4,1.5,2.3,-0.3,0.8,-1.5", "-1.5,1.3,2.2,1.2,0.6,-1.6", "1.6,2.0,-2.2,-1.2,0.5,1.5"],
    "studio-point": ["2.6,1.6,1.8,-1.0,0.6,-1.2", "-2.7,1.4,1.7,1.5,0.8,-1.5", "0.0,2.6,1.8,0.0,0.0,-1.5"],
    "lw-kitchen-point": ["2.2,1.6,1.6,-1.0,0.7,-0.8", "-2.3,1.5,1.5,1.5,0.6,-1.4", "0.0,2.4,-1.7,-0.5,0.4,1.6"],
}
TECHNIQUES = [("lightwave-unshadowed", "flux"), ("lightwave-accurate", "flux"), ("lightwave-integrated", "flux"),
              ("lightwave-unshadowed", "thesis"), ("lightwave-accurate", "thesis"), ("lightwave-integrated", "thesis"),
              ("lightwave-faked", "-")]
SUMS = os.path.join(os.path.dirname(HERE), "light_sums.py")


def run(args):
    return subprocess.run(args, check=True, capture_output=True, text=True).stdout


def reference(vplkit, work, room, pose, camera, size, samples):
    stems = []
    for seed in (1, 2):
        stem = os.path.join(work, "mc-%s-%d-s%d" % (room, pose, seed))
        if not os.path.exists(stem + "-indirect.pfm"):
            run([vplkit, "reference", "--method", "monte-carlo", "--scene", os.path.join(HERE, room + ".gltf"), "--camera", camera,
                 "--size", size, "--samples", samples, "--reference-seed", str(seed), "--out", stem + ".pfm"])
        stems.append(stem)
    return stems


def render(vplkit, out, scene, technique, energy, camera, size, lights=None):
    args = [vplkit, "render", "--scene", scene, "--technique", technique, "--camera", camera, "--size", size, "--out", out]
    if energy != "-":
        args += ["--vpl-energy", energy]
    if lights is not None:
        args += ["--lights", lights]
    text = run(args)
    return float(re.search(r"^\| total \| ([0-9.]+) \|", text, re.M).group(1))


def ratio(image, ref):
    return float(run([sys.executable, SUMS, "ratio", image, ref]).strip())


def main():
    mode, vplkit, work = sys.argv[1], sys.argv[2], sys.argv[3]
    size = sys.argv[4] if len(sys.argv) > 4 else "128"
    os.makedirs(work, exist_ok=True)
    if mode in ("indirect", "direct"):
        samples = sys.argv[5] if len(sys.argv) > 5 else "64"
        per_technique = {}
        for room, poses in ROOMS.items():
            for p, camera in enumerate(poses):
                refs = reference(vplkit, work, room, p, camera, size, samples)
                if mode == "direct":
                    out = os.path.join(work, "%s-%d-lightwave-direct.png" % (room, p))
                    render(vplkit, out, os.path.join(HERE, room + ".gltf"), "lightwave-direct", "-", camera, size)
                    for r in refs:
                        print(room, p, os.path.basename(r), run([sys.executable, SUMS, "direct", out[:-4] + "-direct.pfm", r + "-direct.pfm"]).strip())
                    continue
                for technique, energy in TECHNIQUES:
                    out = os.path.join(work, "%s-%d-%s-%s.png" % (room, p, technique, energy))
                    render(vplkit, out, os.path.join(HERE, room + ".gltf"), technique, energy, camera, size)
                    # Against the mean of the two seeds' references: the ratio of the sums is the mean of the ratios' denominators.
                    r1, r2 = (ratio(out[:-4] + "-indirect.pfm", r + "-indirect.pfm") for r in refs)
                    value = 2.0 / (1.0 / r1 + 1.0 / r2)
                    per_technique.setdefault((technique, energy), []).append(value)
                    print("| %s | %d | %s | %s | %.3f | %.3f |" % (room, p, technique, energy, value, abs(r1 - r2) / value), flush=True)
        for (technique, energy), values in per_technique.items():
            worst = max(values, key=lambda v: abs(v - 1.0))
            print("%s %s: worst %.3f, spread %.3f to %.3f" % (technique, energy, worst, min(values), max(values)))
    elif mode == "cost":
        runs = int(sys.argv[5]) if len(sys.argv) > 5 else 3
        camera = ROOMS["den-point"][0]
        spots, point = os.path.join(HERE, "den-two-spots.gltf"), os.path.join(HERE, "den-point.gltf")
        print("| technique | energy | spot ms | point ms | point / spot | two spots ms | two / one |")
        print("|---|---|---:|---:|---:|---:|---:|")
        for technique, energy in [("lightwave-direct", "-"), ("lightwave-faked", "-"), ("lightwave-unshadowed", "flux"), ("lightwave-accurate", "flux"),
                                  ("lightwave-integrated", "flux")]:
            best = {"spot": 1e30, "point": 1e30, "two": 1e30}
            for _ in range(runs):
                out = os.path.join(work, "cost.png")
                best["spot"] = min(best["spot"], render(vplkit, out, spots, technique, energy, camera, size, "0"))
                best["point"] = min(best["point"], render(vplkit, out, point, technique, energy, camera, size))
                best["two"] = min(best["two"], render(vplkit, out, spots, technique, energy, camera, size, "0,1"))
            print("| %s | %s | %.1f | %.1f | %.2f | %.1f | %.2f |" % (technique, energy, best["spot"], best["point"], best["point"] / best["spot"], best["two"],
                                                                  best["two"] / best["spot"]), flush=True)
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
