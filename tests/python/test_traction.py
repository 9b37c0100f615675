"""ts.traction: the command line's JSON, and the posterior's robust slip."""

import json

import pytest

import terrastudio as ts


def test_the_best_slip_is_the_command_lines(cli):
    out = ts.traction("sandy-loam", "A", load_N=70.0, objective="efficiency")
    run = cli("traction", "--soil", "sandy-loam", "--wheel", "A", "--load", 70, "--json")
    assert run.returncode == 0, run.stderr
    expected = json.loads(run.stdout)
    assert out["optimal_slip"] == expected["optimal_slip"]
    assert [p["efficiency"] for p in out["curve"]] == [p["efficiency"] for p in expected["curve"]]
    # eta at s* from its own forces.
    assert out["efficiency"] == pytest.approx(
        out["Fx_N"] * ts.wheel("A").r_m * (1 - out["optimal_slip"]) / out["My_Nm"], rel=1e-12)


def test_the_dict_is_the_command_lines_json_key_by_key(tmp_path, cli):
    # Issue 26: one toJson in core; Python returns what `traction --json` prints, every key
    # (the status and the notes too), with a posterior.
    soil = tmp_path / "identified.json"
    soil.write_text(json.dumps({"posterior": {"parameters": ["phi_deg", "n"], "mean": [29.0, 0.7],
                                              "covariance": [[4.0, -0.05], [-0.05, 0.0025]]}}))
    out = ts.traction("sandy-loam", "B", load_N=400.0, posterior=soil, posterior_samples=20,
                      curve_points=12, model="quadratic")
    run = cli("traction", "--soil", "sandy-loam", "--wheel", "B", "--load", 400, "--posterior",
              soil, "--samples", 20, "--points", 12, "--model", "quadratic", "--json")
    assert run.returncode == 0, run.stderr
    assert out == json.loads(run.stdout)
    assert out["status"] == "completed"


def test_a_posterior_file_gives_a_robust_slip(tmp_path, cli):
    soil = tmp_path / "identified.json"
    soil.write_text(json.dumps({"posterior": {"parameters": ["phi_deg", "n"], "mean": [29.0, 0.7],
                                              "covariance": [[4.0, -0.05], [-0.05, 0.0025]]}}))
    out = ts.traction("sandy-loam", "A", posterior=soil, posterior_samples=50, model="quadratic")
    assert 0.0 < out["robust_slip"] < 1.0
    assert out["robust_value"] <= max(b["p50"] for b in out["band"] if b["samples"])
    run = cli("traction", "--posterior", soil, "--samples", 50, "--model", "quadratic", "--json")
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["robust_slip"] == out["robust_slip"]


def test_a_cap_no_slip_meets_raises():
    with pytest.raises(RuntimeError, match="sinkage"):
        ts.traction("sandy-loam", "A", max_sinkage_m=1e-4)


def test_an_unknown_scenario_is_named_once():
    with pytest.raises(ValueError) as e:
        ts.compare_controllers("no-such-scenario")
    assert "'no-such-scenario' is neither a file nor a scenario" in str(e.value)
    assert "scenario: scenario:" not in str(e.value)


def test_a_non_finite_number_is_named_by_its_key():
    # As the command line words it, not the JSON parser's error (NaN is not JSON).
    with pytest.raises(ValueError, match="load_N: nan is not a finite number"):
        ts.traction("sandy-loam", "A", load_N=float("nan"))


def test_simulate_takes_a_controller_and_the_summary_has_its_metrics():
    fixed = ts.simulate("traction-load-change", duration_s=4.0, controller="fixed-slip", slip=0.2)
    assert fixed["status"] == "completed"
    summary = fixed["summary"]
    # The set-point of every wheel is the one asked for, all along.
    for wheel in ("FL", "FR", "RL", "RR"):
        assert set(fixed["timeseries"][wheel + "_slip_set"]) == {0.2}
    assert summary["slip_tracking_rms"] > 0.0
    assert summary["energy_per_m_J"] == pytest.approx(summary["energy_J"] / summary["distance_m"])
    plain = ts.simulate("traction-load-change", duration_s=4.0, controller="constant-speed")
    assert plain["summary"]["slip_tracking_rms"] is None
    assert "FL_slip_set" not in plain["timeseries"]


