"""Studies of many missions (docs/field.md, "Mission studies"): the overrides against plain runs,
the drawn cases against their distributions, and the errors naming what is wrong."""

import math

import numpy as np
import pytest
import terrastudio as ts

FIELD = "field-slope-wet"
SHORT = dict(duration_s=4.0, model="quadratic")


def test_the_scenarios_own_soils_as_overrides_give_the_plain_run_bit_for_bit():
    # Soil -> dict -> the rover's reader must give back the same doubles: the case that names
    # every soil as the scenario has it is the run without overrides.
    soils = ts.scenario_soils(FIELD)
    assert set(soils) == {"base", "1", "2", "3"}
    [plain, same] = ts.mission_study(FIELD, [{}, {"soils": soils}], **SHORT)
    assert plain["status"] == "completed", plain["message"]
    assert same == plain
    # And as simulate() gives it (its summary without the measured speed).
    summary = dict(ts.simulate(FIELD, **SHORT)["summary"])
    for key in ("x_m", "y_m", "energy_J", "max_rut_depth_m", "cells_touched"):
        assert plain[key] == summary[key], key


def test_a_heavier_robot_sinks_deeper_and_threads_do_not_change_the_numbers():
    cases = [{"chassis_mass_kg": m} for m in (12.0, 20.0, 40.0)]
    serial = ts.mission_study("straight", cases, duration_s=2.0)
    parallel = ts.mission_study("straight", cases, threads=2, duration_s=2.0)
    assert parallel == serial
    sinkage = [row["max_sinkage_m"] for row in serial]
    assert sinkage[0] < sinkage[1] < sinkage[2]
    # Bekker's pressure-sinkage law (thesis Eq. 2.3) grows as W^(1/(n+1/2)) or so: doubling the
    # load must deepen the rut by clearly less than double and clearly more than nothing.
    ratio = sinkage[2] / sinkage[1]
    assert 1.2 < ratio < 2.0, ratio


def test_drawn_cases_follow_their_distributions_and_repeat_with_the_seed():
    nominal = ts.scenario_soils(FIELD)
    cases = ts.mission_cases(FIELD, 400, soil_spread={"phi_deg": 2.0}, chassis_mass_kg=(18, 26),
                             wheels=["A", "B"], seed=11)
    assert cases == ts.mission_cases(FIELD, 400, soil_spread={"phi_deg": 2.0},
                                     chassis_mass_kg=(18, 26), wheels=["A", "B"], seed=11)
    assert cases != ts.mission_cases(FIELD, 400, soil_spread={"phi_deg": 2.0},
                                     chassis_mass_kg=(18, 26), wheels=["A", "B"], seed=12)
    phi = np.array([c["soils"]["2"]["phi_deg"] for c in cases])
    centre = nominal["2"]["phi_deg"]
    assert abs(phi.mean() - centre) < 4 * 2.0 / math.sqrt(len(phi))
    assert abs(phi.std() - 2.0) < 0.25
    # The other fields are the soil's own; each class drawn independently.
    assert all(c["soils"]["2"]["c_kPa"] == nominal["2"]["c_kPa"] for c in cases)
    assert np.corrcoef(phi, [c["soils"]["1"]["phi_deg"] for c in cases])[0, 1] < 0.2
    masses = np.array([c["chassis_mass_kg"] for c in cases])
    assert masses.min() >= 18 and masses.max() <= 26 and abs(masses.mean() - 22) < 0.4
    radii = {c["wheel"]["r_m"] for c in cases}
    assert radii == {ts.wheel("A").to_dict()["r_m"], ts.wheel("B").to_dict()["r_m"]}


