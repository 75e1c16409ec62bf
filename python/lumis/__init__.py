"""lumis from Python: render pbrt-v4 scenes to numpy arrays.

    >>> import lumis
    >>> img = lumis.render("scene.pbrt", spp=64, integrator="photon")
    >>> img.shape, img.dtype            # (H, W, 3) float32, linear RGB
    >>> img.metadata["lumis:spp"]       # what an EXR written by the CLI carries
    >>> lumis.write("out.exr", img)
    >>> lumis.compare(img, "reference.exr")["mse"]

    >>> scene = lumis.load("scene.pbrt", resolution=(320, 240), spp=16)
    >>> a = lumis.render(scene, seed=1)     # parsed and built once,
    >>> b = lumis.render(scene, seed=2)     # rendered twice

Renders are the CLI's: the same defaults (the scene file's settings, seed
0, all cores) and the same parameters under the same names
(``caustic_photons=`` for ``--caustic-photons``; :func:`parameters` lists
the integrators' own), so an image equals the CLI's bit for bit. Nothing is
written unless asked (``output=``). The render runs with the GIL released;
Ctrl-C stops it after the current pass and raises :class:`Interrupted` (a
``KeyboardInterrupt``) whose ``image`` is the image so far, also given by
:func:`last_render`. Scene errors raise :class:`SceneError` (a
``ValueError``) with ``file``, ``line`` and ``column``; scene warnings are
issued as :class:`SceneWarning` through :mod:`warnings`.

A render's passes (one sample per pixel each) can be rendered in ranges
anywhere, :func:`render_part`, and merged exactly, :func:`merge` and
:class:`Merger`; :mod:`lumis.distributed` does so on a Ray cluster.
"""

from __future__ import annotations

import os
import sys
import time as _time
import warnings as _warnings
from typing import Any, Callable, Dict, Optional, Sequence, Tuple, Union

import numpy as np

from . import _lumis
from ._lumis import Job, SceneError, __version__

__all__ = [
    "Image",
    "Interrupted",
    "Job",
    "Merger",
    "Scene",
    "SceneError",
    "SceneWarning",
    "compare",
    "last_render",
    "load",
    "merge",
    "parameters",
    "read",
    "render",
    "render_part",
    "write",
]

PathLike = Union[str, "os.PathLike[str]"]
ProgressCallback = Callable[[float, int, float], Any]

# How often a waiting caller wakes up: Python runs its signal handlers
# (Ctrl-C) and the progress report then.
_POLL = 0.05


class SceneWarning(UserWarning):
    """A scene's warning: an unused or unsupported parameter, a fallback."""


class Interrupted(KeyboardInterrupt):
    """Ctrl-C stopped a render after its current pass.

    A ``KeyboardInterrupt``, so ``except KeyboardInterrupt`` catches it;
    ``image`` is the image so far (an :class:`Image` whose
    ``stats["spp"]`` says how many samples per pixel it has, and
    ``stats["interrupted"]`` is True). :func:`last_render` gives it too.
    """

    def __init__(self, image: "Image") -> None:
        spp = image.stats["spp"] if image.stats else 0
        super().__init__(
            f"render interrupted at {spp} spp; the image so far is this "
            "exception's `image` and lumis.last_render()"
        )
        self.image = image


class Image(np.ndarray):
    """A rendered or read image: a float32 ``(height, width, 3)`` array of
    linear RGB (top row first), with

    - ``metadata``: ``dict[str, str]``, the text attributes an EXR carries
      (``lumis:spp``, ``lumis:integrator``, ``lumis:seed``, ``lumis:scene``,
      ...); :func:`write` stores them in an EXR, :func:`read` reads them back;
    - ``stats``: the render's figures (``spp``, ``seconds``, ``rays``,
      ``interrupted``, ``bad_samples``, ``first_bad_sample``,
      ``integrator``, ``photons`` for ``photon``, ``written``: the files
      written), or None for an image read from a file.

    It is an ``ndarray`` in every other way; arrays computed from it keep
    these attributes, ``np.asarray(img)`` is a plain array.
    """

    metadata: Dict[str, str]
    stats: Optional[Dict[str, Any]]

    def __new__(
        cls,
        array: Any,
        metadata: Optional[Dict[str, str]] = None,
        stats: Optional[Dict[str, Any]] = None,
    ) -> "Image":
        img = np.asarray(array, dtype=np.float32).view(cls)
        img.metadata = dict(metadata or {})
        img.stats = stats
        return img

    def __array_finalize__(self, obj: Any) -> None:
        self.metadata = getattr(obj, "metadata", {})
        self.stats = getattr(obj, "stats", None)

    # Pickling (e.g. to other processes) keeps the attributes.
    def __reduce__(self):  # type: ignore[override]
        fn, args, state = super().__reduce__()  # type: ignore[misc]
        return fn, args, (state, self.metadata, self.stats)

    def __setstate__(self, state):  # type: ignore[override]
        base, self.metadata, self.stats = state
        super().__setstate__(base)  # type: ignore[misc]


