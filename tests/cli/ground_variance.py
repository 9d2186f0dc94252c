"""Checks that the ground of a render is not one color: the standard deviation of the luminance
(0..255) over a band of rows must reach a minimum. Converts the PNG through oiiotool (OIIO).
Usage: ground_variance.py IMAGE FIRST_ROW_FRACTION LAST_ROW_FRACTION MIN_STDDEV"""
import os
import subprocess
import sys
import tempfile

import numpy as np

image, first, last, minimum = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
with tempfile.TemporaryDirectory() as scratch:
    ppm = os.path.join(scratch, "image.ppm")
    subprocess.run(["oiiotool", image, "--ch", "R,G,B", "-d", "uint8", "-o", ppm], check=True)
    data = open(ppm, "rb").read()
# Binary PPM: "P6", width, height, maxval, one whitespace byte, then the pixels.
magic, width, height, maxval = data.split(maxsplit=4)[:4]
assert magic == b"P6" and maxval == b"255", "unexpected PPM header"
width, height = int(width), int(height)
pixels = np.frombuffer(data[-width * height * 3:], dtype=np.uint8).reshape(height, width, 3).astype(np.float64)
band = pixels[int(first * height):int(last * height)]
luminance = 0.2126 * band[..., 0] + 0.7152 * band[..., 1] + 0.0722 * band[..., 2]
stddev = float(luminance.std())
print("ground band rows %d..%d of %d: luminance stddev %.2f (minimum %.2f)" %
      (int(first * height), int(last * height), height, stddev, minimum))
sys.exit(0 if stddev >= minimum else 1)
