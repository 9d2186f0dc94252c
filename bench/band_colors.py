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

Reads PNGs through oiiotool (tests/cli/render_image.py, the CLI tests' one reader); the colour
maths are tests/cli/colour_difference.py's. Run with the
system Python (numpy)."""
import argparse
import itertools
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "cli"))
from colour_difference import ciede2000, linear_to_lab, srgb8_to_linear  # noqa: E402
from render_image import read_rgb  # noqa: E402

BAND_NAMES = ("sky", "far", "middle", "near")
ENGINES = ("povray", "blender", "embree")


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
    """The template with absolute paths (its DEM, models and masks) and [exports] for POV-Ray and Blender."""
    text = open(template, encoding="utf-8").read()
    base = os.path.dirname(os.path.abspath(template))
    root = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

    def absolute_path(match):
        for candidate in (os.path.join(base, match.group(2)), os.path.join(root, match.group(2))):
            if os.path.exists(candidate):
                return match.group(1) + os.path.abspath(candidate) + '"'
        return match.group(0)

    text = re.sub(r'^((?:dem|mesh|model|mask|raster|polygons)\s*=\s*")([^"]+)"', absolute_path, text, flags=re.M)
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
