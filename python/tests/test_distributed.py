"""lumis.distributed on a real local Ray cluster: a head node started with
`ray start` on 127.0.0.1 whose two CPUs run tasks in separate worker
processes; renders equal to `lumis.render` bit for bit, also when a worker
process is killed during a render; a study's runs as tasks give the report
`lumis study` gives. The cluster is always torn down (`ray stop --force`).
Skipped, with a notice, where `ray` cannot be imported."""

import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import lumis
import lumis.distributed as dist
from conftest import run_cli

# Every Ray address is the loopback one: Ray otherwise replaces 127.0.0.1
# with the machine's network address. (It then allows one node a machine,
# which has as many worker processes as CPUs.) Read when ray is imported.
os.environ["RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER"] = "0"
os.environ["RAY_USAGE_STATS_ENABLED"] = "0"

RAY_BIN = Path(sys.executable).parent / "ray"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def cluster():
    """The address of a fresh local cluster: a head with 2 CPUs (two
    worker processes run tasks side by side), the caller connected."""
    ray = pytest.importorskip("ray", reason="ray is not installed: distributed tests skipped")
    if not RAY_BIN.is_file():
        pytest.skip(f"no `ray` command beside {sys.executable}")
    address = f"127.0.0.1:{free_port()}"
    start = [str(RAY_BIN), "start", "--head", "--node-ip-address", "127.0.0.1",
             "--port", address.split(":")[1], "--num-cpus", "2",
             "--include-dashboard", "false", "--disable-usage-stats",
             "--object-store-memory", str(200 * 1024 * 1024)]
    try:
        p = subprocess.run(start, capture_output=True, text=True, timeout=120)
        assert p.returncode == 0, f"ray start failed:\n{p.stdout}\n{p.stderr}"
        ray.init(address=address, logging_level="warning", log_to_driver=False)
        yield address
    finally:
        if ray.is_initialized():
            ray.shutdown()
        subprocess.run([str(RAY_BIN), "stop", "--force"], capture_output=True, timeout=120)


def test_split_tiles_the_passes_on_iteration_boundaries():
    assert dist.split(8, 3) == [(0, 2), (2, 5), (5, 8)]
    assert dist.split(8, 1) == [(0, 8)]
    assert dist.split(3, 8) == [(0, 1), (1, 2), (2, 3)]
    # Two passes an iteration: every cut even, the last range may be short.
    assert dist.split(9, 3, 2) == [(0, 2), (2, 6), (6, 9)]
    assert dist.split(8, 8, 4) == [(0, 4), (4, 8)]
    for n, t, a in [(64, 7, 1), (100, 9, 3), (5, 2, 8)]:
        r = dist.split(n, t, a)
        assert r[0][0] == 0 and r[-1][1] == n
        assert all(b == c for (_, b), (c, _) in zip(r, r[1:]))
        assert all(s < e and s % a == 0 for s, e in r)
    with pytest.raises(ValueError):
        dist.split(0, 2)


def test_without_ray_the_error_says_how_to_install_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "ray", None)  # `import ray` fails
    with pytest.raises(ImportError, match="pip install ray"):
        dist.render(lumis.Job(spp=1, resolution=(8, 8)), progress=False)


@pytest.mark.parametrize(
    "params",
    [dict(integrator="path"), dict(integrator="photon", iteration_spp=2)],
    ids=["path", "photon-progressive"],
)
def test_a_distributed_render_equals_one_render(cluster, params):
    job = lumis.Job(resolution=(64, 48), spp=8, seed=3, **params)
    whole = lumis.render(job, progress=False)
    seen = []
    img = dist.render(job, cluster, tasks=3, progress=lambda *a: seen.append(a))
    assert np.array_equal(img, whole)
    assert img.metadata["lumis:parts"] == "3"
    # Progress over the tasks: passes done, up to all of them.
    assert seen and seen[-1][1] <= 8 and all(0 <= f <= 1 for f, _, _ in seen)
    assert not np.array_equal(dist.render(job, cluster, tasks=2, seed=4, progress=False),
                              whole)


