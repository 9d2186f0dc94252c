#!/usr/bin/python3
"""Do the engines give one look? Each picture is cut into horizontal bands (top to bottom: sky,
far field and mountain, middle, near ground and plants); each band's mean colour (the mean of the
pixels' linear RGB, so a noisy render's mean is its noise-free one) goes to CIELAB (D65), and every
pair of engines is compared band by band with CIEDE2000 (issue 39: at most 6).

  band_colors.py compare [--limit 6] [--bands 4] ENGINE=IMAGE ENGINE=IMAGE ...
      prints each band's Lab per engine and the CIEDE2000 of every pair; exit 1 above the limit.
  band_colors.py table --wangscape BIN --out DIR [--width 320 --height 180] TEMPLATE.toml ...
      builds each scene (its [exports] set to POV-Ray and Blender), renders it from its own
      camera with povray, blender and embree, and prints the Markdown table of every pair per
      band; exit 1 above the limit. The pictures stay in DIR as SCENE_ENGINE.png.

Reads PNGs through oiiotool (tests/cli/render_image.py, the CLI tests' one reader). Run with the
system Python (numpy)."""
import argparse
import itertools
import math
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "cli"))
from render_image import read_rgb  # noqa: E402

BAND_NAMES = ("sky", "far", "middle", "near")
ENGINES = ("povray", "blender", "embree")


def srgb8_to_linear(values):
    c = np.asarray(values, dtype=np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_lab(rgb):
    """Linear sRGB (D65) to CIELAB."""
    m = np.array([[0.4124564, 0.3575761, 0.1804375], [0.2126729, 0.7151522, 0.0721750],
                  [0.0193339, 0.1191920, 0.9503041]])
    xyz = m @ np.asarray(rgb, dtype=np.float64) / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > (6 / 29) ** 3, np.cbrt(xyz), xyz / (3 * (6 / 29) ** 2) + 4 / 29)
    return (116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2]))


def ciede2000(lab1, lab2):
    """CIEDE2000 (Sharma, Wu and Dalal 2005), kL = kC = kH = 1."""
    (l1, a1, b1), (l2, a2, b2) = lab1, lab2
    c_bar = (math.hypot(a1, b1) + math.hypot(a2, b2)) / 2
    g = 0.5 * (1 - math.sqrt(c_bar ** 7 / (c_bar ** 7 + 25 ** 7)))
    a1p, a2p = (1 + g) * a1, (1 + g) * a2
    c1p, c2p = math.hypot(a1p, b1), math.hypot(a2p, b2)
    h1p = math.degrees(math.atan2(b1, a1p)) % 360 if c1p else 0.0
    h2p = math.degrees(math.atan2(b2, a2p)) % 360 if c2p else 0.0
    dl, dc = l2 - l1, c2p - c1p
    dh = 0.0
    if c1p * c2p:
        dh = h2p - h1p
        if dh > 180:
            dh -= 360
        elif dh < -180:
            dh += 360
    d_big_h = 2 * math.sqrt(c1p * c2p) * math.sin(math.radians(dh / 2))
    l_bar, cp_bar = (l1 + l2) / 2, (c1p + c2p) / 2
    if c1p * c2p == 0:
        hp_bar = h1p + h2p
    elif abs(h1p - h2p) <= 180:
        hp_bar = (h1p + h2p) / 2
    else:
        hp_bar = (h1p + h2p + 360) / 2 if h1p + h2p < 360 else (h1p + h2p - 360) / 2
    t = (1 - 0.17 * math.cos(math.radians(hp_bar - 30)) + 0.24 * math.cos(math.radians(2 * hp_bar)) +
         0.32 * math.cos(math.radians(3 * hp_bar + 6)) - 0.20 * math.cos(math.radians(4 * hp_bar - 63)))
    d_theta = 30 * math.exp(-(((hp_bar - 275) / 25) ** 2))
    r_c = 2 * math.sqrt(cp_bar ** 7 / (cp_bar ** 7 + 25 ** 7))
    s_l = 1 + 0.015 * (l_bar - 50) ** 2 / math.sqrt(20 + (l_bar - 50) ** 2)
    s_c, s_h = 1 + 0.045 * cp_bar, 1 + 0.015 * cp_bar * t
    r_t = -math.sin(math.radians(2 * d_theta)) * r_c
    return math.sqrt((dl / s_l) ** 2 + (dc / s_c) ** 2 + (d_big_h / s_h) ** 2 + r_t * (dc / s_c) * (d_big_h / s_h))


def band_labs(image, bands=4):
    """Each horizontal band's mean colour in Lab, top to bottom."""
    linear = srgb8_to_linear(read_rgb(image))
    edges = [round(k * linear.shape[0] / bands) for k in range(bands + 1)]
    return [linear_to_lab(linear[edges[k]:edges[k + 1]].reshape(-1, 3).mean(axis=0)) for k in range(bands)]


