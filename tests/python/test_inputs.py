"""Soils and wheels: presets, files, dicts and keyword fields, read by the core's strict readers
with the command line's messages."""

import json

import pytest
import terrastudio as ts


def test_preset_file_and_dict_give_the_same_soil(resources):
    preset = ts.soil("sandy-loam")
    path = f"{resources}/soils/sandy-loam.json"
    with open(path) as f:
        as_dict = json.load(f)
    assert ts.soil(path) == preset
    assert ts.soil(as_dict) == preset
    assert preset["phi_deg"] == as_dict["phi_deg"]
    assert preset["c_kPa"] == as_dict["c_kPa"]
    assert preset.name == "sandy loam"
    assert "sandy-loam" in ts.presets("soils") and "A" in ts.presets("wheels")


def test_wheel_preset_values(resources):
    a = ts.wheel("A")
    with open(f"{resources}/wheels/A.json") as f:
        file = json.load(f)
    assert (a.r_m, a.b_m) == (file["r_m"], file["b_m"])
    assert ts.wheel({"name": "w", "r_m": 0.2, "b_m": 0.1}).r_m == 0.2


def test_keyword_fields_replace_the_presets_values():
    soil = ts.soil("sandy-loam", phi_deg=31.0, c_kPa=2.5)
    assert soil["phi_deg"] == 31.0 and soil["c_kPa"] == 2.5
    assert soil["n"] == ts.soil("sandy-loam")["n"]


def test_to_dict_round_trips():
    soil = ts.soil("lete-sand")
    assert ts.soil(soil.to_dict()) == soil


def test_unknown_preset_has_the_cli_message(cli):
    with pytest.raises(ValueError) as e:
        ts.soil("no-such-soil")
    run = cli("wheel", "--soil", "no-such-soil", "--entry-angle", "20")
    assert run.returncode == 2
    assert str(e.value) in run.stderr


def test_bad_soil_file_has_the_cli_message(cli, tmp_path):
    bad = ts.soil("sandy-loam").to_dict()
    bad["phi_deg"] = 95.0
    bad["K_mm"] = 3
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(bad))
    with pytest.raises(ValueError) as e:
        ts.soil(str(path))
    message = str(e.value)
    assert "phi_deg" in message and "95" in message and "K_mm" in message
    run = cli("wheel", "--soil", path, "--entry-angle", "20")
    assert run.returncode == 2
    for line in message.splitlines():
        assert line in run.stderr


def test_keyword_field_out_of_range_names_field_value_and_range():
    with pytest.raises(ValueError, match=r"phi_deg.*95.*allowed range"):
        ts.soil("sandy-loam", phi_deg=95.0)
    with pytest.raises(ValueError, match='did you mean "phi_deg"'):
        ts.soil("sandy-loam", phi=30.0)


def test_wrong_type():
    with pytest.raises(ValueError, match="expected a preset name, a JSON file or a dict"):
        ts.soil(3.0)


def test_soils_and_wheels_pickle_bit_for_bit():
    import pickle

    soil = ts.soil("sandy-loam", phi_deg=29.123456789)
    again = pickle.loads(pickle.dumps(soil))
    assert again == soil and again["phi_deg"] == soil["phi_deg"]
    assert pickle.loads(pickle.dumps(ts.wheel("B"))) == ts.wheel("B")


def test_lugged_wheels_keep_their_grousers_through_pickle_and_into_the_forces():
    # A worker process must get the lug model's fields (docs/model.md, "Lugs"), and ts.forces
    # must use them: the drawbar pull at the load is the command line's, and above the smooth one.
    import pickle

    spec = {"name": "A lugged", "r_m": 0.092, "b_m": 0.107, "grouser_height_m": 0.01,
            "grouser_count": 18, "lug_effect_coefficient": 0.5}
    lugged = ts.wheel(spec)
    again = pickle.loads(pickle.dumps(lugged))
    assert again == lugged and again.to_dict() == lugged.to_dict()
    assert again.to_dict()["lug_effect_coefficient"] == 0.5
    assert lugged != ts.wheel({k: v for k, v in spec.items() if k != "lug_effect_coefficient"})
    smooth = ts.forces("sandy-loam", "A", slip=[0.3], load_N=[58.86])
    out = ts.forces("sandy-loam", again, slip=[0.3], load_N=[58.86])
    assert out["Fx_N"][0] > smooth["Fx_N"][0] + 0.1
