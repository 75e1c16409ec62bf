#!/usr/bin/env python3
"""Writes the wavy water surface of scenes/water/ as a binary PLY mesh.

  python3 scripts/gen-water-scene.py        # rewrites scenes/water/water-surface.ply

The surface is a height field y = DEPTH + h(x, z) over the pool's opening
[-1, 1]^2, with h a sum of WAVES sine waves. Wave i has:
  - direction angle i * 137.508 degrees (the golden angle: spread, no pattern),
  - wavelength LAMBDA_MIN * (LAMBDA_MAX / LAMBDA_MIN) ** frac(i * 0.618034),
  - amplitude SLOPE / k (every wave has the same peak slope SLOPE),
  - phase 2 pi frac(i * 0.754878).
The sum is multiplied by a smoothstep window in x and in z that goes from 0
at the walls to 1 at TAPER from them, so the surface meets the walls and the
deck at exactly y = DEPTH (no gap lets light into the pool without crossing
the water) without steep slopes at the edges.

Numbers (scenes/water/README.md says why): rms slope 0.27 away from the
edges, largest slope 0.64, rms height 0.016. For light entering at about 38
degrees below the surface, the floor 0.5 down lies just past the first foci
of the wave crests, where the filaments are sharpest; the slopes stay too
small for the surface to mirror the scene's light into its camera.
Per-vertex normals come from the analytic gradient; GRID x GRID quads, two
triangles each, counter-clockwise seen from +y (normals point up, out of the
water).

Plain Python, no dependencies; the output is deterministic (float32 values
written little-endian).
"""
import math
import os
import struct

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "water")

DEPTH = 0.5  # mean water level above the floor (y = 0)
WAVES = 9
LAMBDA_MIN, LAMBDA_MAX = 0.32, 0.60
SLOPE = 0.13
GRID = 128  # quads per side over [-1, 1]
TAPER = 0.25  # the waves fade out over this distance from the walls


def waves():
    out = []  # (amplitude, kx, kz, phase)
    for i in range(WAVES):
        theta = math.radians(i * 137.508)
        lam = LAMBDA_MIN * (LAMBDA_MAX / LAMBDA_MIN) ** ((i * 0.618034) % 1.0)
        k = 2 * math.pi / lam
        phase = 2 * math.pi * ((i * 0.754878) % 1.0)
        out.append((SLOPE / k, k * math.cos(theta), k * math.sin(theta), phase))
    return out


def taper(t):
    """Edge window: 0 at the wall (t = distance to it), 1 from TAPER on; value and slope."""
    if t >= TAPER:
        return 1.0, 0.0
    u = t / TAPER
    return u * u * (3 - 2 * u), 6 * u * (1 - u) / TAPER


def height(x, z, ws=None):
    """h(x, z) and its gradient (dh/dx, dh/dz); the surface is y = DEPTH + h."""
    ws = waves() if ws is None else ws
    h, dx, dz = 0.0, 0.0, 0.0
    for a, kx, kz, ph in ws:
        s = kx * x + kz * z + ph
        h += a * math.sin(s)
        dx += a * kx * math.cos(s)
        dz += a * kz * math.cos(s)
    wx, dwx = taper(1 - abs(x))
    wz, dwz = taper(1 - abs(z))
    dwx, dwz = -math.copysign(dwx, x), -math.copysign(dwz, z)
    return h * wx * wz, (dx * wx + h * dwx) * wz, (dz * wz + h * dwz) * wx


def surface(n=GRID):
    ws = waves()
    verts, faces = [], []
    for j in range(n + 1):
        for i in range(n + 1):
            x = -1 + 2 * i / n
            z = -1 + 2 * j / n
            h, dx, dz = height(x, z, ws)
            l = math.sqrt(dx * dx + 1 + dz * dz)
            verts.append((x, DEPTH + h, z, -dx / l, 1 / l, -dz / l))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            faces += [(a, d, c), (a, c, b)]  # counter-clockwise seen from +y
    return verts, faces


def write_ply(path, verts, faces):
    head = (
        "ply\nformat binary_little_endian 1.0\n"
        "comment wavy water surface, scripts/gen-water-scene.py\n"
        f"element vertex {len(verts)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\n"
        f"element face {len(faces)}\n"
        "property list uchar int vertex_indices\nend_header\n"
    )
    with open(path, "wb") as f:
        f.write(head.encode("ascii"))
        for v in verts:
            f.write(struct.pack("<6f", *v))
        for t in faces:
            f.write(struct.pack("<B3i", 3, *t))


def main():
    verts, faces = surface()
    os.makedirs(HERE, exist_ok=True)
    write_ply(os.path.join(HERE, "water-surface.ply"), verts, faces)
    ws = waves()
    print(f"{len(verts)} vertices, {len(faces)} triangles; max |h| <= {sum(w[0] for w in ws):.3f}")


if __name__ == "__main__":
    main()
