#!/usr/bin/env python3
"""Renders a Mitsuba 3 scene for scripts/bench-vs-mitsuba.sh and prints its
timings as one JSON line (label, render seconds, notes).

  python run_mitsuba.py SCENE.xml OUT.exr --spp N [--threads 2] [--seed 1]
                        [--variant llvm_ad_rgb] [--warmup-spp 4]

The first render (warm-up, --warmup-spp samples, another seed) includes the
JIT compilation of the llvm variants; the timed render is the second one,
with the kernels cached. Dr.Jit's kernel history gives the compile time
(code generation + LLVM backend) of every launch. If the variant cannot be
set (e.g. no usable libLLVM), scalar_rgb is used; "variant" says which ran.
Times are wall-clock seconds; "render" is mi.render up to the finished
image; the notes give the scene's load (parsing and the acceleration
structure), the warm-up and the cores the timed render used on average
(CPU time of all threads over wall time).
"""

import argparse
import json
import os
import sys
import time

import drjit as dr
import mitsuba as mi


def render(scene, spp, seed):
    t, c = time.perf_counter(), time.process_time()
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img)
    dr.sync_thread()
    return img, time.perf_counter() - t, time.process_time() - c


def compiled(history):
    """Compile time of the kernels launched (code generation + LLVM), and
    how many were compiled, loaded from Dr.Jit's disk cache (~/.drjit) or
    found in memory."""
    ks = [k for k in history if k.get("cache_hit") is not None]
    secs = sum(k["codegen_time"] + k["backend_time"] for k in ks) / 1000.0
    disk = sum(1 for k in ks if k["cache_disk"])
    fresh = sum(1 for k in ks if not k["cache_hit"])
    return f"{secs:.3f} s (kernels: {fresh} compiled, {disk} from disk, {len(ks) - fresh - disk} in memory)"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("out")
    ap.add_argument("--spp", type=int, required=True)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--warmup-spp", type=int, default=4)
    a = ap.parse_args()

    dr.set_thread_count(a.threads)
    variant = a.variant
    try:
        mi.set_variant(variant)
    except Exception as e:  # no LLVM backend: fall back to the scalar variant
        print(f"run_mitsuba.py: variant {variant} unavailable ({e}); using scalar_rgb", file=sys.stderr)
        variant = "scalar_rgb"
        mi.set_variant(variant)
    jit = variant.startswith(("llvm", "cuda"))
    if jit:
        dr.set_flag(dr.JitFlag.KernelHistory, True)

    t = time.perf_counter()
    scene = mi.load_file(a.scene)
    load = time.perf_counter() - t
    notes = f"scene load {load:.2f} s"
    if jit:
        dr.kernel_history()  # drop the loading's kernels
        _, warm, _ = render(scene, a.warmup_spp, a.seed + 1000)
        jit_s = compiled(dr.kernel_history())
        notes += f"; warm-up render ({a.warmup_spp} spp) {warm:.2f} s, JIT compile {jit_s}"
    img, secs, cpu = render(scene, a.spp, a.seed)
    notes += f"; timed render on {cpu / secs:.2f} cores"
    if jit:
        notes += f", its JIT compile {compiled(dr.kernel_history())}"
    # Writing an EXR hangs with a pool of one thread (Mitsuba 3.9.1): the
    # timed part is over, so the pool gets its default size back first.
    dr.set_thread_count(os.cpu_count())
    mi.Bitmap(img).write(a.out)
    print(json.dumps({"label": "mitsuba " + variant, "render": secs, "notes": notes}))


if __name__ == "__main__":
    main()