class Scene:
    """A scene loaded by :func:`load`: parsed and built once, rendered any
    number of times. Renders that change only ``seed``, ``time``,
    ``threads``, ``clamp`` or ``output`` reuse it; other parameters
    (``spp``, ``integrator``, ``resolution``, an integrator's parameter...)
    change how it is built, so such a render loads the scene again for
    itself (give them to :func:`load` to build once)."""

    def __init__(self, session: "_lumis.Session") -> None:
        self._session = session

    @property
    def job(self) -> Job:
        """The job it was loaded for (a copy)."""
        return self._session.job

    @property
    def size(self) -> Tuple[int, int]:
        """The rendered image's (width, height): the crop window's."""
        return self._session.size

    @property
    def resolution(self) -> Tuple[int, int]:
        """The film's full (width, height)."""
        return self._session.resolution

    @property
    def integrator(self) -> str:
        return self._session.integrator

    @property
    def spp(self) -> int:
        """Samples per pixel as loaded."""
        return self._session.spp

    @property
    def warnings(self) -> list:
        """The scene's warnings, as text (also issued as SceneWarning)."""
        return self._session.warnings

    def render(self, **params: Any) -> Image:
        """``lumis.render(self, **params)``."""
        return render(self, **params)

    def __repr__(self) -> str:
        scene = self._session.job.scene
        w, h = self.size
        name = os.fspath(scene) if scene is not None else "<built-in default scene>"
        return f"<lumis.Scene {name!r}: {w}x{h}, {self.integrator}, {self.spp} spp>"


_last: Optional[Image] = None


def last_render() -> Optional[Image]:
    """The image of the latest render in this process (finished or
    interrupted), or None before the first."""
    return _last


def parameters() -> Dict[str, Dict[str, str]]:
    """The integrators' own parameters: keyword → its scene-file ``type``
    and ``name``, the CLI's ``flag``, the ``value`` it takes and ``help``.
    Besides these, :func:`render` takes ``spp``, ``time``, ``seed``,
    ``threads``, ``integrator``, ``maxdepth``, ``resolution``, ``crop``,
    ``sampler``, ``filter_splat``, ``clamp``, ``accel``, ``output`` and
    ``exposure``."""
    return _lumis.parameters()


def load(path: Optional[PathLike] = None, **params: Any) -> Scene:
    """Parses and builds a pbrt-v4 scene file (None: the built-in default
    scene) with ``params`` layered over the file's settings, as
    :func:`render` takes them. Raises :class:`SceneError` with the location
    of a scene's mistake; issues its warnings as :class:`SceneWarning`."""
    job = Job(_path(path), **params)
    return Scene(_load_session(job, stacklevel=3))


