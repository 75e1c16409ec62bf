#!/usr/bin/env python3
"""Prints a test image's 4x4 tile means over a reference's (luminance-free
channel average), and the reference's tile means: where two renders of the
same scene disagree, beyond their noise.

  python tiles.py REFERENCE.exr TEST.exr
"""

import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")


def channel_mean(path):
    img = np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32))
    return img.mean(axis=2)


def tiles(img, n=4):
    h, w = img.shape
    return img[: h // n * n, : w // n * n].reshape(n, h // n, n, w // n).mean(axis=(1, 3))


ref, test = (tiles(channel_mean(p)) for p in sys.argv[1:3])
with np.errstate(invalid="ignore", divide="ignore"):
    print("tile means, test / reference:")
    print(np.array2string(test / ref, precision=3))
print("reference tile means:")
print(np.array2string(ref, precision=3))
