"""Scenes and runs: a scene loaded from TOML or built from a dict, changed key by key, run in
this process; and a sweep over keys, one record per case."""

import copy
import itertools
import json
import os

from . import _toml, _topomill
from .surface import Map, _parameters


class Scene:
    """A scene: its TOML text, the name it came under (relative paths in it resolve against
    that file's directory) and the changes ``set`` made, applied as ``--set`` applies them."""

    def __init__(self, text, name="<text>", plugin_paths=(), allow_scene_plugin_paths=True):
        self.text = text
        self.name = os.fspath(name)
        self.overrides = []
        self.plugin_paths = [os.fspath(p) for p in plugin_paths]
        self.allow_scene_plugin_paths = allow_scene_plugin_paths
        _topomill.parse_scene(self._native())

    @classmethod
    def load(cls, path, **options):
        """The scene file at ``path``; SceneError (with file, line, column) for malformed TOML.
        Options: plugin_paths (directories searched first), allow_scene_plugin_paths (False
        refuses a scene that names plugin directories: one you did not write)."""
        path = os.fspath(path)
        data = _topomill.read_scene(path)  # bounded, as the command line reads it
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            # The TOML reader names the line and column of the bad byte, as for the command line.
            _topomill.parse_scene(_topomill.SceneText(data, path, [], [], True))
            raise
        return cls(text, path, **options)

    @classmethod
    def from_dict(cls, tables, name="<dict>", **options):
        """A scene from a dict of tables: {"tool": {"plugin": "ball_end_loxodrome", ...},
        "cutting": {...}, ...}, written as TOML (``scene.text``) and read as a file is."""
        return cls(_toml.document(tables), name, **options)

    def set(self, key, value):
        """Changes one key ("cutting.feed_per_tooth", "tool.radius"), checked at once for its
        form and when run for its value. Returns the scene, so that calls chain."""
        if not isinstance(key, str) or not key:
            raise TypeError("set(key, value): key is a dotted string, e.g. 'cutting.stepover'")
        change = f"{key}={_toml.literal(value, key)}"
        _topomill.parse_scene(self._native(self.overrides + [change]))
        self.overrides.append(change)
        return self

    def copy(self):
        """An independent copy: set() on it leaves this one as it is."""
        return copy.deepcopy(self)

    def check(self, threads=1):
        """Validates every table, the unused ones too, and the models built from them, as
        ``topomill check``; returns the resolved scene as TOML text (defaults filled in)."""
        return _topomill.check_scene(self._native(), int(threads))

    def _native(self, overrides=None):
        return _topomill.SceneText(self.text, self.name,
                                   self.overrides if overrides is None else overrides,
                                   self.plugin_paths, self.allow_scene_plugin_paths)

    def __repr__(self):
        changes = "".join(f", {o}" for o in self.overrides)
        return f"Scene({self.name!r}{changes})"


class Result:
    """A finished run. ``height_raw`` (the Z-map over the plan grid) and ``height_residual``
    (after form removal; along the surface when the scene unrolls it) are read-only numpy views
    of the run's own memory, in mm, shape (ny, nx); ``raw`` and ``residual`` are the same as
    Maps with their grids. ``x``, ``y``, ``spacing`` and ``origin`` are the raw grid's."""

    def __init__(self, record):
        self._record = record
        g, r = record.raw_grid, record.residual_grid
        self.raw = Map(record.raw, g["dx"], g["dy"], g["x0"], g["y0"], "height_raw")
        self.residual = Map(record.residual, r["dx"], r["dy"], r["x0"], r["y0"], "height_residual")
        self.parameters = _parameters(record.parameters)
        self.undefined = dict(record.undefined)
        self.summary = json.loads(record.summary)
        self.timing = dict(record.stages)
        self.timing["total"] = self.summary["timing_s"]["total"]

    @property
    def height_raw(self):
        return self.raw.z

    @property
    def height_residual(self):
        return self.residual.z

    @property
    def x(self):
        return self.raw.x

    @property
    def y(self):
        return self.raw.y

    @property
    def spacing(self):
        return self.raw.spacing

    @property
    def origin(self):
        return self.raw.origin

    @property
    def unrolled(self):
        """Whether height_residual lies on the unrolled surface (x, s) rather than the plan."""
        return self._record.unrolled

    def __repr__(self):
        sa = self.parameters.get("Sa")
        roughness = f", Sa {sa.value:g} {sa.unit}" if sa else ""
        return f"Result({self.summary['scene']['name']!r}, raw {self.raw.shape}{roughness})"


def run(scene, threads=1):
    """Runs a scene (a Scene, or a path to a scene file) in this process, with the GIL
    released; Ctrl-C stops it within 2 s (KeyboardInterrupt). No files are written: the
    Result holds the maps, the parameters and what summary.json would say."""
    if not isinstance(scene, Scene):
        scene = Scene.load(scene)
    return Result(_topomill.run_scene(scene._native(), int(threads)))


# The parameters each sweep record carries, as `topomill sweep` tabulates them.
SWEEP_PARAMETERS = ("Sa", "Sq", "Sz", "Ssk", "Sku", "Sdq", "Sdr")


def _column(name, unit):
    """A parameter's column, its unit in the name as `topomill sweep` writes it: Sa_um,
    Sdr_percent, Ssk (no unit)."""
    if unit == "1":
        return name
    return f"{name}_{'percent' if unit == '%' else unit}"


def sweep(scene, vary, threads=1, keep_results=False):
    """Runs the cross product of ``vary`` ({"cutting.feed_per_tooth": [0.05, 0.1], ...}) on
    copies of ``scene``, one after the other; returns one record (a dict) per case: the varied
    keys, each of SWEEP_PARAMETERS as "Sa_um" etc. (unit in the name), "time_s", and with
    ``keep_results`` the Result under "result". ``pandas.DataFrame(records)`` takes them."""
    if not isinstance(scene, Scene):
        scene = Scene.load(scene)
    keys = list(vary)
    values = [list(vary[k]) for k in keys]
    for k, v in zip(keys, values):
        if not v:
            raise ValueError(f"vary[{k!r}]: expected at least one value")
        for value in v:  # every value checked before any case runs, as `topomill sweep` does
            _topomill.resolve_scene(scene.copy().set(k, value)._native())
    records = []
    for combination in itertools.product(*values):
        case = scene.copy()
        for k, v in zip(keys, combination):
            case.set(k, v)
        result = run(case, threads)
        record = dict(zip(keys, combination))
        for name in SWEEP_PARAMETERS:
            p = result.parameters.get(name)
            if p is not None:
                record[_column(name, p.unit)] = p.value
        record["time_s"] = result.timing["total"]  # the run's own, as `topomill sweep` reports
        if keep_results:
            record["result"] = result
        records.append(record)
    return records
