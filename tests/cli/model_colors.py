"""Counts a render's pixels of the test models' colours (tests/data/models: the tulip's red head,
the leaf card's red and orange halves and its transparent blue, which must never show) and checks
them against limits. Prints the counts and the mean colour of the plant pixels (red and orange).
Usage: model_colors.py IMAGE [NAME:min:N | NAME:max:N | agrees:OTHER_IMAGE:MAX_DE]...  (NAME: red,
orange, blue; agrees: the plant pixels' mean colours of both images within CIEDE2000 MAX_DE, and
each image holds at least 100 plant pixels, so that two pictures without plants never agree)"""
import sys

from colour_difference import ciede2000, srgb8_to_lab
from render_image import read_rgb

MIN_PLANT_PIXELS = 100  # below this, a mean colour says little (and none at all is black)


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
        other_counts, other_mean = plant_mean(other)
        difference = ciede2000(srgb8_to_lab(mean), srgb8_to_lab(other_mean))
        print("  plant mean of %s: sRGB %.1f %.1f %.1f, CIEDE2000 %.2f (at most %s)" %
              (other, other_mean[0], other_mean[1], other_mean[2], difference, most))
        ok = ok and difference <= float(most)
        for image, c in ((sys.argv[1], counts), (other, other_counts)):
            if c["red"] + c["orange"] < MIN_PLANT_PIXELS:
                print("  %s holds %d plant pixels: too few to compare (at least %d)" %
                      (image, c["red"] + c["orange"], MIN_PLANT_PIXELS))
                ok = False
        continue
    name, bound, value = limit.split(":")
    held = counts[name] >= int(value) if bound == "min" else counts[name] <= int(value)
    if not held:
        print("  %s is %d: expected at %s %s" % (name, counts[name], "least" if bound == "min" else "most", value))
        ok = False
sys.exit(0 if ok else 1)
