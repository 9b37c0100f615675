"""A mission scenario (docs/field.md, "Missions") runs from Python as from the command line."""

import math

import numpy as np

import terrastudio as ts


def test_a_mission_runs_from_python():
    # The shipped controlled-traffic mission, its first 12 s: the robot is still in its first lane.
    out = ts.simulate("mission-controlled-traffic", duration_s=12.0)
    assert out["status"] == "completed", out["message"]
    summary = out["summary"]
    assert summary["mission_completed"] is False  # the duration ran out first
    assert summary["mission_time_s"] is None
    # Two 16 m lanes joined by a half circle of 1.5 m (M6; its chords 0.5 mm shorter).
    assert math.isclose(summary["path_length_m"], 32.0 + math.pi * 1.5, abs_tol=1e-3)
    assert 5.0 < summary["path_progress_m"] < 16.0
    series = out["timeseries"]
    # The time series carries the path columns: still on the lane at y = 0.3 m, heading +x.
    assert np.all(np.abs(series["path_error_m"]) < 0.02)
    assert np.all(np.abs(series["y_m"] - 0.3) < 0.02)
    assert abs(series["path_s_m"][-1] - summary["path_progress_m"]) < 0.01
