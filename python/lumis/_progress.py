"""Progress of distributed work: the Ray actor tasks report to, and the
one line the caller prints."""

from __future__ import annotations

import sys
import time as _time
from typing import Any, Callable, Optional


class _Progress:
    """A Ray actor the tasks report to: passes done per task."""

    def __init__(self, n: int) -> None:
        self.done = [0] * n

    def report(self, index: int, passes: int) -> None:
        self.done[index] = passes

    def total(self) -> int:
        return sum(self.done)


def _reporter(progress: Any, ntasks: int) -> Optional[Callable[..., Any]]:
    if callable(progress):
        return lambda f, p, s, _done: progress(f, p, s)
    return _Line(ntasks) if progress else None


class _Line:
    """One line of progress on stderr: rewritten in place on a terminal,
    else printed every 5 s and at the end."""

    def __init__(self, ntasks: int, unit: str = "passes") -> None:
        self.ntasks = ntasks
        self.unit = unit
        self.tty = getattr(sys.stderr, "isatty", lambda: False)()
        self.last: Optional[float] = None
        self.width = 0

    def __call__(self, fraction: float, passes: int, seconds: float, done: int) -> None:
        now = _time.monotonic()
        end = done == self.ntasks
        if self.last is not None and now - self.last < (0.1 if self.tty else 5.0) and not end:
            return
        line = (
            f"lumis: {done}/{self.ntasks} tasks, {fraction * 100:5.1f}% of {self.unit} "
            f"({passes}), {seconds:.1f} s"
        )
        if self.tty:
            sys.stderr.write("\r" + line.ljust(self.width))
            self.width = len(line)
        else:
            sys.stderr.write(line + "\n")
        self.last = now
        sys.stderr.flush()

    def finish(self) -> None:
        if self.tty and self.width:
            sys.stderr.write("\r" + " " * self.width + "\r")
            sys.stderr.flush()
