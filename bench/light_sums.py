#!/usr/bin/env python3
"""The numbers of docs/scenes.md "Lights" from linear PFMs (no numpy needed):
    light_sums.py sum BOTH.pfm ONE.pfm OTHER.pfm   # |both - (one + other)| summed over the image, over the sum's total
    light_sums.py ratio IMAGE.pfm REFERENCE.pfm    # image-wide mean ratio: the image's total over the reference's
    light_sums.py direct IMAGE.pfm REFERENCE.pfm   # per lit pixel: share within +-7 %, share darker than half, mean ratio
Totals are over the three channels of every pixel; exit 1 with the reason for a bad file."""
import struct, sys

def read_pfm(path):
    with open(path, "rb") as f:
        data = f.read()
    parts = data.split(b"\n", 3)
    if len(parts) < 4 or parts[0] not in (b"PF", b"Pf"):
        sys.exit("%s: not a PFM" % path)
    channels = 3 if parts[0] == b"PF" else 1
    width, height = (int(v) for v in parts[1].split())
    scale = float(parts[2])
    fmt = ("<" if scale < 0 else ">") + "%df" % (width * height * channels)
    values = struct.unpack(fmt, parts[3][: 4 * width * height * channels])
    if any(v != v for v in values):
        sys.exit("%s: NaN" % path)
    return width, height, channels, values

def same(a, b, what):
    if a[:3] != b[:3]:
        sys.exit("%s: sizes differ" % what)

mode = sys.argv[1] if len(sys.argv) > 1 else ""
if mode == "sum" and len(sys.argv) == 5:
    both, one, other = (read_pfm(p) for p in sys.argv[2:5])
    same(both, one, "sum"); same(both, other, "sum")
    error = sum(abs(x - (y + z)) for x, y, z in zip(both[3], one[3], other[3]))
    total = sum(y + z for y, z in zip(one[3], other[3]))
    print("%.6f" % (error / total if total > 0 else float("nan")))
elif mode == "ratio" and len(sys.argv) == 4:
    image, reference = read_pfm(sys.argv[2]), read_pfm(sys.argv[3])
    same(image, reference, "ratio")
    print("%.4f" % (sum(image[3]) / sum(reference[3])))
elif mode == "direct" and len(sys.argv) == 4:
    image, reference = read_pfm(sys.argv[2]), read_pfm(sys.argv[3])
    same(image, reference, "direct")
    c = image[2]
    lit = within = dark = 0
    total_image = total_reference = 0.0
    for i in range(0, len(image[3]), c):
        r, d = sum(reference[3][i:i + c]), sum(image[3][i:i + c])
        if r <= 1e-6: continue
        lit += 1; total_image += d; total_reference += r
        within += abs(d / r - 1.0) <= 0.07
        dark += d < 0.5 * r
    print("lit %d, within 7%%: %.4f, darker than half: %.4f, mean ratio %.4f" % (lit, within / lit, dark / lit, total_image / total_reference))
else:
    sys.exit(__doc__)
