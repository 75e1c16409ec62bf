"""lumis across machines, on a Ray cluster.

    >>> import lumis, lumis.distributed
    >>> job = lumis.Job("/shared/scenes/room.pbrt", spp=1024, integrator="photon")
    >>> img = lumis.distributed.render(job, address="head:6379", tasks=64)
    >>> lumis.distributed.study("/shared/studies/caustics.toml", address="auto")

:func:`render` cuts a job's passes into ranges, renders each range as a
Ray task (:func:`lumis.render_part`) and merges the parts at the caller as
they arrive (:class:`lumis.Merger`): the image is bit for bit the one
:func:`lumis.render` gives on one machine. A task whose worker dies is run again (Ray's
``max_retries``); a part depends only on its range, so a rerun gives the
same bytes. :func:`study` runs a study's runs as tasks into its shared
folder, then the study once more at the caller, which finds them finished
and writes the report ``lumis study`` writes.

Only the parts travel through Ray's object store. Scenes and the files
they read reach the workers by their path: the job's scene path is made
absolute and must name the same, unchanged files on every machine (a
shared file system, or the same copy at the same path); a scene changed
between parts is refused by the merge (the scene hash). ``ray`` is
imported when first needed; install it with ``pip install ray``.
"""

from __future__ import annotations

import math
import os
import time as _time
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import lumis
from lumis import Image, Job, PathLike, Scene

from ._progress import _Line, _Progress, _reporter

__all__ = ["render", "split", "study"]

# How often the caller wakes up to report progress.
_POLL = 0.25


def _ray() -> Any:
    try:
        import ray
    except ImportError as e:
        raise ImportError(
            "lumis.distributed needs Ray: `pip install ray` (on the caller and on every worker)"
        ) from e
    return ray


def _connect(address: Optional[str]) -> Any:
    """Ray, connected: to ``address`` (None: a running connection, else
    Ray's default: ``RAY_ADDRESS`` or a new local cluster)."""
    ray = _ray()
    if not ray.is_initialized():
        ray.init(address=address, logging_level="warning", log_to_driver=False)
    return ray