def test_simulate_takes_the_traction_limited_mode():
    # Up the slope the fixed set-point 0.45 stalls at the floor; traction-limited, the set-point
    # is raised above it once the stall is confirmed (docs/traction.md section 5).
    limited = ts.simulate("traction-slope", duration_s=15.0, controller="fixed-slip",
                          traction_limited=True)
    assert limited["status"] == "completed"
    assert limited["summary"]["traction_limited_switches"] == 1
    assert max(limited["timeseries"]["FL_slip_set"]) > 0.5
    plain = ts.simulate("traction-slope", duration_s=15.0, controller="fixed-slip",
                        traction_limited=False)
    assert "traction_limited_switches" not in plain["summary"]
    assert set(plain["timeseries"]["FL_slip_set"]) == {0.45}
    with pytest.raises(ValueError, match="traction_limited"):
        ts.simulate("traction-slope", duration_s=1.0, traction_limited="yes")


def test_compare_controllers_is_the_command_lines_table(cli, tmp_path):
    rows = ts.compare_controllers("traction-load-change", duration_s=2.0)
    assert [r["controller"] for r in rows] == ["constant-speed", "fixed-slip", "optimal", "oracle"]
    assert all(r["status"] == "completed" for r in rows)
    run = cli("simulate", "--scenario", "traction-load-change", "--duration", 2, "--compare",
              "--json", "--out", tmp_path)
    assert run.returncode == 0, run.stderr
    assert rows == json.loads(run.stdout)
    # One row against a run of its own: the energy per metre of that controller's summary.
    fixed = ts.simulate("traction-load-change", duration_s=2.0, controller="fixed-slip")
    assert rows[1]["energy_per_m_J"] == fixed["summary"]["energy_per_m_J"]
    assert rows[1]["distance_m"] == fixed["summary"]["distance_m"]
    with pytest.raises(ValueError, match="controller"):
        ts.compare_controllers("traction-load-change", controller="oracle")


def test_simulate_takes_the_robust_set_point_and_the_soil_estimator(cli, tmp_path):
    # The optimal controller's robust keys (docs/traction.md section 8) as the scenario's
    # controller object and simulate's flags take them: the same run byte for byte.
    robust = ts.simulate("traction-border", duration_s=7.0, controller="optimal",
                         robust="quantile", quantile=0.2, posterior_method="sigma-points")
    assert robust["status"] == "completed"
    run = cli("simulate", "--scenario", "traction-border", "--duration", 7, "--controller",
              "optimal", "--robust", "quantile", "--quantile", 0.2, "--posterior-method",
              "sigma-points", "--out", tmp_path)
    assert run.returncode == 0, run.stderr
    with open(tmp_path / "timeseries.csv") as f:
        header = f.readline().strip().split(",")
        plans = [float(line.split(",")[header.index("FL_slip_plan")]) for line in f]
    assert plans == pytest.approx(list(robust["timeseries"]["FL_slip_plan"]), abs=1e-12)
    # Planned on the posterior: other set-points than the point estimate's once planned.
    point = ts.simulate("traction-border", duration_s=7.0, controller="optimal", robust="none")
    assert list(point["timeseries"]["FL_slip_plan"]) != list(robust["timeseries"]["FL_slip_plan"])
    # The full-model estimator: its streaming table carries the normalised innovation.
    full = ts.simulate("traction-border", duration_s=4.0, controller="optimal", identifier="full")
    assert full["status"] == "completed"
    assert "nis" in full["streaming"] and "residual_score" not in full["streaming"]
    with pytest.raises(ValueError, match="quantile"):
        ts.simulate("traction-border", duration_s=1.0, quantile=1.5)
    with pytest.raises(ValueError, match="identifier"):
        ts.simulate("traction-border", duration_s=1.0, identifier="kalman")
