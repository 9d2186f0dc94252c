"""Counts a render's pixels of the test models' colours (tests/data/models: the tulip's red head,
the leaf card's red and orange halves and its transparent blue, which must never show) and checks
them against limits. Prints the counts and the mean colour of the plant pixels (red and orange).
Usage: model_colors.py IMAGE [NAME:min:N | NAME:max:N | agrees:OTHER_IMAGE:MAX_DE]...  (NAME: red,
orange, blue; agrees: the plant pixels' mean colours of both images within CIEDE2000 MAX_DE)"""
import math
import sys

from render_image import read_rgb


def lab(srgb8):
    """CIELAB (D65) of an 8-bit sRGB colour."""
    linear = [((c / 255 + 0.055) / 1.055) ** 2.4 if c / 255 > 0.04045 else c / 255 / 12.92 for c in srgb8]
    x = (0.4124 * linear[0] + 0.3576 * linear[1] + 0.1805 * linear[2]) / 0.95047
    y = 0.2126 * linear[0] + 0.7152 * linear[1] + 0.0722 * linear[2]
    z = (0.0193 * linear[0] + 0.1192 * linear[1] + 0.9505 * linear[2]) / 1.08883
    f = [t ** (1 / 3) if t > 216 / 24389 else (24389 / 27 * t + 16) / 116 for t in (x, y, z)]
    return 116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])


def ciede2000(lab1, lab2):
    """Sharma, Wu and Dalal's formulation of CIEDE2000 (kL = kC = kH = 1)."""
    (l1, a1, b1), (l2, a2, b2) = lab1, lab2
    c_mean = (math.hypot(a1, b1) + math.hypot(a2, b2)) / 2
    g = 0.5 * (1 - math.sqrt(c_mean ** 7 / (c_mean ** 7 + 25 ** 7)))
    a1p, a2p = (1 + g) * a1, (1 + g) * a2
    c1p, c2p = math.hypot(a1p, b1), math.hypot(a2p, b2)
    h1p = math.degrees(math.atan2(b1, a1p)) % 360 if c1p else 0
    h2p = math.degrees(math.atan2(b2, a2p)) % 360 if c2p else 0
    dl, dc = l2 - l1, c2p - c1p
    dh = 0 if c1p * c2p == 0 else (h2p - h1p if abs(h2p - h1p) <= 180 else h2p - h1p - 360 * math.copysign(1, h2p - h1p))
    dhh = 2 * math.sqrt(c1p * c2p) * math.sin(math.radians(dh / 2))
    lp, cp = (l1 + l2) / 2, (c1p + c2p) / 2
    if c1p * c2p == 0:
        hp = h1p + h2p
    elif abs(h1p - h2p) <= 180:
        hp = (h1p + h2p) / 2
    else:
        hp = (h1p + h2p + 360) / 2 if h1p + h2p < 360 else (h1p + h2p - 360) / 2
    t = (1 - 0.17 * math.cos(math.radians(hp - 30)) + 0.24 * math.cos(math.radians(2 * hp)) +
         0.32 * math.cos(math.radians(3 * hp + 6)) - 0.20 * math.cos(math.radians(4 * hp - 63)))
    sl = 1 + 0.015 * (lp - 50) ** 2 / math.sqrt(20 + (lp - 50) ** 2)
    sc, sh = 1 + 0.045 * cp, 1 + 0.015 * cp * t
    rt = (-2 * math.sqrt(cp ** 7 / (cp ** 7 + 25 ** 7)) *
          math.sin(math.radians(60 * math.exp(-(((hp - 275) / 25) ** 2)))))
    return math.sqrt((dl / sl) ** 2 + (dc / sc) ** 2 + (dhh / sh) ** 2 + rt * (dc / sc) * (dhh / sh))


def plant_mean(image):
    """The counts of each class and the mean colour of the plant pixels (red and orange)."""
    pixels = read_rgb(image).astype(float)
    r, g, b = pixels[..., 0], pixels[..., 1], pixels[..., 2]
    classes = {
        # The tulip's head (Kd 0.8 0.05 0.05) and the card's top (sRGB 200 30 30), lit or shaded.
        "red": (r > 50) & (g < 0.35 * r) & (b < 0.35 * r),
        # The card's lower left (sRGB 230 120 20): green about half of red, little blue.
        "orange": (r > 60) & (g > 0.35 * r) & (g < 0.75 * r) & (b < 0.3 * r),
        # The card's transparent half (sRGB 20 40 230): far bluer than any sky.
        "blue": (b > 60) & (r < 0.35 * b) & (g < 0.5 * b),
    }
    plant = classes["red"] | classes["orange"]
    mean = pixels[plant].mean(axis=0) if plant.any() else [0, 0, 0]
    return {name: int(mask.sum()) for name, mask in classes.items()}, mean


counts, mean = plant_mean(sys.argv[1])
print("%s: %s; plant mean sRGB %.1f %.1f %.1f" % (sys.argv[1], " ".join("%s %d" % kv for kv in counts.items()),
                                                  mean[0], mean[1], mean[2]))
ok = True
for limit in sys.argv[2:]:
    if limit.startswith("agrees:"):
        _, other, most = limit.split(":")
        other_mean = plant_mean(other)[1]
        difference = ciede2000(lab(mean), lab(other_mean))
        print("  plant mean of %s: sRGB %.1f %.1f %.1f, CIEDE2000 %.2f (at most %s)" %
              (other, other_mean[0], other_mean[1], other_mean[2], difference, most))
        ok = ok and difference <= float(most)
        continue
    name, bound, value = limit.split(":")
    held = counts[name] >= int(value) if bound == "min" else counts[name] <= int(value)
    if not held:
        print("  %s is %d: expected at %s %s" % (name, counts[name], "least" if bound == "min" else "most", value))
        ok = False
sys.exit(0 if ok else 1)
