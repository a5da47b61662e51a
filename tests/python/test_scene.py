"""Scenes and runs from Python, against the command line on the same scene."""

import json

import numpy as np
import pytest

import topomill
from conftest import QUICK, ROOT, cli


def test_a_loaded_scene_runs_to_the_command_lines_bits(tmp_path):
    # The same scene and the same change both ways: the summary's parameters as doubles, and
    # the heights through the same x3p writer and reader.
    scene = topomill.Scene.load(QUICK).set("cutting.feed_per_tooth", 0.15)
    r = topomill.run(scene.set("output.formats", ["x3p"]))
    out = tmp_path / "cli"
    cli("run", QUICK, "-q", "--set", "cutting.feed_per_tooth=0.15", "--set",
        'output.formats=["x3p"]', "--out", out)
    summary = json.loads((out / "summary.json").read_text())
    assert r.summary["roughness"] == summary["roughness"]
    for name, entry in summary["roughness"].items():
        assert r.parameters[name].value == entry["value"]
        assert r.parameters[name].unit == entry["unit"]
    assert r.summary["grid"] == summary["grid"]
    assert r.summary["resolved_scene"] == summary["resolved_scene"]
    for which, m in (("height_raw", r.raw), ("height_residual", r.residual)):
        topomill.write(tmp_path / f"{which}.x3p", m)
        ours = topomill.read(tmp_path / f"{which}.x3p").z
        theirs = topomill.read(out / f"{which}.x3p").z
        assert np.array_equal(ours, theirs)


def test_the_maps_are_views_of_the_run_not_copies():
    r = topomill.run(QUICK)
    g = r.summary["grid"]["zmap"]
    assert r.height_raw.shape == (g["ny"], g["nx"])
    assert r.height_raw.dtype == np.float64 and r.height_raw.flags["C_CONTIGUOUS"]
    assert not r.height_raw.flags["OWNDATA"] and not r.height_raw.flags["WRITEABLE"]
    assert r.height_raw is r.raw.z and r.height_residual is r.residual.z
    # The same memory each time it is asked for: a view kept alive by the result.
    again = topomill.Map(r.raw.z, *r.raw.spacing)
    assert np.shares_memory(again.z, r.height_raw)
    with pytest.raises(ValueError):
        r.height_raw[0, 0] = 1.0
    assert r.x.shape == (g["nx"],) and r.y.shape == (g["ny"],)
    assert r.spacing == (g["dx_mm"], g["dy_mm"]) and r.origin == (g["x0_mm"], g["y0_mm"])
    assert np.all(np.isfinite(r.height_raw)) and np.all(np.isfinite(r.height_residual))


def test_a_view_outlives_the_result_that_made_it():
    z = topomill.run(QUICK).height_residual
    import gc
    gc.collect()
    assert np.isfinite(z).all() and z.std() > 0


def test_threads_change_nothing():
    one = topomill.run(QUICK, threads=1)
    two = topomill.run(QUICK, threads=2)
    assert np.array_equal(one.height_raw, two.height_raw)


def test_timing_and_summary():
    r = topomill.run(QUICK)
    assert set(r.timing) >= {"setup", "evaluate", "form_removal", "parameters", "total"}
    assert all(v >= 0 for v in r.timing.values())
    assert r.summary["scene"]["name"] == "quick example"
    assert r.summary["files"] == []


def test_from_dict_is_the_same_scene_as_its_file():
    tables = {
        "scene": {"name": "quick example"},
        "tool": {"plugin": "ball_end_loxodrome", "radius": 5.0, "teeth": 2, "helix_angle": 30.0},
        "workpiece": {"plugin": "convex_arc", "radius": 50.0},
        "cutting": {"spindle_speed": 4000, "feed_per_tooth": 0.1, "depth_of_cut": 0.3,
                    "stepover": 0.3},
        "region": {"lambda": 30.0, "size": [0.3, 0.3], "spacing": 0.02},
        "evaluator": {"plugin": "tooth_passage"},
    }
    from_dict = topomill.run(topomill.Scene.from_dict(tables))
    from_file = topomill.run(QUICK)
    assert np.array_equal(from_dict.height_raw, from_file.height_raw)


