"""Height maps in numpy: files, parameters and comparisons, against published values, closed
forms and the command line."""

import math

import numpy as np
import pytest

import topomill
from conftest import ROOT, cli_json

REF = ROOT / "tests" / "refdata" / "surfacetopography"


def sine(nx=200, ny=60, dx=0.001, period=0.02, amplitude=0.002):
    """z = A sin(2 pi x / period) over whole periods, in mm."""
    x = dx * np.arange(nx)
    return np.tile(amplitude * np.sin(2 * np.pi * x / period), (ny, 1))


def test_published_parameters_of_a_measured_map():
    # tests/refdata/README.md: Gwyddion, SurfaceTopography and a plain recomputation agree.
    m = topomill.read(REF / "x3p-2.x3p")
    assert m.shape == (650, 650) and m.dx == pytest.approx(1.27656509837346e-04, rel=1e-14)
    p = topomill.measure(m).parameters
    assert p["Sa"].unit == "um"
    assert p["Sa"].value == pytest.approx(6.19546556887485e-08 * 1e6, rel=1e-12)
    assert p["Sq"].value == pytest.approx(7.72803327359775e-08 * 1e6, rel=1e-12)
    assert p["Sz"].value == pytest.approx(5.543362e-07 * 1e6, rel=1e-12)
    assert p["Ssk"].value == pytest.approx(-0.346788601267018, rel=1e-12)


def test_measure_agrees_with_the_command_line_to_the_bit():
    path = REF / "x3p-2.x3p"
    ours = topomill.measure(topomill.read(path), form="plane", filter_l=0.025,
                            parameters=["all"]).parameters
    theirs = cli_json("measure", path, "--form", "plane", "--filter-l", "0.025", "--parameters",
                      "all", "--json")["roughness"]
    assert set(ours) == {k for k, v in theirs.items() if "value" in v}
    for name, p in ours.items():
        assert p.value == theirs[name]["value"], name


def test_a_sine_has_its_closed_form_parameters():
    # N nodes a period (N even): the mean of |sin| over them is (2 / N) cot(pi / N), of sin^2
    # 1/2 and of sin^4 3/8 (N > 4).
    a, n = 0.002, 20  # mm; sine()'s period over its spacing
    p = topomill.measure(sine(amplitude=a), dx=0.001, dy=0.001).parameters
    assert p["Sa"].value == pytest.approx(a * 2 / n / math.tan(math.pi / n) * 1e3, rel=1e-12)
    assert p["Sq"].value == pytest.approx(a / math.sqrt(2) * 1e3, rel=1e-12)
    assert p["Sku"].value == pytest.approx(1.5, rel=1e-12)
    assert p["Ssk"].value == pytest.approx(0, abs=1e-12)


def test_a_plane_is_removed_and_a_filter_applied():
    z = sine() + 0.01 * np.arange(200)[None, :] * 0.001
    m = topomill.measure(z, dx=0.001, dy=0.001, form="plane", parameters=["Sq"])
    assert m.parameters["Sq"].value == pytest.approx(0.002 / math.sqrt(2) * 1e3, rel=2e-2)
    assert m.surface.shape == z.shape and "plane" in m.processing
    assert abs(np.mean(m.surface.z)) < 1e-9


@pytest.mark.parametrize("ext", ["x3p", "sdf", "gsf", "csv"])
def test_each_format_reads_back_what_was_written(tmp_path, ext):
    z = sine(nx=40, ny=30)
    m = topomill.Map(z, 0.001, 0.002, x0=0.5, y0=-0.25)
    topomill.write(tmp_path / f"m.{ext}", m)
    back = topomill.read(tmp_path / f"m.{ext}")
    assert back.shape == z.shape
    assert np.allclose(back.z, z, rtol=0, atol=1e-9)
    assert back.spacing == pytest.approx((0.001, 0.002), rel=1e-9)


