"""Checks that the ground of a render is not one color: the standard deviation of the luminance
(0..255) over a band of rows must reach a minimum. Converts the PNG through oiiotool (OIIO).
Usage: ground_variance.py IMAGE FIRST_ROW_FRACTION LAST_ROW_FRACTION MIN_STDDEV"""
import sys

from render_image import read_rgb

image, first, last, minimum = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
pixels = read_rgb(image).astype(float)
height = pixels.shape[0]
band = pixels[int(first * height):int(last * height)]
luminance = 0.2126 * band[..., 0] + 0.7152 * band[..., 1] + 0.0722 * band[..., 2]
stddev = float(luminance.std())
print("ground band rows %d..%d of %d: luminance stddev %.2f (minimum %.2f)" %
      (int(first * height), int(last * height), height, stddev, minimum))
sys.exit(0 if stddev >= minimum else 1)
