"""The plugin catalogue, and sweeps as records a DataFrame takes."""

import pandas as pd
import pytest

import topomill
from conftest import QUICK, cli_json


def test_plugins_are_the_command_lines():
    ours = topomill.plugins()
    theirs = cli_json("plugins", "--json")
    for slot, models in ours.items():
        assert [m["name"] for m in models] == [m["name"] for m in theirs[slot]]
    assert "ball_end_loxodrome" in [m["name"] for m in ours["tool_geometry"]]


def test_describe_a_model_and_the_core():
    assert topomill.describe("zmap") == cli_json("describe", "zmap", "--json")
    assert "cutting" in topomill.describe("core")
    with pytest.raises(topomill.InputError) as e:
        topomill.describe("zmapp")
    assert e.value.key == "name" and "zmap" in str(e.value)  # the near miss suggested


def test_a_sweep_is_one_record_per_case_in_order():
    feeds, stepovers = [0.05, 0.1], [0.2, 0.3]
    records = topomill.sweep(QUICK, {"cutting.feed_per_tooth": feeds,
                                     "cutting.stepover": stepovers})
    assert [(r["cutting.feed_per_tooth"], r["cutting.stepover"]) for r in records] == [
        (f, s) for f in feeds for s in stepovers]
    alone = topomill.run(topomill.Scene.load(QUICK).set("cutting.feed_per_tooth", 0.1)
                         .set("cutting.stepover", 0.2))
    assert records[2]["Sa_um"] == alone.parameters["Sa"].value
    assert all(r["time_s"] > 0 for r in records)
    frame = pd.DataFrame(records)
    assert frame.shape[0] == 4
    assert {"Sa_um", "Sq_um", "Sz_um", "Ssk", "Sku", "Sdq", "Sdr_percent", "time_s"} <= set(
        frame.columns)


def test_a_sweep_refuses_an_empty_list_and_a_bad_value():
    with pytest.raises(ValueError):
        topomill.sweep(QUICK, {"cutting.feed_per_tooth": []})
    with pytest.raises(topomill.SceneError) as e:
        topomill.sweep(QUICK, {"cutting.feed_per_tooth": [0.1, -0.1]})
    assert e.value.key == "cutting.feed_per_tooth"


def test_a_sweep_checks_every_value_before_it_runs_a_case(monkeypatch):
    ran = []
    monkeypatch.setattr(topomill.scene, "run", lambda *a, **k: ran.append(a))
    with pytest.raises(topomill.SceneError):
        topomill.sweep(QUICK, {"cutting.stepover": [0.2, 0.3], "cutting.feed_per_tooth": [0.1, -1]})
    assert ran == []
