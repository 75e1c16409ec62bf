"""Distributed rendering on a local Ray cluster against one process: the
figures of docs/distributed.md. Not a test: it prints numbers.

    bash scripts/python-tests.sh -q test_parts.py     # builds the venv and the wheel
    target/python-venv/bin/python scripts/bench/distributed.py [--address HOST:PORT]

Without --address it starts a head node on 127.0.0.1 (`ray start`, all
CPUs of the machine) and stops it at the end (`ray stop --force`). It
measures, on the built-in default scene:

- a Ray round trip of an empty task, and of a tiny part (one pass at 8x8:
  Ray plus lumis loading the scene), serially: the per-task overhead;
- the bytes per pixel of a part (320x240, of 1 and of 64 passes);
- the merge of parts at the caller (HD, 4 parts): seconds and MB/s;
- wall times of one job rendered by `lumis.render` in this process and
  by `lumis.distributed.render` with 1, 2, 4 and 8 tasks, and with 8
  tasks merged in a tree (`fan_in=2`).
"""

from __future__ import annotations

import argparse
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER", "0")  # loopback addresses
os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")

import numpy as np  # noqa: E402

import lumis  # noqa: E402
import lumis.distributed as dist  # noqa: E402

RAY = Path(sys.executable).parent / "ray"


def start_cluster() -> str:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    subprocess.run(
        [str(RAY), "start", "--head", "--node-ip-address", "127.0.0.1", "--port", str(port),
         "--include-dashboard", "false", "--disable-usage-stats"],
        check=True, capture_output=True,
    )
    return f"127.0.0.1:{port}"


def timed(f, *a, **k):
    t = time.perf_counter()
    r = f(*a, **k)
    return r, time.perf_counter() - t


def _empty() -> int:
    return 0


def _tiny_part(job_json: str) -> bytes:
    return lumis.render_part(lumis.Job.from_json(job_json), 0, 1, progress=False)


def overhead(ray, repeat: int) -> tuple:
    empty = ray.remote(_empty)
    tiny = ray.remote(_tiny_part)
    job = lumis.Job(resolution=(8, 8), spp=1, integrator="path").to_json()
    ray.get([empty.remote() for _ in range(4)] + [tiny.remote(job) for _ in range(4)])
    t_empty = min(timed(lambda: ray.get(empty.remote()))[1] for _ in range(repeat))
    t_tiny = min(timed(lambda: ray.get(tiny.remote(job)))[1] for _ in range(repeat))
    t_local = min(timed(_tiny_part, job)[1] for _ in range(repeat))
    return t_empty, t_tiny, t_local


def part_bytes(w: int = 320, h: int = 240) -> list:
    """Bytes per pixel of parts of 1 and of 64 passes (the film's sums are
    packed, so a part's size depends on what it holds; its header is a
    few hundred bytes plus the job)."""
    def size(passes):
        return len(lumis.render_part(None, 0, passes, spp=64, integrator="path",
                                     resolution=(w, h), progress=False))

    return [(p, size(p) / (w * h)) for p in (1, 64)]


def merge_speed(n: int = 4, res=(1920, 1080)) -> tuple:
    job = lumis.Job(resolution=res, spp=n, integrator="path")
    parts = [lumis.render_part(job, i, i + 1, progress=False) for i in range(n)]
    # The merge loads the scene again (cheap for the default scene): time
    # that alone too, so the adding of the sums can be told apart.
    _, load = timed(lumis.load, None, resolution=res, spp=n, integrator="path")
    _, t = timed(lumis.merge, parts)
    return sum(map(len, parts)), t, load


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--address", help="an existing cluster (default: start one here)")
    ap.add_argument("--resolution", default="320x240")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--integrator", default="path")
    ap.add_argument("--tasks", default="1,2,4,8")
    ap.add_argument("--repeat", type=int, default=10)
    a = ap.parse_args()
    import ray

    address = a.address or start_cluster()
    try:
        ray.init(address=address, logging_level="warning", log_to_driver=False)
        cpus = ray.cluster_resources().get("CPU", 0)
        print(f"cluster {address}: {cpus:g} CPUs; this machine {os.cpu_count()} cores")
        e, t, loc = overhead(ray, a.repeat)
        print(f"per-task overhead: empty Ray task {e * 1e3:.1f} ms round trip; "
              f"a 1-pass 8x8 part {t * 1e3:.1f} ms as a task, {loc * 1e3:.1f} ms in process "
              f"(so Ray adds {(t - loc) * 1e3:.1f} ms)")
        sizes = ", ".join(f"{p} passes {b:.1f}" for p, b in part_bytes())
        print(f"part size, bytes/pixel (320x240 path, header included): {sizes}")
        size, t_merge, t_load = merge_speed()
        t_add = max(t_merge - t_load, 1e-9)
        print(f"merge of 4 HD parts ({size / 1e6:.1f} MB): {t_merge:.3f} s, of which loading "
              f"the scene {t_load:.3f} s; {size / 1e6 / t_add:.0f} MB/s of parts, "
              f"{4 * 1920 * 1080 / 1e6 / t_add:.2f} M part pixels/s (unpacking, adding sums)")
        job = lumis.Job(resolution=a.resolution, spp=a.spp, integrator=a.integrator)
        ref, t_one = timed(lumis.render, job, progress=False)
        print(f"job: default scene {a.resolution} {a.integrator} {a.spp} spp; "
              f"lumis.render in this process: {t_one:.2f} s")
        for n in map(int, a.tasks.split(",")):
            # Each task reserves (and renders with) its share of the CPUs:
            # one task, all of them; more tasks than CPUs, one each.
            per = max(1, int(cpus) // min(n, max(1, int(cpus))))
            img, t_n = timed(dist.render, job, address, tasks=n, num_cpus=per,
                             progress=False)
            same = "identical" if np.array_equal(img, ref) else "DIFFERENT"
            print(f"  distributed, {n} tasks: {t_n:.2f} s ({t_one / t_n:.2f}x), {same}")
        n = max(map(int, a.tasks.split(",")))
        img, t_n = timed(dist.render, job, address, tasks=n, num_cpus=1, fan_in=2,
                         progress=False)
        same = "identical" if np.array_equal(img, ref) else "DIFFERENT"
        print(f"  distributed, {n} tasks, merged in a tree on the workers (fan_in=2): "
              f"{t_n:.2f} s ({t_one / t_n:.2f}x), {same}")
    finally:
        if ray.is_initialized():
            ray.shutdown()
        if not a.address:
            subprocess.run([str(RAY), "stop", "--force"], capture_output=True)


if __name__ == "__main__":
    main()