def pair_differences(labs):
    """{(engine, engine): [CIEDE2000 per band]} for every pair of the {engine: band_labs} given."""
    return {(a, b): [ciede2000(x, y) for x, y in zip(labs[a], labs[b])]
            for a, b in itertools.combinations(labs, 2)}


def band_name(k, bands):
    return BAND_NAMES[k] if bands == len(BAND_NAMES) else "band %d" % k


def compare(args):
    images = dict(item.split("=", 1) for item in args.images)
    labs = {engine: band_labs(path, args.bands) for engine, path in images.items()}
    for engine, bands in labs.items():
        print("%-8s " % engine + "  ".join("%s L %5.1f a %5.1f b %5.1f" % ((band_name(k, args.bands),) + tuple(lab))
                                         for k, lab in enumerate(bands)))
    worst = 0.0
    for (a, b), differences in pair_differences(labs).items():
        worst = max([worst] + differences)
        print("%-16s " % ("%s-%s" % (a, b)) + "  ".join("%s %5.1f" % (band_name(k, args.bands), d)
                                                      for k, d in enumerate(differences)))
    print("worst CIEDE2000 %.1f (limit %.1f)" % (worst, args.limit))
    return 0 if worst <= args.limit else 1


def scene_for_table(template, folder):
    """The template with an absolute DEM path and [exports] for POV-Ray and Blender."""
    text = open(template, encoding="utf-8").read()
    base = os.path.dirname(os.path.abspath(template))
    root = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

    def absolute_dem(match):
        for candidate in (os.path.join(base, match.group(2)), os.path.join(root, match.group(2))):
            if os.path.exists(candidate):
                return match.group(1) + os.path.abspath(candidate) + '"'
        return match.group(0)

    text = re.sub(r'^(dem\s*=\s*")([^"]+)"', absolute_dem, text, flags=re.M)
    lines, section = [], ""
    for line in text.splitlines():
        header = re.match(r"^\[(\w+)\]", line)
        if header:
            section = header.group(1)
        if section == "exports" and re.match(r"^(povray|blender)\s*=", line):
            continue
        lines.append(line)
        if header and section == "exports":
            lines += ["povray = true", "blender = true"]
    if not any(re.match(r"^\[exports\]", line) for line in lines):
        lines += ["[exports]", "povray = true", "blender = true"]
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "scene.toml")
    open(path, "w", encoding="utf-8").write("\n".join(lines) + "\n")
    return path


def table(args):
    rows = []
    for template in args.templates:
        name = os.path.splitext(os.path.basename(template))[0]
        work = os.path.join(args.out, name)
        scene = scene_for_table(template, os.path.join(args.out, "scenes", name))
        subprocess.run([args.wangscape, "--quiet", "build", scene, "--out", work], check=True)
        labs = {}
        for engine in ENGINES:
            image = os.path.join(args.out, "%s_%s.png" % (name, engine))
            subprocess.run([args.wangscape, "--quiet", "render", work, "--engine", engine, "--width", str(args.width),
                            "--height", str(args.height), "--out", image], check=True)
            labs[engine] = band_labs(image, args.bands)
        for (a, b), differences in pair_differences(labs).items():
            rows.append((name, "%s-%s" % (a, b), differences))
    print("| scene | pair | " + " | ".join(band_name(k, args.bands) for k in range(args.bands)) + " |")
    print("|---|---|" + "---:|" * args.bands)
    for name, pair, differences in rows:
        print("| %s | %s | " % (name, pair) +
              " | ".join(("**%.1f**" if d > args.limit else "%.1f") % d for d in differences) + " |")
    worst = max(d for _, _, differences in rows for d in differences)
    print("\nworst CIEDE2000 %.1f (limit %.1f)" % (worst, args.limit))
    return 0 if worst <= args.limit else 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bands", type=int, default=4)
    parser.add_argument("--limit", type=float, default=6.0)
    sub = parser.add_subparsers(dest="command", required=True)
    c = sub.add_parser("compare")
    c.add_argument("images", nargs="+", metavar="ENGINE=IMAGE")
    t = sub.add_parser("table")
    t.add_argument("--wangscape", required=True)
    t.add_argument("--out", required=True)
    t.add_argument("--width", type=int, default=320)
    t.add_argument("--height", type=int, default=180)
    t.add_argument("templates", nargs="+")
    args = parser.parse_args()
    if args.command == "compare" and any("=" not in item for item in args.images):
        parser.error("compare takes ENGINE=IMAGE pairs")
    return compare(args) if args.command == "compare" else table(args)


if __name__ == "__main__":
    sys.exit(main())
