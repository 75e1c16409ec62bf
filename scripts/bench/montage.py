#!/usr/bin/env python3
"""Writes EXR images side by side as one sRGB PNG (for the docs' pictures),
each scaled up by an integer factor (nearest pixel).

  python montage.py OUT.png --scale 3 [--exposure STOPS] A.exr B.exr ...
"""

import argparse

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")


def read(path):
    return np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32))


def srgb(x):
    x = np.clip(x, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
ap.add_argument("out")
ap.add_argument("images", nargs="+")
ap.add_argument("--scale", type=int, default=1)
ap.add_argument("--exposure", type=float, default=0.0)
a = ap.parse_args()
tiles = [np.kron(read(p) * 2.0**a.exposure, np.ones((a.scale, a.scale, 1))) for p in a.images]
gap = np.ones((tiles[0].shape[0], 4, 3))
row = np.concatenate(sum(([t, gap] for t in tiles), [])[:-1], axis=1)
png = (srgb(row) * 255 + 0.5).astype(np.uint8)
mi.Bitmap(png, mi.Bitmap.PixelFormat.RGB).write(a.out)
