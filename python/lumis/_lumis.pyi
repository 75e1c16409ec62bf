"""Type stubs of the native module `lumis._lumis` (see python/src/)."""

import os
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

_Path = Union[str, "os.PathLike[str]"]

__version__: str

class SceneError(ValueError):
    """A scene could not be read or built; `str(e)` is the full diagnostic."""

    message: str
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    help: Optional[str]

class Job:
    """A render job: scene, parameters layered over the file's, seed,
    budget, threads and outputs, as plain data (the library's RenderJob)."""

    seed: int
    spp: Optional[int]
    time: Optional[float]
    threads: int
    clamp: Optional[float]
    accel: str
    exposure: float
    @property
    def scene(self) -> Optional[Path]:
        """The scene file (None: the built-in default scene)."""
    @scene.setter
    def scene(self, value: Optional[_Path]) -> None: ...
    @property
    def outputs(self) -> List[Path]:
        """Images the render writes (empty: none)."""
    @outputs.setter
    def outputs(self, value: Sequence[_Path]) -> None: ...
    @property
    def passes(self) -> Optional[Tuple[int, int]]:
        """A partial render's passes (start, end), or None for all."""
    @passes.setter
    def passes(self, value: Optional[Tuple[int, int]]) -> None: ...
    @property
    def dir(self) -> Path:
        """The folder relative paths resolve against."""
    @dir.setter
    def dir(self, value: _Path) -> None: ...
    def __init__(self, scene: Optional[_Path] = None, **params: Any) -> None: ...
    @property
    def overrides(self) -> List[Dict[str, Optional[str]]]: ...
    def set(self, **params: Any) -> None: ...
    def with_params(self, **params: Any) -> "Job": ...
    def copy(self) -> "Job": ...
    def to_json(self) -> str: ...
    @staticmethod
    def from_json(text: str) -> "Job": ...
    def scene_path(self) -> Optional[Path]: ...
    def __eq__(self, other: object) -> bool: ...

class Loading:
    def wait(self, timeout: Optional[float] = None) -> bool: ...
    def result(self) -> "Session": ...

class Session:
    @property
    def job(self) -> Job: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def resolution(self) -> Tuple[int, int]: ...
    @property
    def size(self) -> Tuple[int, int]: ...
    @property
    def integrator(self) -> str: ...
    @property
    def spp(self) -> int: ...
    @property
    def pass_count(self) -> Optional[int]:
        """The whole render's passes (None: a time budget alone)."""
    @property
    def iteration_passes(self) -> int:
        """Passes per progressive photon iteration (1 otherwise)."""
    def can_render(self, job: Job) -> bool: ...
    def start(self, job: Job) -> "Task": ...

class Task:
    @property
    def cancelled(self) -> bool: ...
    @property
    def done(self) -> bool: ...
    def wait(self, timeout: Optional[float] = None) -> bool: ...
    def cancel(self) -> None: ...
    def progress(self) -> Optional[Tuple[float, int, float]]: ...
    def result(self) -> "_Result":
        """(pixels, width, height, metadata, stats, written, write_error, part)."""

_Result = Tuple[
    bytearray,
    int,
    int,
    Dict[str, str],
    Dict[str, Any],
    List[Path],
    Optional[str],
    Optional[bytes],
]

class Merger:
    def __init__(self) -> None: ...
    def __len__(self) -> int: ...
    def add(self, part: Union[bytes, _Path], name: Optional[str] = None) -> None: ...
    def finish(self, outputs: Optional[Sequence[_Path]] = None) -> _Result: ...
    def finish_part(self) -> bytes: ...

class StudyTask:
    def wait(self, timeout: Optional[float] = None) -> bool: ...
    def cancel(self) -> None: ...
    def result(self) -> Dict[str, Any]: ...

def job_from_flags(args: Sequence[str]) -> Job: ...
def study_runs(config: _Path) -> List[Tuple[str, List[str], bool]]: ...
def start_study(
    config: _Path,
    out: Optional[_Path] = None,
    command: str = "",
    run: Optional[str] = None,
    quiet: bool = False,
) -> StudyTask: ...

def load(job: Job) -> Loading: ...
def parameters() -> Dict[str, Dict[str, str]]: ...
def read_image(path: _Path) -> Tuple[bytearray, int, int, Dict[str, str]]: ...
def write_image(
    path: _Path,
    pixels: bytes,
    width: int,
    height: int,
    metadata: Sequence[Tuple[str, str]] = ...,
    exposure: float = 0.0,
) -> None: ...
def compare(
    test: Tuple[bytes, int, int],
    reference: Tuple[bytes, int, int],
    mask: Optional[Any] = None,
    lit: bool = False,
    heatmap: Optional[_Path] = None,
    heatmap_error: str = "rel",
    heatmap_range: Optional[Tuple[float, float]] = None,
) -> Dict[str, Any]: ...
