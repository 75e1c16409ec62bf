#!/usr/bin/env python3
"""Runs a command and writes its wall time and CPU time (user + system, of
all its threads and children) as JSON, for scripts/bench-vs-mitsuba.sh.

  python timed.py TIMES.json COMMAND [ARGS...]

The command's output passes through; the exit status is the command's.
"""

import json
import resource
import subprocess
import sys
import time


def main():
    out, cmd = sys.argv[1], sys.argv[2:]
    t0 = time.perf_counter()
    code = subprocess.call(cmd)
    wall = time.perf_counter() - t0
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(out, "w") as f:
        json.dump({"wall": wall, "cpu": ru.ru_utime + ru.ru_stime}, f)
    sys.exit(code)


if __name__ == "__main__":
    main()
