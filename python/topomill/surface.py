"""Height maps in numpy: reading and writing x3p, sdf, gsf and csv, ISO 25178-2 parameters, and
a simulation compared with a measurement."""

import os
from typing import NamedTuple

import numpy as np

from . import _topomill


class Parameter(NamedTuple):
    """One areal parameter: its value in ``unit`` ("um", "%", "1" for none), and how it was
    discretised where topomill offers more than one way (else "")."""

    value: float
    unit: str
    method: str = ""


def _parameters(rows):
    return {name: Parameter(value, unit, method) for name, value, unit, method in rows}


class Map:
    """A height map: ``z`` of shape (ny, nx), x fastest, in mm, NaN where a point is missing;
    node (i, j) at (x0 + i dx, y0 + j dy) mm."""

    def __init__(self, z, dx, dy=None, x0=0.0, y0=0.0, source="map"):
        self.z = np.asarray(z, dtype=np.float64)
        if self.z.ndim != 2:
            raise ValueError(f"z: expected a 2-D array (ny, nx), got shape {self.z.shape}")
        self.dx = float(dx)
        self.dy = float(dx if dy is None else dy)
        self.x0 = float(x0)
        self.y0 = float(y0)
        self.source = source

    @property
    def shape(self):
        return self.z.shape

    @property
    def spacing(self):
        """(dx, dy) in mm."""
        return (self.dx, self.dy)

    @property
    def origin(self):
        """(x0, y0) in mm: the first node's place."""
        return (self.x0, self.y0)

    @property
    def x(self):
        """The nodes' x in mm, one per column."""
        return self.x0 + self.dx * np.arange(self.z.shape[1])

    @property
    def y(self):
        """The nodes' y in mm, one per row."""
        return self.y0 + self.dy * np.arange(self.z.shape[0])

    @property
    def valid(self):
        """True where a point has a height."""
        return np.isfinite(self.z)

    def _args(self):
        return _topomill.MapArgs(self.z, self.dx, self.dy, self.x0, self.y0, self.source)

    def __repr__(self):
        ny, nx = self.z.shape
        return (f"Map({nx} x {ny} nodes, {self.dx * 1e3:g} x {self.dy * 1e3:g} um, "
                f"from {self.source!r})")


def _map(parts, source):
    z, dx, dy, x0, y0 = parts
    return Map(z, dx, dy, x0, y0, source)


def read(path, spacing=0.0):
    """A height map from an .x3p, .sdf, .gsf or .csv file (a CSV without a grid in its header
    needs ``spacing`` in mm). Heights in mm."""
    path = os.fspath(path)
    return _map(_topomill.read_surface(path, float(spacing)), path)


def write(path, surface, description="written by the topomill Python package"):
    """Writes a Map (or anything with z, dx, dy, x0, y0) as .x3p, .sdf, .gsf or .csv, by the
    extension; atomically. Missing points (NaN) only .x3p can keep."""
    m = _as_map(surface)
    _topomill.write_surface(os.fspath(path), m._args(), description)


def _as_map(surface, dx=None, dy=None):
    if isinstance(surface, Map):
        return surface
    if isinstance(getattr(surface, "residual", None), Map):  # a run's Result: what it measured
        return surface.residual
    if hasattr(surface, "z") and hasattr(surface, "dx"):
        return Map(surface.z, surface.dx, surface.dy, surface.x0, surface.y0,
                   getattr(surface, "source", "map"))
    if dx is None:
        raise TypeError("an array needs its spacing: measure(z, dx=..., dy=...)")
    return Map(surface, dx, dy, source="array")


def _options(form, filter_s, filter_l, parameters, settings):
    if isinstance(parameters, str):
        parameters = [parameters]
    options = {"form": form, "filter_s": float(filter_s), "filter_l": float(filter_l),
               "parameters": ",".join(parameters), "acf_threshold": 0.2, "volume_p": 10.0,
               "volume_q": 80.0, "sxp_p": 2.5, "sxp_q": 50.0, "smr_c": 0.0, "smc_mr": 10.0}
    for key, value in settings.items():
        if key not in options or key in ("form", "filter_s", "filter_l", "parameters"):
            raise TypeError(f"unexpected setting {key!r}: expected one of acf_threshold, "
                            "volume_p, volume_q, sxp_p, sxp_q, smr_c, smc_mr")
        options[key] = float(value)
    return options


class Measurement(NamedTuple):
    """What ``measure`` returns: the parameters, those undefined for this map (name -> why),
    the processed map (form removed, filtered) and the processing in ISO 25178-3's words."""

    parameters: dict
    undefined: dict
    surface: Map
    processing: str


def measure(surface, dx=None, dy=None, form="none", filter_s=0.0, filter_l=0.0,
            parameters=("default",), **settings):
    """ISO 25178-2 parameters of a Map, a run's result or a 2-D array (then with dx, dy in mm),
    as ``topomill measure`` computes them: the form removed ("none", "plane", "poly:N", "arc"),
    then the S-filter (nesting index ``filter_s`` mm) and the L-filter (cut-off ``filter_l``
    mm). ``parameters``: names or families (default, all, height, spatial, hybrid, functional,
    volume). Settings as the command line's, by keyword: acf_threshold, volume_p, volume_q,
    sxp_p, sxp_q (in %), smr_c (um), smc_mr (%)."""
    m = _as_map(surface, dx, dy)
    processed, rows, undefined, processing = _topomill.measure(
        m._args(), _options(form, filter_s, filter_l, parameters, settings))
    return Measurement(_parameters(rows), dict(undefined), _map(processed, m.source), processing)


class Comparison(NamedTuple):
    """What ``compare`` returns. ``registration``: the move that takes the simulation onto the
    measurement (tx, ty mm, angle rad, offset mm, correlation, rms mm, overlap nodes,
    iterations, converged); ``sim`` and ``aligned`` (the measurement in the simulation's frame)
    over the overlap on the common grid, and ``difference`` = aligned - sim; each one's
    parameters over the overlap, and their lays (std_deg, lay_deg, across_mm, along_mm, x_mm,
    y_mm)."""

    registration: dict
    sim: Map
    aligned: Map
    difference: Map
    sim_parameters: dict
    meas_parameters: dict
    sim_lay: dict
    meas_lay: dict
    overlap_share: float
    interpolation: str
    processing: str


def compare(sim, meas, form="none", filter_s=0.0, filter_l=0.0, parameters=("default",),
            rotation=False, max_shift=0.0, **settings):
    """A simulated surface beside a measured one, as ``topomill compare`` does: both processed
    alike, on the coarser grid, the measurement registered onto the simulation (the in-plane
    angle too with ``rotation``; shifts up to ``max_shift`` mm, 0: any), differenced."""
    s, m = _as_map(sim), _as_map(meas)
    out = _topomill.compare(s._args(), m._args(),
                            _options(form, filter_s, filter_l, parameters, settings),
                            bool(rotation), float(max_shift))
    return Comparison(
        registration=out["registration"], sim=_map(out["sim"], s.source),
        aligned=_map(out["aligned"], m.source), difference=_map(out["difference"], "difference"),
        sim_parameters=_parameters(out["sim_parameters"]),
        meas_parameters=_parameters(out["meas_parameters"]), sim_lay=out["sim_lay"],
        meas_lay=out["meas_lay"], overlap_share=out["overlap_share"],
        interpolation=out["interpolation"], processing=out["processing"])