def test_set_changes_a_copy_only():
    base = topomill.Scene.load(QUICK)
    changed = base.copy().set("cutting.feed_per_tooth", 0.2)
    assert base.overrides == [] and len(changed.overrides) == 1
    a, b = topomill.run(base), topomill.run(changed)
    assert a.parameters["Sa"].value != b.parameters["Sa"].value


def test_check_returns_the_resolved_scene():
    text = topomill.Scene.load(QUICK).check()
    assert "[evaluator]" in text and "walk = " in text  # a default filled in
    assert text == cli("check", QUICK, "-q")[1]


def bad_scene(tmp_path, text):
    p = tmp_path / "bad.toml"
    p.write_text(text)
    return p


def test_malformed_toml_is_a_scene_error_with_the_command_lines_message(tmp_path):
    p = bad_scene(tmp_path, QUICK.read_text().replace("teeth = 2", "teeth = = 2"))
    with pytest.raises(topomill.SceneError) as e:
        topomill.Scene.load(p)
    code, _, stderr = cli("check", p, check=False)
    assert code == 2
    assert str(e.value) == stderr.strip()
    assert e.value.file == str(p) and e.value.line == 9 and e.value.column > 0


def test_a_value_out_of_range_names_its_key_and_place(tmp_path):
    p = bad_scene(tmp_path, QUICK.read_text().replace("radius = 5.0", "radius = -5.0"))
    scene = topomill.Scene.load(p)  # well-formed: refused when resolved
    with pytest.raises(topomill.SceneError) as e:
        topomill.run(scene)
    code, _, stderr = cli("run", p, "--out", tmp_path / "out", check=False)
    assert code == 2 and str(e.value) == stderr.strip()
    assert (e.value.file, e.value.line, e.value.key) == (str(p), 8, "tool.radius")
    assert isinstance(e.value, topomill.InputError) and isinstance(e.value, ValueError)


def test_set_refuses_what_the_scene_cannot_hold():
    scene = topomill.Scene.load(QUICK)
    with pytest.raises(topomill.SceneError) as e:
        topomill.run(scene.copy().set("cutting.feed_per_tooth", -1))
    assert e.value.key == "cutting.feed_per_tooth"
    assert e.value.file == "--set cutting.feed_per_tooth=-1"
    with pytest.raises(topomill.SceneError) as e:
        topomill.run(scene.copy().set("cutting.feed_pertooth", 0.1))
    assert "feed_per_tooth" in str(e.value)  # the near miss suggested
    with pytest.raises(TypeError):
        scene.set("cutting.feed_per_tooth", object())
    assert scene.overrides == []  # a refused set() leaves the scene as it was


def test_no_nan_or_infinity_gets_into_a_scene():
    for value in (float("nan"), float("inf")):
        with pytest.raises(topomill.SceneError):
            topomill.run(topomill.Scene.load(QUICK).set("cutting.stepover", value))


def test_threads_out_of_range():
    with pytest.raises(topomill.SceneError) as e:
        topomill.run(QUICK, threads=0)
    assert e.value.key == "threads"


@pytest.mark.parametrize("case", ["missing", "directory", "not utf-8"])
def test_an_unreadable_scene_file_fails_as_on_the_command_line(tmp_path, case):
    p = tmp_path / "scene.toml"
    if case == "directory":
        p.mkdir()
    elif case == "not utf-8":
        p.write_bytes(QUICK.read_bytes().replace(b"quick example", b"quick \xff example"))
    with pytest.raises(topomill.SceneError) as e:
        topomill.Scene.load(p)
    code, _, stderr = cli("check", p, check=False)
    assert code == 2 and str(e.value) == stderr.strip()
    assert e.value.file == str(p)
