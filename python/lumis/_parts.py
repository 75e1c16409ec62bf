"""Partial renders and their exact merge.

A render of N passes (one sample per pixel each; N is the sample count)
can be cut into pass ranges ``start..end`` rendered anywhere, in any order,
by any number of processes or machines: :func:`render_part` renders one
range and gives its *part* (bytes: the film's exact sums and the range's
figures, the format of ``lumis render --passes A..B --partial FILE``);
:func:`merge` adds the parts of ranges that tile ``0..N`` into the image
one :func:`lumis.render` of the whole job gives, bit for bit.
"""

from __future__ import annotations

import os
from typing import Any, Optional, Sequence, Union

from . import (
    Image,
    Job,
    PathLike,
    ProgressCallback,
    Scene,
    _lumis,
    _path,
    _prepare,
    _result,
    _run,
)

PartLike = Union[bytes, bytearray, memoryview, PathLike]


def render_part(
    scene: Union[Scene, Job, PathLike, None],
    start: int,
    end: int,
    *,
    spp: Optional[int] = None,
    seed: Optional[int] = None,
    threads: Optional[int] = None,
    progress: Union[bool, ProgressCallback] = True,
    **params: Any,
) -> bytes:
    """Renders passes ``start..end`` (``start < end <= N``, N the render's
    pass count: its samples per pixel) of the render :func:`lumis.render`
    would make with the same arguments, and returns the part as bytes,
    for :func:`merge`. Writes nothing unless ``output=`` is given (then
    the image of this range alone).

    A part needs a sample count: a time budget (``time=``) is refused,
    since where it stops depends on the machine. A progressive ``photon``
    range that starts inside an iteration traces that iteration's photons
    again (the result is still exact); ranges aligned to
    ``iterationspp`` passes avoid it. Ctrl-C raises
    :class:`lumis.Interrupted` (the part so far is not returned).
    """
    given = dict(params, spp=spp, seed=seed, threads=threads)
    job, session = _prepare(scene, given, stacklevel=4)
    job.passes = (int(start), int(end))
    _, part = _run(session, job, progress)
    assert part is not None, "a partial render gives its part"
    return part


def merge(parts: Sequence[PartLike], output: Any = None) -> Image:
    """Merges the parts of one render (bytes from :func:`render_part`, or
    files from ``lumis render --partial``), given in any order, into the
    whole render's :class:`lumis.Image`: bit for bit the image of one
    :func:`lumis.render` of the whole job. ``output``: a path or a list of
    paths to write it to too (as ``lumis merge -o``).

    The scene is loaded again from the parts' job (its path as the parts
    recorded it, made absolute), so it must be reachable here and
    unchanged. Parts of different renders (another scene, seed, sample
    count or setting), ranges that overlap or leave a gap, and an
    unfinished part raise ``RuntimeError`` with the library's message.
    :class:`Merger` takes the parts one at a time instead."""
    if isinstance(parts, (bytes, bytearray, memoryview, str, os.PathLike)):
        raise TypeError("merge takes a list of parts (bytes or paths)")
    m = Merger()
    for p in parts:
        m.add(p)
    return m.finish(output)


class Merger:
    """A merge of parts added one at a time, in any order (e.g. as the
    machines rendering them finish): it keeps one film, the sum so far,
    so its memory is one part's however many there are.

        >>> m = lumis.Merger()
        >>> for part in parts_as_they_come():
        ...     m.add(part)
        >>> img = m.finish("out.exr")

    ``add`` refuses a part of another render than the first one's at once;
    ``finish`` checks the ranges (no gap, no overlap, all finished) and
    returns the :class:`lumis.Image`, as :func:`merge` does."""

    def __init__(self) -> None:
        self._m = _lumis.Merger()

    def __len__(self) -> int:
        """Parts added so far."""
        return len(self._m)

    def add(self, part: PartLike, name: Optional[str] = None) -> None:
        """Adds a part: bytes, or the path of its file. ``name`` labels
        it in errors (default ``part N``, or its path)."""
        if isinstance(part, (bytearray, memoryview)):
            part = bytes(part)
        elif not isinstance(part, bytes):
            part = os.fspath(part)
        self._m.add(part, name)

    def finish_part(self) -> bytes:
        """The parts added, which must be finished and tile a range of
        passes ``A..B`` without a gap or an overlap, as one part of
        ``A..B``: a part like any other, so parts can be merged in a tree
        (a few at a time where they were rendered, then those), to the
        same bits. Loads the scene; the merger is finished then."""
        return self._m.finish_part()

    def finish(self, output: Any = None) -> Image:
        """The whole render's image (``output``: a path or a list of paths
        to write it to too). A merger finishes once."""
        outputs = None
        if output is not None:
            many = isinstance(output, (list, tuple))
            outputs = [_path(o) for o in (output if many else [output])]
        img, _ = _result(self._m.finish(outputs))
        return img
