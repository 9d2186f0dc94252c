"""Checks that a render of the meadow shows one: mostly green (grass, leaves) with yellow
flower heads among it. Prints both shares of the pixels below the horizon row fraction.
Usage: meadow_colors.py IMAGE FIRST_ROW_FRACTION MIN_GREEN_SHARE MIN_YELLOW_SHARE"""
import sys

from render_image import read_rgb

image, first, min_green, min_yellow = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
pixels = read_rgb(image).astype(float)
band = pixels[int(first * pixels.shape[0]):]
r, g, b = band[..., 0], band[..., 1], band[..., 2]
green = float(((g > r) & (g > b)).mean())
# Dandelion and sunflower yellow: red and green well above blue, red near green.
yellow = float(((r > 120) & (g > 90) & (b < 0.5 * g) & (r > 0.8 * g)).mean())
print("meadow rows %d..%d: green %.3f (minimum %.3f), yellow %.4f (minimum %.4f)" %
      (int(first * pixels.shape[0]), pixels.shape[0], green, min_green, yellow, min_yellow))
sys.exit(0 if green >= min_green and yellow >= min_yellow else 1)