def render(
    scene: Union[Scene, Job, PathLike, None] = None,
    *,
    spp: Optional[int] = None,
    time: Optional[float] = None,
    seed: Optional[int] = None,
    threads: Optional[int] = None,
    progress: Union[bool, ProgressCallback] = True,
    **params: Any,
) -> Image:
    """Renders a scene and returns its :class:`Image`.

    ``scene``: a :class:`Scene` from :func:`load`, a :class:`Job`, a scene
    file's path, or None for the built-in default scene.

    - ``spp``: samples per pixel (default: the scene file's);
    - ``time``: a wall-clock budget in seconds (the render stops after the
      last whole pass that fits; with ``spp`` too, at whichever comes first);
    - ``seed``: default 0 (a Scene's or Job's own otherwise);
    - ``threads``: default all cores; the image does not depend on it;
    - ``progress``: True prints one line of progress on stderr, False
      nothing; a callable is called as ``progress(fraction, spp_done,
      seconds)`` from the calling thread while it waits;
    - ``params``: the CLI's other render options by the same names:
      ``integrator``, ``maxdepth``, ``resolution=(w, h)``,
      ``crop=(x0, x1, y0, y1)``, ``sampler``, ``filter_splat`` (True, the
      default for filters wider than a pixel: each sample weighted into
      every pixel the filter reaches; False: the filter sampled, one pixel
      per sample, as pbrt-v4), ``clamp``, ``accel``,
      ``output`` (a path or a list: files to write, as ``-o``),
      ``exposure`` (for PNG outputs), and every integrator parameter of
      :func:`parameters` (``caustic_photons=``, ``caustics="mis"``, ...).
      An unknown name raises ``TypeError``.

    Ctrl-C stops the render after its current pass and raises
    :class:`Interrupted` carrying the image so far. Scene errors raise
    :class:`SceneError`.
    """
    given = dict(params, spp=spp, time=time, seed=seed, threads=threads)
    job, session = _prepare(scene, given, stacklevel=4)
    return _run(session, job, progress)[0]


def _prepare(
    scene: Union[Scene, Job, PathLike, None], given: Dict[str, Any], stacklevel: int
) -> Tuple[Job, "_lumis.Session"]:
    """The job ``scene`` and ``given`` make, and a session loaded for it
    (a Scene's own when it can render the job)."""
    if isinstance(scene, Scene):
        job = scene._session.job.with_params(**given)
        session = scene._session
        if not session.can_render(job):
            session = _load_session(job, stacklevel=stacklevel)
    elif isinstance(scene, Job):
        job = scene.with_params(**given)
        session = _load_session(job, stacklevel=stacklevel)
    else:
        job = Job(_path(scene), **given)
        session = _load_session(job, stacklevel=stacklevel)
    return job, session


def read(path: PathLike) -> Image:
    """Reads an .exr, .pfm or .png file (PNG decoded from sRGB to linear)
    as an :class:`Image` whose ``metadata`` is the EXR's text attributes."""
    pixels, w, h, metadata = _lumis.read_image(os.fspath(path))
    return Image(_array(pixels, w, h), metadata)


def write(
    path: PathLike,
    image: Any,
    *,
    exposure: float = 0.0,
    metadata: Optional[Dict[str, str]] = None,
) -> None:
    """Writes an ``(H, W, 3)`` array by its extension: .exr (float32, with
    ``metadata``, by default the image's own, as text attributes), .pfm,
    or .png (sRGB, 8-bit, scaled by ``2**exposure``). Written to a
    temporary file, then renamed: never left half-written."""
    a = _rgb(image, "image")
    if metadata is None:
        metadata = getattr(image, "metadata", None) or {}
    items = [(str(k), str(v)) for k, v in metadata.items()]
    h, w, _ = a.shape
    _lumis.write_image(os.fspath(path), a.tobytes(), w, h, items, float(exposure))


def compare(
    test: Union[PathLike, Any],
    reference: Union[PathLike, Any],
    *,
    mask: Optional[Sequence[float]] = None,
    lit: bool = False,
    heatmap: Optional[PathLike] = None,
    heatmap_error: str = "rel",
    heatmap_range: Optional[Tuple[float, float]] = None,
) -> Dict[str, Any]:
    """The metrics ``lumis compare`` prints, of ``test`` against
    ``reference`` (arrays or image files of the same size): ``pixels``,
    ``mse``, ``rmse``, ``relmse`` (mean of (t-r)^2 / (r^2 + 0.01)),
    ``mae``, ``mean_test``, ``mean_reference`` and ``ratio`` (per channel).

    ``mask=(x0, x1, y0, y1)``: only that region (fractions, as ``--mask``);
    ``lit``: only pixels where the test image and its eight neighbours are
    not black (``--lit``); ``heatmap``: also write the per-pixel error map
    to this PNG (``--heatmap``, with ``heatmap_error`` ``"rel"`` or
    ``"abs"`` and ``heatmap_range=(lo, hi)``), its range then given as
    ``heatmap_range``."""
    t = _image_arg(test, "test")
    r = _image_arg(reference, "reference")
    return _lumis.compare(
        t,
        r,
        mask=mask,
        lit=lit,
        heatmap=None if heatmap is None else os.fspath(heatmap),
        heatmap_error=heatmap_error,
        heatmap_range=heatmap_range,
    )


