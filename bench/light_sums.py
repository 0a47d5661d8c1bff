#!/usr/bin/env python3
"""The numbers of docs/scenes.md "Lights" from linear PFMs (no numpy needed):
    light_sums.py sum BOTH.pfm ONE.pfm OTHER.pfm   # |both - (one + other)| summed over the image, over the sum's total
    light_sums.py ratio IMAGE.pfm REFERENCE.pfm    # image-wide mean ratio: the image's total over the reference's
    light_sums.py direct IMAGE.pfm REFERENCE.pfm   # per lit pixel: share within +-7 %, share darker than half, mean ratio
    light_sums.py split IMAGE.pfm REFERENCE.pfm REFERENCE-direct.pfm [MAP.png]
        # the ratio split over the pixels the reference's direct light reaches and those in the light's
        # shadow, each part's excess over the reference's total; MAP.png: the per-pixel ratio, green
        # where equal, red up to 2x too bright, blue up to 2x too dark, dark blue: no reference light
Totals are over the three channels of every pixel; exit 1 with the reason for a bad file."""
import math, struct, sys, zlib

def read_pfm(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        sys.exit("%s: cannot read: %s" % (path, e.strerror))
    parts = data.split(b"\n", 3)
    if len(parts) < 4 or parts[0] not in (b"PF", b"Pf"):
        sys.exit("%s: not a PFM" % path)
    channels = 3 if parts[0] == b"PF" else 1
    try:
        width, height = (int(v) for v in parts[1].split())
        scale = float(parts[2])
    except ValueError:
        sys.exit("%s: not a PFM (bad size or scale line)" % path)
    if width <= 0 or height <= 0 or len(parts[3]) < 4 * width * height * channels:
        sys.exit("%s: %d x %d pixels announced, the file is shorter" % (path, width, height))
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
elif mode == "split" and len(sys.argv) in (5, 6):
    image, reference, direct = (read_pfm(p) for p in sys.argv[2:5])
    same(image, reference, "split"); same(image, direct, "split")
    w, h, c = image[:3]
    def pixel(values, i): return sum(values[3][i * c:(i + 1) * c])
    px = [(pixel(image, i), pixel(reference, i), pixel(direct, i)) for i in range(w * h)]
    total = sum(r for _, r, _ in px)
    if not total > 0: sys.exit("%s: no indirect light" % sys.argv[3])
    print("image-wide ratio %.4f" % (sum(t for t, _, _ in px) / total))
    for name, part in (("lit", [p for p in px if p[2] > 1e-6]), ("in shadow", [p for p in px if p[2] <= 1e-6 and p[1] > 0])):
        t, r = sum(p[0] for p in part), sum(p[1] for p in part)
        print("%s: %d pixels, %.3f of the reference's light, ratio %s, excess %+.4f of the reference's total"
              % (name, len(part), r / total, "%.4f" % (t / r) if r > 0 else "-", (t - r) / total))
    if len(sys.argv) == 6:
        rows = []
        for y in range(h - 1, -1, -1):  # PFM rows run bottom to top, PNG rows top to bottom
            row = bytearray(b"\0")
            for x in range(w):
                t, r, _ = px[y * w + x]
                if not r > 0: row += bytes((0, 0, 64)); continue
                l = max(-1.0, min(1.0, math.log2(max(t / r, 1e-9))))  # -1: half, +1: twice the reference
                row += bytes((int(255 * max(l, 0.0)), int(153 * (1.0 - abs(l))), int(255 * max(-l, 0.0))))
            rows.append(bytes(row))
        def chunk(kind, data): return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
        png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
               chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b""))
        try:
            with open(sys.argv[5], "wb") as f: f.write(png)
        except OSError as e:
            sys.exit("%s: cannot write: %s" % (sys.argv[5], e.strerror))
        print("wrote %s" % sys.argv[5])
else:
    sys.exit(__doc__)