def test_a_csv_without_a_grid_needs_its_spacing(tmp_path):
    p = tmp_path / "bare.csv"
    p.write_text("1,2,3\n4,5,6\n7,8,9\n")
    with pytest.raises(topomill.InputError):
        topomill.read(p)
    m = topomill.read(p, spacing=0.002)
    assert m.spacing == (0.002, 0.002) and m.z[1, 2] == pytest.approx(6e-3)  # um in a CSV
    topomill.write(tmp_path / "grid.csv", m)
    with pytest.raises(topomill.InputError) as e:
        topomill.read(tmp_path / "grid.csv", spacing=0.001)  # not the grid the file gives
    assert e.value.key == "spacing" and e.value.file == "read()"


def test_missing_points_survive_in_x3p_only(tmp_path):
    z = sine(nx=20, ny=20)
    z[3, 4] = np.nan
    topomill.write(tmp_path / "m.x3p", topomill.Map(z, 0.001))
    back = topomill.read(tmp_path / "m.x3p")
    assert np.isnan(back.z[3, 4]) and back.valid.sum() == z.size - 1
    with pytest.raises(topomill.InputError):
        topomill.write(tmp_path / "m.gsf", topomill.Map(z, 0.001))
    assert not (tmp_path / "m.gsf").exists()


def test_bad_input_names_the_argument():
    z = sine()
    with pytest.raises(topomill.InputError) as e:
        topomill.measure(z, dx=0.001, form="cubic")
    assert e.value.key == "form" and "cubic" in str(e.value)
    with pytest.raises(topomill.InputError) as e:
        topomill.measure(z, dx=0.001, filter_s=0.1, filter_l=0.05)
    assert e.value.key == "filter_s"
    with pytest.raises(topomill.InputError) as e:
        topomill.measure(z, dx=0.001, parameters=["Sb"])
    assert e.value.key == "parameters"
    with pytest.raises(topomill.InputError) as e:
        topomill.measure(z, dx=0.001, volume_p=150)
    assert e.value.key == "volume_p"
    with pytest.raises(topomill.InputError):
        topomill.measure(np.full((3, 3), np.nan), dx=0.001)
    with pytest.raises(topomill.InputError):
        topomill.read(ROOT / "README.md")
    with pytest.raises(TypeError):
        topomill.measure(z)  # an array needs its spacing


def test_compare_finds_a_known_shift_and_offset():
    rng = np.random.default_rng(7)
    base = rng.normal(0, 1e-3, (90, 90))
    base = (base + np.roll(base, 1, 0) + np.roll(base, 1, 1)) / 3  # some correlation
    sim = topomill.Map(base[10:70, 10:70], 0.001)
    meas = topomill.Map(base[13:73, 5:65] + 0.004, 0.001)  # sim's node (i, j) at (i+5, j-3)
    c = topomill.compare(sim, meas, max_shift=0.01)
    reg = c.registration
    assert reg["tx"] == pytest.approx(0.005, abs=1e-6)
    assert reg["ty"] == pytest.approx(-0.003, abs=1e-6)
    assert reg["offset"] == pytest.approx(0.004, abs=1e-9)
    d = c.difference.z[np.isfinite(c.difference.z)]
    assert d.size > 1000 and np.max(np.abs(d)) < 1e-9
    assert c.sim_parameters["Sa"].value == pytest.approx(c.meas_parameters["Sa"].value, rel=1e-9)


def test_hostile_maps_are_refused_not_written(tmp_path):
    with pytest.raises(topomill.InputError):
        topomill.write(tmp_path / "empty.x3p", topomill.Map(np.zeros((0, 5)), 0.001))
    with pytest.raises(topomill.InputError):
        topomill.write(tmp_path / "flat.x3p", topomill.Map(np.zeros((4, 4)), float("nan")))
    with pytest.raises(topomill.InputError):
        topomill.write(tmp_path / "m.txt", topomill.Map(np.zeros((4, 4)), 0.001))
    assert list(tmp_path.iterdir()) == []
    huge = sine() * 1e300  # finite heights whose squares overflow
    with pytest.raises(topomill.InputError):
        topomill.measure(huge, dx=0.001)
