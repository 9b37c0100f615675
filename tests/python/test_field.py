"""ts.field: the command line's summary and traversability, the maps as arrays."""

import json
import math
import os

import numpy as np
import pytest

import terrastudio as ts


def test_the_summary_is_the_command_lines(cli, resources):
    path = os.path.join(resources, "fields", "sloped-wet", "field.json")
    out = ts.field(path)
    run = cli("field", path, "--json")
    assert run.returncode == 0, run.stderr
    assert out == json.loads(run.stdout)


def test_traversability_maps(cli, resources, tmp_path):
    path = os.path.join(resources, "fields", "sloped-wet", "field.json")
    out = ts.field(path, traversability={"robot": "wheel-b", "headings": 4, "cell_m": 2.0})
    t = out["traversability"]
    assert len(t["slip"]) == 4 and t["slip"][0].shape == (20, 30)
    assert t["x_m"][0] == 1.0 and t["y_m"][0] == 39.0  # the northern row first
    # The counts of the JSON are the maps' statuses.
    for h, heading in enumerate(t["headings"]):
        assert heading["stalled"] == int(np.sum(t["status"][h] == 1))
        assert heading["braking"] == int(np.sum(t["status"][h] == 2))
    # On the plane (8 % along x, 3 % across; away from the hollow) uphill (heading 0) needs more
    # slip than across (heading 90).
    plane_deg = math.degrees(math.atan(math.hypot(0.08, 0.03)))
    on_plane = np.abs(t["slope_deg"] - plane_deg) < 0.01
    both = on_plane & np.isfinite(t["slip"][0]) & np.isfinite(t["slip"][1])
    assert np.sum(both) > 300
    assert np.all(t["slip"][0][both] >= t["slip"][1][both])
    run = cli("field", path, "--robot", "wheel-b", "--headings", 4, "--cell", 2,
              "--traversability", tmp_path / "t.csv", "--json")
    assert run.returncode == 0, run.stderr
    expected = json.loads(run.stdout)["traversability"]
    assert {k: t[k] for k in expected} == expected


def test_bad_settings_name_the_field(resources):
    path = os.path.join(resources, "fields", "sloped-wet", "field.json")
    with pytest.raises(ValueError, match="headings"):
        ts.field(path, traversability={"headings": 0})
    with pytest.raises(ValueError, match="nowhere"):
        ts.field("nowhere.json")
    assert math.isfinite(ts.field(path)["max_slope_deg"])
