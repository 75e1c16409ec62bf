#!/usr/bin/env python3
"""Prints the table of scripts/bench-vs-mitsuba.sh for one scene and checks
that the images agree in mean.

  python report.py RESULTS.jsonl REFERENCE.exr REFERENCE_SPP

RESULTS.jsonl has one JSON object per renderer: label, image, spp, render
(seconds of rendering alone, or null where it cannot be measured), wall
and cpu (seconds of the whole process, wall-clock and CPU time of all its
threads) and optional notes. For each: spp/s from the render time and from
the wall time, the ratio of the first to lumis', the cores used on average
over the whole process (cpu / wall), the mean of each channel and of the
luminance against the reference's, the MSE against the reference, and the
equal-time MSE: the MSE scaled to lumis' render time by MSE x time =
constant, which holds for unbiased renderers whose error is noise.

The mean check: every RGB channel within 1% of the reference's for the RGB
renderers; pbrt-v4 renders spectrally (saturated walls and gold differ by
a few percent after a few bounces), so for it only the luminance must be
within 1% and the channels are printed for information. A deviation over
1% is a MISMATCH only if it is also over 3 sigma of the means' noise
(sigma from the per-pixel squared error of the run, or of lumis' run if
larger, over the pixel count, and the reference's share); otherwise the
run has too few samples to tell (NOISY). A coarse check (the image in 8x8
blocks, the RMS of the blocks' relative luminance difference, 32-45% for
a mirrored image) shows a mirrored or shifted camera, which the means
cannot. Exit status 1 on a MISMATCH or a layout over 20%.
"""

import json
import sys

import mitsuba as mi
import numpy as np

LUM = np.array([0.2126, 0.7152, 0.0722])  # linear sRGB (Rec. 709) luminance
TOL = 0.01
BLOCK_TOL = 0.20


def load(path):
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


def blocks(img, n=8):
    h, w = img.shape[0] // n * n, img.shape[1] // n * n
    lum = img[:h, :w] @ LUM
    return lum.reshape(n, h // n, n, w // n).mean(axis=(1, 3))


COLUMNS = [  # (heading, width)
    ("renderer", 20), ("render s", 8), ("wall s", 7), ("spp/s", 8), ("(wall)", 8),
    ("x lumis", 7), ("cores", 5), ("mean dR dG dB %", 20), ("dLum %", 7), ("+-%", 5),
    ("blocks%", 7), ("MSE", 9), ("MSE eq.t", 9),
]  # fmt: skip


def row(cells):
    """One line of the table; missing measurements are "-"."""
    out = [f"{cells[0]:<{COLUMNS[0][1]}}"]
    out += [f"{'-' if c is None else c:>{w}}" for c, (_, w) in zip(cells[1:], COLUMNS[1:], strict=False)]
    return " ".join(out).rstrip()


def check(dev, sigma, tol):
    """'' if |dev| <= tol, NOISY if within 3 sigma, else MISMATCH."""
    if all(abs(dev) <= tol):
        return ""
    return "NOISY" if all(abs(dev) <= np.maximum(tol, 3 * sigma)) else "MISMATCH"


def main():
    mi.set_variant("scalar_rgb")
    results_path, ref_path, ref_spp = sys.argv[1], sys.argv[2], int(sys.argv[3])
    with open(results_path) as f:
        runs = [json.loads(line) for line in f if line.strip()]
    ref = load(ref_path)
    npix = ref.shape[0] * ref.shape[1]
    ref_mean, ref_blocks = ref.reshape(-1, 3).mean(0), blocks(ref)
    ref_lum = ref_mean @ LUM
    floor = np.maximum(ref_blocks, 0.05 * ref_lum)  # black blocks: relative to 5% of the mean
    for r in runs:
        r["img"] = load(r["image"])
        if r["img"].shape != ref.shape:
            sys.exit(f"report.py: {r['image']} is not the size of the reference")
        err = r["img"] - ref
        r["sq"] = np.append((err**2).reshape(-1, 3).mean(0), ((err @ LUM) ** 2).mean())
    lumis = next((r for r in runs if r["label"].startswith("lumis")), runs[0])
    t_lumis = lumis["render"]
    print(row([h for h, _ in COLUMNS]))
    print(row(["reference"] + [""] * 6 + ["(%.4g %.4g %.4g)" % tuple(ref_mean)]))
    bad = []
    for r in runs:
        mean = r["img"].reshape(-1, 3).mean(0)
        dev = np.append(mean / ref_mean - 1, mean @ LUM / ref_lum - 1) * 100
        # noise of the mean difference, in % of the reference's mean
        sq = np.maximum(r["sq"], lumis["sq"]) * (1 + r["spp"] / ref_spp)
        sigma = np.sqrt(sq / npix) / np.append(ref_mean, ref_lum) * 100
        spectral = r["label"].startswith("pbrt")
        flag = check(dev[3:] if spectral else dev, sigma[3:] if spectral else sigma, TOL * 100)
        dblk = np.sqrt(np.mean(((blocks(r["img"]) - ref_blocks) / floor) ** 2)) * 100
        if dblk > BLOCK_TOL * 100:
            flag = (flag + " LAYOUT").strip()
        if flag not in ("", "NOISY"):
            bad.append(r["label"])
        mse, t, spp, wall = float(r["sq"][:3].mean()), r["render"], r["spp"], r["wall"]
        both = t and t_lumis
        cells = [r["label"], f"{t:.2f}" if t else None, f"{wall:.2f}", f"{spp / t:.2f}" if t else None]
        cells += [f"{spp / wall:.2f}", f"{t_lumis / t:.2f}" if both else None, f"{r['cpu'] / wall:.2f}"]
        cells += ["%+.2f %+.2f %+.2f" % tuple(dev[:3]), f"{dev[3]:+.2f}", f"{sigma[3]:.2f}", f"{dblk:.1f}"]
        cells += [f"{mse:.3g}", f"{mse * t / t_lumis:.3g}" if both else None]
        print(row(cells) + (f"  <- {flag}" if flag else ""))
        if r.get("notes"):
            print(f"{'':<20} {r['notes']}")
    if bad:
        print(f"check FAILED for: {', '.join(bad)}")
        sys.exit(1)
    print(
        f"check passed: means within {TOL:.0%} of the reference's (RGB channels; luminance for "
        "pbrt-v4) or, where marked NOISY, within 3 sigma of its noise"
    )


if __name__ == "__main__":
    main()