# ----------------------------------------------------------------------------


def _path(p: Optional[PathLike]) -> Optional[str]:
    return None if p is None else os.fspath(p)


def _array(pixels: bytearray, w: int, h: int) -> np.ndarray:
    return np.frombuffer(pixels, dtype=np.float32).reshape(h, w, 3)


def _rgb(image: Any, what: str) -> np.ndarray:
    a = np.asarray(image)
    if a.ndim != 3 or a.shape[2] != 3:
        raise ValueError(f"{what}: expected an (H, W, 3) RGB array, found shape {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float32)


def _image_arg(x: Any, what: str) -> Tuple[bytes, int, int]:
    if isinstance(x, (str, os.PathLike)):
        x = read(x)
    a = _rgb(x, what)
    return a.tobytes(), a.shape[1], a.shape[0]


def _load_session(job: Job, stacklevel: int) -> "_lumis.Session":
    """Loads on a thread of its own, waiting in slices so Ctrl-C is not
    held up by a long parse or build (the load then finishes unseen)."""
    loading = _lumis.load(job)
    while not loading.wait(_POLL):
        pass
    session = loading.result()
    for w in session.warnings:
        _warnings.warn(w, SceneWarning, stacklevel=stacklevel)
    return session


def _run(
    session: "_lumis.Session", job: Job, progress: Union[bool, ProgressCallback]
) -> Tuple[Image, Optional[bytes]]:
    """The render's image and, for a partial render, its part."""
    global _last
    report = _reporter(progress)
    task = session.start(job)
    try:
        while not task.wait(_POLL):
            p = task.progress()
            if report is not None and p is not None:
                report(*p)
        p = task.progress()
        if report is not None and p is not None:
            report(*p)
    except KeyboardInterrupt:
        # Stop after the current pass and keep what it made; a second
        # Ctrl-C while waiting for that gives up on the image.
        task.cancel()
        while not task.wait(_POLL):
            pass
        _last = _result(task.result())[0]
        raise Interrupted(_last) from None
    except BaseException:
        task.cancel()
        raise
    finally:
        if isinstance(report, _StderrProgress):
            report.finish()
    _last, part = _result(task.result())
    return _last, part


def _result(result: tuple) -> Tuple[Image, Optional[bytes]]:
    """A render's or a merge's image (``OSError`` if its outputs could not
    be written), and a partial render's part."""
    pixels, w, h, metadata, stats, written, write_error, part = result
    stats["written"] = [os.fspath(p) for p in written]
    img = Image(_array(pixels, w, h), metadata, stats)
    if write_error is not None:
        global _last
        _last = img
        raise OSError(write_error)
    return img, part


def _reporter(progress: Union[bool, ProgressCallback]) -> Optional[ProgressCallback]:
    if callable(progress):
        return progress
    return _StderrProgress() if progress else None


class _StderrProgress:
    """One line on stderr, as the CLI's: rewritten in place on a terminal
    (at most 10 times a second, cleared at the end), else a line every
    5 s and one at the end."""

    def __init__(self) -> None:
        try:
            self.tty = sys.stderr.isatty()
        except (AttributeError, ValueError):
            self.tty = False
        self.last: Optional[float] = None
        self.width = 0
        self.closed = False

    def __call__(self, fraction: float, spp: int, seconds: float) -> None:
        now = _time.monotonic()
        line = f"{fraction * 100:5.1f}%  {spp} spp  {seconds:.1f} s"
        if self.tty:
            if self.last is not None and now - self.last < 0.1:
                return
            line = f"lumis [{'#' * int(fraction * 30):<30}] {line}"
            sys.stderr.write("\r" + line.ljust(self.width))
            self.width = len(line)
        else:
            done = fraction >= 1.0
            if self.closed or (not done and self.last is not None and now - self.last < 5.0):
                return
            sys.stderr.write(f"progress: {line}\n")
            self.closed = done
        self.last = now
        sys.stderr.flush()

    def finish(self) -> None:
        if self.tty and self.width > 0:
            sys.stderr.write("\r" + " " * self.width + "\r")
            sys.stderr.flush()


# Partial renders and their merge (they use the helpers above).
from ._parts import Merger, merge, render_part  # noqa: E402
