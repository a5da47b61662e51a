# What `import topomill` offers, for editors and type checkers (the package's .py files hold
# the code and the documentation).
import os
from typing import Any, Iterable, Mapping, NamedTuple, Sequence, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, os.PathLike[str]]
_Heights = npt.NDArray[np.float64]

__version__: str
SWEEP_PARAMETERS: tuple[str, ...]

class InputError(ValueError):
    file: str
    line: int
    column: int
    key: str
    message: str
    def __init__(self, text: str, file: str = ..., line: int = ..., column: int = ...,
                 key: str = ..., message: str = ...) -> None: ...

class SceneError(InputError): ...
class PluginError(RuntimeError): ...

class Parameter(NamedTuple):
    value: float
    unit: str
    method: str = ...

class Map:
    z: _Heights
    dx: float
    dy: float
    x0: float
    y0: float
    source: str
    def __init__(self, z: npt.ArrayLike, dx: float, dy: float | None = ..., x0: float = ...,
                 y0: float = ..., source: str = ...) -> None: ...
    @property
    def shape(self) -> tuple[int, int]: ...
    @property
    def spacing(self) -> tuple[float, float]: ...
    @property
    def origin(self) -> tuple[float, float]: ...
    @property
    def x(self) -> _Heights: ...
    @property
    def y(self) -> _Heights: ...
    @property
    def valid(self) -> npt.NDArray[np.bool_]: ...

class Measurement(NamedTuple):
    parameters: dict[str, Parameter]
    undefined: dict[str, str]
    surface: Map
    processing: str

class Comparison(NamedTuple):
    registration: dict[str, Any]
    sim: Map
    aligned: Map
    difference: Map
    sim_parameters: dict[str, Parameter]
    meas_parameters: dict[str, Parameter]
    sim_lay: dict[str, float]
    meas_lay: dict[str, float]
    overlap_share: float
    interpolation: str
    processing: str

class Scene:
    text: str
    name: str
    overrides: list[str]
    plugin_paths: list[str]
    allow_scene_plugin_paths: bool
    def __init__(self, text: str, name: _Path = ..., plugin_paths: Iterable[_Path] = ...,
                 allow_scene_plugin_paths: bool = ...) -> None: ...
    @classmethod
    def load(cls, path: _Path, *, plugin_paths: Iterable[_Path] = ...,
             allow_scene_plugin_paths: bool = ...) -> Scene: ...
    @classmethod
    def from_dict(cls, tables: Mapping[str, Any], name: str = ..., *,
                  plugin_paths: Iterable[_Path] = ...,
                  allow_scene_plugin_paths: bool = ...) -> Scene: ...
    def set(self, key: str, value: Any) -> Scene: ...
    def copy(self) -> Scene: ...
    def check(self, threads: int = ...) -> str: ...

class Result:
    raw: Map
    residual: Map
    parameters: dict[str, Parameter]
    undefined: dict[str, str]
    summary: dict[str, Any]
    timing: dict[str, float]
    @property
    def height_raw(self) -> _Heights: ...
    @property
    def height_residual(self) -> _Heights: ...
    @property
    def x(self) -> _Heights: ...
    @property
    def y(self) -> _Heights: ...
    @property
    def spacing(self) -> tuple[float, float]: ...
    @property
    def origin(self) -> tuple[float, float]: ...
    @property
    def unrolled(self) -> bool: ...

_Surface = Union[Map, Result, npt.ArrayLike]

def run(scene: Union[Scene, _Path], threads: int = ...) -> Result: ...
def sweep(scene: Union[Scene, _Path], vary: Mapping[str, Sequence[Any]], threads: int = ...,
          keep_results: bool = ...) -> list[dict[str, Any]]: ...
def read(path: _Path, spacing: float = ...) -> Map: ...
def write(path: _Path, surface: Union[Map, Result], description: str = ...) -> None: ...
def measure(surface: _Surface, dx: float | None = ..., dy: float | None = ...,
            form: str = ..., filter_s: float = ..., filter_l: float = ...,
            parameters: Union[str, Sequence[str]] = ..., **settings: float) -> Measurement: ...
def compare(sim: Union[Map, Result], meas: Union[Map, Result], form: str = ...,
            filter_s: float = ..., filter_l: float = ...,
            parameters: Union[str, Sequence[str]] = ..., rotation: bool = ...,
            max_shift: float = ..., **settings: float) -> Comparison: ...
def plugins(plugin_paths: Iterable[_Path] = ...) -> dict[str, list[dict[str, Any]]]: ...
def describe(name: str, plugin_paths: Iterable[_Path] = ...) -> dict[str, Any]: ...
def log_level(level: str) -> None: ...
