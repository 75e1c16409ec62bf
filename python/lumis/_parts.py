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
    unfinished part raise ``RuntimeError`` with the library's message."""
    if isinstance(parts, (bytes, bytearray, memoryview, str, os.PathLike)):
        raise TypeError("merge takes a list of parts (bytes or paths)")
    items = []
    for p in parts:
        if isinstance(p, (bytearray, memoryview)):
            p = bytes(p)
        elif not isinstance(p, bytes):
            p = os.fspath(p)
        items.append(p)
    outputs = None
    if output is not None:
        many = isinstance(output, (list, tuple))
        outputs = [_path(o) for o in (output if many else [output])]
    img, _ = _result(_lumis.merge(items, outputs))
    return img