def split(passes: int, tasks: int, align: int = 1) -> List[Tuple[int, int]]:
    """``passes`` cut into at most ``tasks`` ranges ``(start, end)`` of
    nearly equal length that tile ``0..passes``, every boundary a multiple
    of ``align`` (a progressive photon render's passes per iteration, so
    no range starts inside an iteration; fewer ranges when there are
    fewer iterations than tasks)."""
    if passes < 1 or tasks < 1 or align < 1:
        raise ValueError(f"split({passes}, {tasks}, {align}): all must be >= 1")
    units = -(-passes // align)
    n = min(tasks, units)
    cuts = [min(passes, (units * k // n) * align) for k in range(n + 1)]
    return [(a, b) for a, b in zip(cuts, cuts[1:])]


def _render_range(
    job_json: str, start: int, end: int, index: int, reporter: Any
) -> bytes:
    """A Ray task: passes ``start..end`` of the job, as the part's bytes;
    progress (passes done) goes to the ``reporter`` actor."""
    job = Job.from_json(job_json)
    last = [0.0]

    def progress(fraction: float, spp: int, seconds: float) -> None:
        now = _time.monotonic()
        if reporter is not None and (now - last[0] >= 0.5 or fraction >= 1.0):
            last[0] = now
            # `spp` counts from the render's start: this range's passes.
            reporter.report.remote(index, max(0, spp - start))

    return lumis.render_part(job, start, end, progress=progress)


def render(
    job: Union[Job, Scene, PathLike, None],
    address: Optional[str] = None,
    tasks: Optional[int] = None,
    progress: Union[bool, Callable[[float, int, float], Any]] = True,
    *,
    output: Any = None,
    max_retries: int = 3,
    num_cpus: float = 1,
    fan_in: Optional[int] = None,
    **params: Any,
) -> Image:
    """Renders ``job`` (a :class:`lumis.Job`, a :class:`lumis.Scene`'s job,
    a scene path, or None for the built-in scene; ``params`` as for
    :func:`lumis.render`, e.g. ``spp=``, ``seed=``, ``integrator=``) as
    Ray tasks, and returns the merged :class:`lumis.Image`, bit for bit
    :func:`lumis.render`'s.

    - ``address``: the cluster (``"auto"``, ``"host:port"``; None: the
      current connection, else Ray's default);
    - ``tasks``: ranges of passes to render, one task each (default: the
      cluster's CPUs); at most the pass count (the sample count), and for
      progressive ``photon`` at most the iterations, since ranges start on
      iteration boundaries;
    - ``progress``: True prints one line on stderr (tasks finished, passes
      done), False nothing, a callable is called as ``progress(fraction,
      passes_done, seconds)``;
    - ``output``: files to write the image to (at the caller);
    - ``max_retries``: reruns of a task whose worker dies;
    - ``num_cpus``: CPUs Ray reserves per task, and the threads each task
      renders with unless the job sets ``threads`` (so a machine's tasks
      use its cores once, not once each). Each task loads the scene: for a
      large scene, give ``num_cpus`` the machines' core count, so that a
      machine runs one task with all its cores and one copy of the scene;
    - ``fan_in``: merge in a tree on the workers: Ray tasks merge the parts
      of ``fan_in`` consecutive ranges into one part, then those, until at
      most ``fan_in`` parts reach the caller (None: every part does). For
      many large parts (docs/distributed.md): each merge task loads the
      scene, and the caller receives and adds ``fan_in`` parts, not all.

    The scene path is made absolute: every worker must see the same files
    there. A time budget is refused (parts need a sample count)."""
    ray = _connect(address)
    base = job.job if isinstance(job, Scene) else job
    if isinstance(base, Job):
        j = base.with_params(**params)
    else:
        j = Job(None if base is None else os.fspath(base), **params)
    if j.scene is not None:
        j.scene = j.scene_path()
    if j.time is not None:
        raise ValueError("a distributed render needs a sample count, not a time budget")
    if j.threads == 0:
        j.threads = max(1, math.ceil(num_cpus))
    # The pass count and iteration length, as the job's scene defines them
    # (and the scene's warnings, issued here once).
    session = lumis._load_session(j, stacklevel=3)
    total = session.pass_count
    n = tasks or max(1, int(ray.cluster_resources().get("CPU", 1)))
    ranges = split(total, n, session.iteration_passes)
    del session
    if fan_in is not None and fan_in < 2:
        raise ValueError(f"fan_in must be at least 2, found {fan_in}")
    merger = lumis.Merger()
    _run_tasks(ray, j, ranges, progress, (max_retries, num_cpus, fan_in), merger)
    return merger.finish(output)


def _merge_parts(*parts: bytes) -> bytes:
    """A Ray task: parts of consecutive ranges merged into one part."""
    m = lumis.Merger()
    for p in parts:
        m.add(p)
    return m.finish_part()


def _run_tasks(
    ray: Any,
    job: Job,
    ranges: Sequence[Tuple[int, int]],
    progress: Union[bool, Callable[[float, int, float], Any]],
    options: Tuple[int, float, Optional[int]],
    merger: "lumis.Merger",
) -> None:
    """Renders ``ranges`` as Ray tasks (merged in a tree of ``fan_in``
    when set) and adds each part that reaches the caller to ``merger`` as
    it arrives, then drops it: the caller holds one film, not every part.
    Reports progress."""
    max_retries, num_cpus, fan_in = options
    total = ranges[-1][1]
    actor = ray.remote(num_cpus=0)(_Progress).remote(len(ranges))
    opts = dict(max_retries=max_retries, retry_exceptions=False, num_cpus=num_cpus)
    task = ray.remote(_render_range).options(**opts)
    text = job.to_json()
    rendering = [task.remote(text, a, b, i, actor) for i, (a, b) in enumerate(ranges)]
    # Each part that will reach the caller, with its range.
    level = [(r, a, b) for r, (a, b) in zip(rendering, ranges)]
    if fan_in is not None:
        merge = ray.remote(_merge_parts).options(**opts)
        while len(level) > fan_in:
            groups = [level[k : k + fan_in] for k in range(0, len(level), fan_in)]
            level = [(merge.remote(*(r for r, _, _ in g)), g[0][1], g[-1][2]) for g in groups]
    names = {r: f"passes {a}..{b}" for r, a, b in level}
    pending = [r for r, _, _ in level]
    del level
    report = _reporter(progress, len(ranges))
    t0 = _time.monotonic()
    try:
        while pending:
            ready, pending = ray.wait(pending, num_returns=1, timeout=_POLL)
            for r in ready:
                merger.add(ray.get(r), names.pop(r))
            # The renders still running (a finished one is dropped here, so
            # its part is freed once merged).
            if rendering:
                _, rendering = ray.wait(
                    rendering, num_returns=len(rendering), timeout=0, fetch_local=False
                )
            if report is not None:
                done = ray.get(actor.total.remote())
                report(done / total, done, _time.monotonic() - t0, len(ranges) - len(rendering))
    except BaseException:
        for r in pending + rendering:
            ray.cancel(r, force=True)
        raise
    finally:
        if isinstance(report, _Line):
            report.finish()
        ray.kill(actor)


def _study_run(config: str, out: str, run_id: str) -> Dict[str, Any]:
    """A Ray task: one run of a study, recorded in its folder."""
    task = lumis._lumis.start_study(config, out, run=run_id, quiet=True)
    while not task.wait(lumis._POLL):
        pass
    return task.result()


def study(
    config: PathLike,
    address: Optional[str] = None,
    *,
    out: Optional[PathLike] = None,
    progress: bool = True,
    max_retries: int = 3,
    num_cpus: float = 1,
) -> Dict[str, Any]:
    """Runs the study ``config`` (a ``lumis study`` TOML file) with its
    runs as Ray tasks, each writing its image and record into ``out``
    (default: ``<config stem>-report`` beside the config), then the study
    once more here: it finds those runs finished, runs the external
    settings' programs itself and writes the report ``lumis study``
    writes. Runs finished before are not rendered again. ``out`` and the
    config's scenes and references must be at the same paths on every
    worker (a shared folder). Runs with a time budget measure what a run
    makes in its time: give ``num_cpus`` the machines' core count so that
    runs do not share a machine (the config's ``threads`` is each run's
    thread count). Returns ``{finished, planned, interrupted,
    report, tasks}``: ``tasks`` is each task's run (``id``, ``status``,
    ``spp``, ``seconds``, ``relmse``)."""
    config = os.path.abspath(os.fspath(config))
    if out is None:
        stem = os.path.splitext(os.path.basename(config))[0]
        out = os.path.join(os.path.dirname(config), f"{stem}-report")
    out = os.path.abspath(os.fspath(out))
    runs = lumis._lumis.study_runs(config)
    ray = _connect(address)
    task = ray.remote(_study_run).options(
        max_retries=max_retries, retry_exceptions=False, num_cpus=num_cpus
    )
    refs = [task.remote(config, out, rid) for rid, _args, external in runs if not external]
    t0 = _time.monotonic()
    line = _Line(len(refs), "runs") if progress else None
    pending = list(refs)
    try:
        while pending:
            _, pending = ray.wait(pending, num_returns=len(pending), timeout=_POLL)
            if line is not None:
                done = len(refs) - len(pending)
                line(done / max(1, len(refs)), done, _time.monotonic() - t0, done)
        done_runs = ray.get(refs)
    except BaseException:
        for r in refs:
            ray.cancel(r, force=True)
        raise
    finally:
        if line is not None:
            line.finish()
    command = f"lumis.distributed.study({config!r})"
    final = lumis._lumis.start_study(config, out, command=command, quiet=True)
    try:
        while not final.wait(lumis._POLL):
            pass
    except KeyboardInterrupt:
        final.cancel()
        final.wait()
        raise
    result = final.result()
    result["tasks"] = done_runs
    return result