def test_parts_merged_in_a_tree_on_the_workers_give_the_same_image(cluster):
    job = lumis.Job(resolution=(64, 48), spp=10, seed=2, integrator="path")
    whole = lumis.render(job, progress=False)
    # 5 parts, merged 2 at a time into 3, then 2: what reaches the caller.
    img = dist.render(job, cluster, tasks=5, fan_in=2, progress=False)
    assert np.array_equal(img, whole)
    assert img.metadata["lumis:parts"] == "2"
    with pytest.raises(ValueError, match="fan_in"):
        dist.render(job, cluster, fan_in=1, progress=False)


def workers_running(name: str):
    """Pids of the processes whose title says they run task `name` (Ray
    names a busy worker process `ray::<function>`)."""
    pids = []
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                cmd = (d / "cmdline").read_bytes()
            except OSError:
                continue
            if cmd.startswith(f"ray::{name}".encode()):
                pids.append(int(d.name))
    return pids


def test_a_killed_worker_reruns_its_task_and_the_image_is_the_same(cluster):
    job = lumis.Job(resolution=(200, 150), spp=48, integrator="path", seed=1)
    whole = lumis.render(job, progress=False)
    killed = []

    def kill_one():
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and not killed:
            pids = workers_running("_render_range")
            if pids:
                os.kill(pids[0], signal.SIGKILL)
                killed.append(pids[0])
            time.sleep(0.05)

    killer = threading.Thread(target=kill_one)
    killer.start()
    try:
        img = dist.render(job, cluster, tasks=2, progress=False, max_retries=2)
    finally:
        killer.join()
    assert killed, "no worker was seen running a task"
    assert not Path(f"/proc/{killed[0]}").exists() or \
        b"ray::_render_range" not in Path(f"/proc/{killed[0]}/cmdline").read_bytes()
    assert np.array_equal(img, whole)


def test_a_distributed_study_writes_the_report_lumis_study_writes(cluster, cli, scenes,
                                                                   tmp_path):
    scene = scenes / "test" / "caustic_sphere.pbrt"
    flags = dict(resolution=(24, 24), integrator="path")
    lumis.write(tmp_path / "ref.exr", lumis.render(scene, spp=64, progress=False, **flags))
    config = tmp_path / "small.toml"
    config.write_text(f"""title = "small"
seeds = [1, 2]
spp = [2, 4]
threads = 1

[[scene]]
name = "sphere"
file = "{scene}"
reference = "ref.exr"
flags = ["--resolution", "24x24"]

[[setting]]
name = "path"
flags = ["--integrator", "path", "--maxdepth", "4"]
""")
    out = tmp_path / "dist-report"
    result = dist.study(config, cluster, out=out, progress=False)
    assert result["finished"] == result["planned"] == 4
    assert sorted(t["status"] for t in result["tasks"]) == ["rendered"] * 4
    assert (out / "index.html").is_file()
    run_cli(cli, "study", config, "--out", tmp_path / "cli-report", "-q")
    for name in ["sphere__path__2spp__s1", "sphere__path__4spp__s2"]:
        a = lumis.read(out / "sphere" / f"{name}.exr")
        b = lumis.read(tmp_path / "cli-report" / "sphere" / f"{name}.exr")
        assert np.array_equal(a, b), name
    # The same records, but for the time each run took.
    for rec in (out / "runs").glob("*.json"):
        a, b = json.loads(rec.read_text()), json.loads(
            (tmp_path / "cli-report" / "runs" / rec.name).read_text())
        for r in (a, b):
            del r["seconds"], r["photon_seconds"]
        assert a == b, rec.name
    assert len(list((out / "runs").glob("*.json"))) == 4
    # A second distributed study finds every run finished.
    again = dist.study(config, cluster, out=out, progress=False)
    assert [t["status"] for t in again["tasks"]] == ["finished"] * 4
