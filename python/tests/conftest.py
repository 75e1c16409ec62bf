"""Shared fixtures: the CLI built beside the wheel, the repository's scenes,
and a reader of PFM files that does not go through lumis."""

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli() -> Path:
    """The `lumis` binary (scripts/python-tests.sh builds it and sets
    LUMIS_CLI); a missing one fails the tests that need it."""
    path = Path(os.environ.get("LUMIS_CLI", ROOT / "target" / "debug" / "lumis"))
    if not path.is_file():
        pytest.fail(f"no lumis binary at {path}: run scripts/python-tests.sh")
    return path


@pytest.fixture(scope="session")
def scenes() -> Path:
    return ROOT / "scenes"


def run_cli(cli: Path, *args, cwd=None) -> subprocess.CompletedProcess:
    """Runs the CLI; fails the test, with its stderr, if it fails."""
    p = subprocess.run(
        [str(cli), *map(str, args)], cwd=cwd, capture_output=True, text=True
    )
    assert p.returncode == 0, f"lumis {' '.join(map(str, args))} failed:\n{p.stderr}"
    return p


def read_pfm(path: Path) -> np.ndarray:
    """An RGB PFM as an (H, W, 3) float32 array, top row first."""
    data = Path(path).read_bytes()
    fields = data.split(maxsplit=4)
    assert fields[0] == b"PF"
    w, h, scale = int(fields[1]), int(fields[2]), float(fields[3])
    header = len(b" ".join(fields[:4])) + 1
    dtype = "<f4" if scale < 0 else ">f4"
    a = np.frombuffer(data[header:], dtype=dtype, count=w * h * 3).reshape(h, w, 3)
    return np.ascontiguousarray(a[::-1]).astype(np.float32)
