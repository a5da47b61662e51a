"""topomill from Python: scenes, runs, height maps as numpy arrays, ISO 25178-2 parameters and
comparisons with measurements. Lengths and heights are in mm, as inside topomill; parameters
carry their units. docs/python.md is the guide."""

import json as _json

from . import _topomill
from ._errors import InputError, PluginError, SceneError
from .scene import SWEEP_PARAMETERS, Result, Scene, run, sweep
from .surface import Comparison, Map, Measurement, Parameter, compare, measure, read, write

__version__ = _topomill.version
__all__ = ["Comparison", "InputError", "Map", "Measurement", "Parameter", "PluginError",
           "Result", "SWEEP_PARAMETERS", "Scene", "SceneError", "compare", "describe", "log_level",
           "measure", "plugins", "read", "run", "sweep", "write"]


_LOG_LEVELS = {"quiet": 0, "normal": 1, "verbose": 2}


def log_level(level):
    """What topomill writes to stderr: "quiet" (warnings and errors: the default here),
    "normal" (the command line's: the models chosen, the grid) or "verbose"."""
    if level not in _LOG_LEVELS:
        raise ValueError(f"log_level: expected one of {', '.join(_LOG_LEVELS)}, got {level!r}")
    _topomill.set_log_level(_LOG_LEVELS[level])


def plugins(plugin_paths=()):
    """The models on the plugin search path, per slot: {"tool_geometry": [{"name": ..., "doc":
    ..., "parameters": [...]}, ...], ...}, as ``topomill plugins --json``."""
    return _json.loads(_topomill.plugins_json([str(p) for p in plugin_paths]))


def describe(name, plugin_paths=()):
    """A model's description and parameter schema (``"core"``: the core tables'), as
    ``topomill describe NAME --json``."""
    return _json.loads(_topomill.describe_json(name, [str(p) for p in plugin_paths]))