def test_cases_drawn_from_a_posterior_keep_its_mean_and_correlations():
    # An identification's posterior (identify --save-soil's form, in its names: Ks_kPa is the
    # soil's kphi with kc = 0) for the wet hollow's class: the drawn soils' sample mean and
    # covariance are the posterior's, against numpy's own statistics of the draws.
    mean = [25.0, 1.2, 800.0]
    std = np.array([2.0, 0.3, 60.0])
    corr = np.array([[1.0, -0.8, 0.3], [-0.8, 1.0, 0.0], [0.3, 0.0, 1.0]])
    cov = (corr * np.outer(std, std)).tolist()
    posterior = {"posterior": {"parameters": ["phi_deg", "c_kPa", "Ks_kPa"], "mean": mean,
                               "covariance": cov}}
    nominal = ts.scenario_soils(FIELD)
    cases = ts.mission_cases(FIELD, 2000, posterior={2: posterior}, seed=3)
    assert cases == ts.mission_cases(FIELD, 2000, posterior={"2": posterior}, seed=3)
    assert set(cases[0]["soils"]) == {"2"}  # the other soils are the scenario's own
    x = np.array([[c["soils"]["2"][k] for k in ("phi_deg", "c_kPa", "kphi")] for c in cases])
    n = len(x)
    assert np.all(np.abs(x.mean(axis=0) - mean) < 4 * std / math.sqrt(n))
    assert np.allclose(x.std(axis=0), std, rtol=0.06)
    r = np.corrcoef(x.T)
    assert abs(r[0, 1] + 0.8) < 0.03 and abs(r[0, 2] - 0.3) < 0.06 and abs(r[1, 2]) < 0.06
    assert all(c["soils"]["2"]["kc"] == 0.0 for c in cases)
    assert all(c["soils"]["2"]["K_m"] == nominal["2"]["K_m"] for c in cases)
    # One drawn case runs.
    [row] = ts.mission_study(FIELD, cases[:1], **SHORT)
    assert row["status"] == "completed", row["message"]
    with pytest.raises(ValueError, match=r"posterior\.9"):
        ts.mission_cases(FIELD, 2, posterior={9: posterior})
    with pytest.raises(ValueError, match="varied twice"):
        ts.mission_cases(FIELD, 2, posterior={2: posterior}, soil_spread={"phi_deg": 1.0})
    bad = {"parameters": ["phi_deg"], "mean": [25.0], "covariance": [[-1.0]]}
    with pytest.raises(ValueError, match="positive definite"):
        ts.mission_cases(FIELD, 2, posterior={2: bad})


def test_bad_cases_name_the_key():
    with pytest.raises(ValueError, match=r"soils\.7"):
        ts.mission_study(FIELD, [{"soils": {7: "sandy-loam"}}], **SHORT)
    with pytest.raises(ValueError, match="chassis_mass_kg"):
        ts.mission_study(FIELD, [{"chassis_mass_kg": -1.0}], **SHORT)
    with pytest.raises(ValueError, match=r"cases\[1\]"):
        ts.mission_study(FIELD, [{}, 3], **SHORT)
    with pytest.raises(ValueError, match="soil_spread"):
        ts.mission_cases(FIELD, 2, soil_spread={"phi": 1.0})
    with pytest.raises(ValueError, match="samples"):
        ts.mission_cases(FIELD, 0)


def test_the_example_of_docs_field_md_runs(resources, capsys):
    # docs/field.md, "Mission studies": the example block after its marker, run as shown.
    import os
    import re

    page = open(os.path.join(resources, "..", "docs", "field.md"), encoding="utf-8").read()
    marker = r"<!-- python example \"mission-study\"[^>]*-->\n```python\n(.*?)```"
    match = re.search(marker, page, re.S)
    assert match, "the example block of docs/field.md is missing"
    exec(compile(match.group(1), "docs/field.md", "exec"), {})
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 4
    assert all(" kg  wheel r = " in line and " J/m  rut " in line for line in lines)


def test_simulate_takes_soil_and_wheel_objects():
    wheel = ts.wheel("B")
    out = ts.simulate("straight", duration_s=1.0, wheel=wheel, soils={"base": ts.soil("clayey-soil")})
    assert out["status"] == "completed", out["message"]
    # The same run with the overrides by preset name.
    again = ts.simulate("straight", duration_s=1.0, wheel="B", soils={"base": "clayey-soil"})
    assert again["summary"]["x_m"] == out["summary"]["x_m"]
    plain = ts.simulate("straight", duration_s=1.0)
    assert plain["summary"]["x_m"] != out["summary"]["x_m"]
