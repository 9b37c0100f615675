"""sweep, stresses, identify, simulate and run: the registry's analyses from Python."""

import json
import os

import numpy as np
import pytest
import terrastudio as ts

SOIL, WHEEL = "sandy-loam", "A"


def test_sweep_agrees_with_forces_point_by_point():
    # The sweep warm-starts each entry-angle solve from the previous slip, the batch starts cold:
    # two routes to the same equilibrium, equal within the solver's tolerance.
    slips = [0.05, 0.2, 0.4, 0.8]
    table = ts.sweep(SOIL, WHEEL, slips, slip_angles_deg=[5.0, 20.0], load_N=70.0)
    assert len(table["slip"]) == 8 and table["notes"] == []
    out = ts.forces(SOIL, WHEEL, slip=table["slip"], slip_angle_deg=table["slip_angle_deg"],
                    load_N=70.0)
    np.testing.assert_allclose(table["Fz_N"], 70.0, rtol=1e-6)
    np.testing.assert_allclose(out["Fx_N"], table["Fx_N"], rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(out["entry_angle_deg"], table["entry_angle_deg"], rtol=1e-6)


def test_sweep_with_a_fixed_entry_angle_is_the_batch_exactly():
    table = ts.sweep(SOIL, WHEEL, [0.1, 0.5], slip_angles_deg=[10.0], entry_angle_deg=25.0)
    out = ts.forces(SOIL, WHEEL, slip=[0.1, 0.5], slip_angle_deg=10.0, entry_angle_deg=25.0)
    np.testing.assert_array_equal(out["My_Nm"], table["My_Nm"])


def test_sweep_reports_unknown_keys_like_a_script():
    with pytest.raises(ValueError, match='did you mean "slips"'):
        ts.sweep(SOIL, WHEEL, slipz=[0.1])
    with pytest.raises(ValueError, match=r"slips\[1\]: 2 is outside the allowed range"):
        ts.sweep(SOIL, WHEEL, [0.1, 2.0])


def test_stresses_at_a_given_entry_angle():
    out = ts.stresses(SOIL, WHEEL, slip=0.3, slip_angle_deg=12.0, entry_angle_deg=30.0,
                      step_deg=0.5)
    s = out["stresses"]
    assert out["entry_angle_deg"] == pytest.approx(30.0, rel=1e-12)
    assert s["theta_deg"][-1] == pytest.approx(30.0)
    # σ vanishes at the entry angle (no sinkage there, Eq. 2.13) and peaks inside the contact.
    assert s["sigma_kPa"][-1] == pytest.approx(0.0, abs=1e-9)
    assert 0.0 < np.argmax(s["sigma_kPa"]) < len(s["sigma_kPa"]) - 1
    assert len(out["errors"]["rmse_kPa"]) == 4


def test_stresses_document_is_what_stresses_json_prints(cli):
    # Issue 26: one toJson in core; ts.stresses carries what `stresses --json` prints, every key.
    out = ts.stresses(SOIL, WHEEL, slip=0.2, slip_angle_deg=5.0, load_N=80.0, step_deg=0.5)
    run = cli("stresses", "--soil", SOIL, "--wheel", WHEEL, "--slip", 0.2, "--slip-angle", 5,
              "--load", 80, "--step", 0.5, "--json")
    assert run.returncode == 0, run.stderr
    assert out["document"] == json.loads(run.stdout)
    assert out["document"]["status"] == "completed"
    assert out["document"]["errors"]["entry_angle_deg"] == pytest.approx(out["entry_angle_deg"])


def test_identify_recovers_the_soil_of_noiseless_synthetic_data():
    # Data made from the soil without noise: the full-model refinement lands on that soil (the
    # decoupled start is a linearisation and is off by itself).
    soil, wheel = ts.soil(SOIL), ts.wheel(WHEEL)
    out = ts.identify(None, wheel, soil, noise_percent=0.0, slip_count=12)
    p = out["parameters"]
    assert out["usable"]
    for key, expected in (("phi_deg", soil["phi_deg"]), ("c_kPa", soil["c_kPa"]),
                          ("K_m", soil["K_m"]), ("n0", soil["n"]), ("a0", soil["a0"]),
                          ("a1", soil["a1"])):
        assert p[key] == pytest.approx(expected, rel=1e-6), key
    # K_s = k_c / b + k_phi (Eq. 2.3), in kPa-based file units.
    assert p["Ks_kPa"] == pytest.approx(soil["kc"] / wheel.b_m + soil["kphi"], rel=1e-6)
    assert p["phi_deg_std"] < 1e-6
    assert len(out["curves"]["slip"]) == 12


def test_identify_reads_the_old_parameter_keys_with_a_deprecation_warning():
    # Issue 26: "Ks" and "n" (the keys of before) name the same parameters as "Ks_kPa" and "n0".
    settings = dict(noise_percent=1.0, slip_count=10, starts=4)
    new = ts.identify(None, WHEEL, SOIL, fix={"n0": 0.7}, priors=["Ks_kPa=1500±500"], **settings)
    with pytest.warns(DeprecationWarning, match="'Ks' is deprecated: use 'Ks_kPa'"):
        old = ts.identify(None, WHEEL, SOIL, fix={"n": 0.7}, priors=["Ks=1500±500"], **settings)
    assert old["parameters"] == new["parameters"]
    assert old["n0"] == 0.7
    assert old["start"] == new["start"]


def test_the_parameter_names_are_the_cores_table_as_the_command_line_names_them(tmp_path, cli):
    # Issue 26: one table of the identified parameters, in the core; Python reads it
    # (identified_parameters()) and names the parameters as `identify` does: its JSON's keys,
    # its flags' words and its deprecation note for an old key.
    fields = ts.identified_parameters()
    assert [f["key"] for f in fields] == ["a0", "a1", "Ks_kPa", "n0", "n1", "c_kPa", "phi_deg",
                                          "K_m", "jmax_m"]
    assert {f["old_key"]: f["key"] for f in fields if f["old_key"]} == {"Ks": "Ks_kPa", "n": "n0"}
    assert {f["key"]: f["soil_key"] for f in fields if f["soil_key"] != f["key"]} == {
        "Ks_kPa": "kphi", "n0": "n"}
    refined = [f["key"] for f in fields if f["refined"]]
    # One load: c and phi trade off, and the flag names them.
    data = tmp_path / "one-load.csv"
    made = cli("synth", "--soil", SOIL, "--wheel", WHEEL, "--load", "58.86", "--noise",
               "fx=2%,fz=2%,my=2%", "--out", data)
    assert made.returncode == 0, made.stderr
    printed = cli("identify", "--data", data, "--wheel", WHEEL, "--prior", "Ks=1500±500", "--json")
    assert printed.returncode == 0, printed.stderr
    expected = json.loads(printed.stdout)
    assert sorted(expected["std"]) == sorted(refined)  # a JSON object: keys in any order
    with pytest.warns(DeprecationWarning) as said:
        out = ts.identify(data, WHEEL, priors=["Ks=1500±500"])
    assert sorted(out["std"]) == sorted(refined)
    assert out["flags"] == expected["flags"]
    assert any(f.startswith("c_kPa and phi_deg trade off") for f in out["flags"]), out["flags"]
    # The same note: the command line's after its flag's name, Python's after "priors".
    note = "prior 'Ks=1500±500': parameter key 'Ks' is deprecated: use 'Ks_kPa'"
    assert f"warning: --prior: {note}" in printed.stderr.splitlines(), printed.stderr
    assert [str(w.message) for w in said] == [f"priors: {note}"]


def test_identify_from_columns_equals_from_csv(tmp_path):
    soil = ts.soil(SOIL)
    synthetic = ts.identify(None, WHEEL, soil, noise_percent=1.0, slip_count=10, refine=False)
    c = synthetic["curves"]
    data = {k: c[k] for k in ("slip", "entry_angle_deg", "Fx_N", "Fz_N", "My_Nm")}
    path = tmp_path / "data.csv"
    with open(path, "w") as f:
        f.write(",".join(data) + "\n")
        for row in zip(*data.values()):
            f.write(",".join(repr(float(v)) for v in row) + "\n")
    from_columns = ts.identify(data, WHEEL, refine=False)
    from_file = ts.identify(path, WHEEL, refine=False)
    assert from_columns["parameters"] == from_file["parameters"]


def _same(a, b, where):
    """a == b, numbers to 1e-9 relative (the same code on the same data), recursively."""
    if isinstance(b, dict):
        assert isinstance(a, dict) and set(a) == set(b), where
        for key in b:
            _same(a[key], b[key], f"{where}.{key}")
    elif isinstance(b, list):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{where}[{i}]")
    elif isinstance(b, float) and not isinstance(b, bool):
        assert a == pytest.approx(b, rel=1e-9, abs=1e-300), where
    else:
        assert a == b, where


def test_identify_returns_what_the_command_line_prints(tmp_path, cli):
    # Issue 25: ts.identify returned less than `identify --json` (no flags, no covariance, no
    # held-out errors). Both print the core's one JSON; only the wall times differ.
    data = tmp_path / "data.csv"
    made = cli("synth", "--soil", SOIL, "--wheel", WHEEL, "--load", "30,58.86,90", "--slips",
               "0.05:0.85:15", "--noise", "fx=1%,fz=1%,my=1%", "--out", data)
    assert made.returncode == 0, made.stderr
    printed = cli("identify", "--data", data, "--wheel", WHEEL, "--jmax", "0.02", "--folds", "3",
                  "--json")
    assert printed.returncode == 0, printed.stderr
    expected = json.loads(printed.stdout)
    out = ts.identify(data, WHEEL, jmax_m=0.02, folds=3)
    assert out["usable"]
    for step in expected["steps"] + out["steps"]:
        del step["time_ms"]
    for key, value in expected.items():
        assert key in out, key
        _same(out[key], value, key)
    assert out["covariance"]["parameters"] == ["a0", "a1", "Ks_kPa", "n0", "c_kPa", "phi_deg",
                                               "K_m"]
    assert out["jmax_m"] == 0.02 and out["std"]["jmax_m"] == 0.0  # held
    assert out["holdout"]["samples"] == 45
    # The held-out step says what it did (it was an empty line).
    held = [n for n in out["notes"] if n.startswith("held-out")]
    assert held and "45 samples predicted" in held[0], out["notes"]


def test_identify_fits_jmax_as_the_command_line_does(tmp_path, cli):
    # Issue 25, item 3: j_max identified (`--jmax fit`, jmax_m="fit"): the same JSON, j_max in
    # the covariance, and near the 20 mm the data were made with (sandy loam's j_max).
    data = tmp_path / "data.csv"
    made = cli("synth", "--soil", SOIL, "--wheel", WHEEL, "--load", "30,58.86,90", "--noise",
               "fx=1%,fz=1%,my=1%", "--out", data)
    assert made.returncode == 0, made.stderr
    printed = cli("identify", "--data", data, "--wheel", WHEEL, "--jmax", "fit", "--json")
    assert printed.returncode == 0, printed.stderr
    expected = json.loads(printed.stdout)
    out = ts.identify(data, WHEEL, jmax_m="fit")
    for step in expected["steps"] + out["steps"]:
        del step["time_ms"]
    for key, value in expected.items():
        assert key in out, key
        _same(out[key], value, key)
    assert out["covariance"]["parameters"][-1] == "jmax_m"
    assert abs(out["jmax_m"] - 0.02) < 3 * out["std"]["jmax_m"]
    assert not out["adequacy"]["flag"]
    with pytest.raises(ValueError, match="jmax_m"):
        ts.identify(data, WHEEL, jmax_m="yes")


def test_validation_returns_what_validate_json_prints(cli, resources):
    # Issue 26, item 3: the validation's result is described once in core (toJson), so a script's
    # "validation" analysis from Python returns what `terrastudio validate --json` prints, key by
    # key, the calibration with its held-out points included.
    test = os.path.join(resources, "experiments", "ding2011-smooth-fig9-hit-lss1-80N.csv")
    printed = cli("validate", "--experiments", test, "--soil", "hit-lss1", "--wheel",
                  "ding2011-smooth", "--calibrate", "--noise", "Fx_N=0.5,My_Nm=0.1,sinkage_m=0.0005",
                  "--fit-slips", "0,0.2,0.6", "--json")
    assert printed.returncode == 0, printed.stderr
    expected = json.loads(printed.stdout)
    out = ts.run("validation", "hit-lss1", "ding2011-smooth", experiments=test, calibrate=True,
                 noise={"Fx_N": 0.5, "My_Nm": 0.1, "sinkage_m": 0.0005}, fit_slips=[0, 0.2, 0.6])
    assert out["status"] == "completed", out["message"]
    document = out["documents"]["-validation.json"]
    assert sorted(document) == sorted(expected)
    for key, value in expected.items():
        _same(document[key], value, key)
    assert document["calibration"]["held_out"]["metrics"]["Fx_N"]["count"] == 3
    # A flag's bad value and a script key's are refused in the same words.
    bad = cli("validate", "--experiments", test, "--soil", "hit-lss1", "--calibrate", "--noise",
              "Fx_N=-1")
    assert bad.returncode == 2
    assert "--noise Fx_N: -1 is outside the allowed range (0, 1e+06] N" in bad.stderr, bad.stderr
    with pytest.raises(ValueError, match=r"noise.Fx_N: -1 is outside the allowed range \(0, "):
        ts.run("validation", "hit-lss1", "ding2011-smooth", experiments=test, calibrate=True,
               noise={"Fx_N": -1})


def test_identify_gives_the_same_numbers_on_two_threads():
    # Issue 25, item 7: the global search shared among threads (identify --threads): the same
    # parameters, std and flags, bit for bit; a count out of range is a ValueError naming it.
    settings = dict(noise_percent=1.0, slip_count=31, loads_N=[30.0, 60.0, 90.0], jmax_m=0.02)
    one = ts.identify(None, WHEEL, SOIL, **settings)
    two = ts.identify(None, WHEEL, SOIL, threads=2, **settings)
    assert one["usable"] and two["usable"]
    assert one["parameters"] == two["parameters"]
    assert one["flags"] == two["flags"]
    assert one["covariance"] == two["covariance"]
    with pytest.raises(ValueError, match=r"threads: -1 is outside the allowed range \[0, 64\]"):
        ts.identify(None, WHEEL, SOIL, threads=-1, **settings)


def test_identify_bad_data():
    with pytest.raises(ValueError, match="slip"):
        ts.identify({"slip": [0.1, 3.0], "entry_angle_deg": [20, 20], "Fx_N": [1, 2],
                     "Fz_N": [50, 50], "My_Nm": [1, 1]}, WHEEL)


def test_simulate_a_preset_scenario():
    out = ts.simulate("pulse-steering", duration_s=1.0)
    assert out["status"] == "completed", out["message"]
    t = out["timeseries"]
    assert t["t_s"][-1] == pytest.approx(1.0, abs=0.05)
    assert isinstance(out["summary"], dict)
    with pytest.raises(ValueError, match="scenario"):
        ts.simulate("no-such-scenario")


def test_run_lists_and_runs_the_registry():
    assert "forces" in ts.analyses() and "soil-curves" in ts.analyses()
    out = ts.run("soil-curves", SOIL, WHEEL)
    assert out["status"] == "completed" and out["tables"]
    with pytest.raises(ValueError, match='did you mean "forces"'):
        ts.run("forcse")
