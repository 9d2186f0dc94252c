"""Reads a render (PNG) as an 8-bit RGB numpy array (height x width x 3), through oiiotool (OIIO):
the one reader of the CLI tests' image checks."""
import os
import subprocess
import tempfile

import numpy as np


def read_rgb(image):
    with tempfile.TemporaryDirectory() as scratch:
        ppm = os.path.join(scratch, "image.ppm")
        subprocess.run(["oiiotool", image, "--ch", "R,G,B", "-d", "uint8", "-o", ppm], check=True)
        data = open(ppm, "rb").read()
    # Binary PPM: "P6", width, height, maxval, one whitespace byte, then the pixels.
    magic, width, height, maxval = data.split(maxsplit=4)[:4]
    assert magic == b"P6" and maxval == b"255", "unexpected PPM header"
    width, height = int(width), int(height)
    return np.frombuffer(data[-width * height * 3:], dtype=np.uint8).reshape(height, width, 3)
