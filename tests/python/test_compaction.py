"""ts.compaction: the JSON of `terrastudio compaction --json`, and broadcasting over arrays."""

import json

import numpy as np
import pytest

import terrastudio as ts


def test_scalars_give_the_command_lines_json(cli):
    out = ts.compaction("sandy-loam", "A", load_N=120.0, slip=0.2, profile="loam-moist",
                        passes=2)
    run = cli("compaction", "--soil", "sandy-loam", "--wheel", "A", "--load", 120, "--slip", 0.2,
              "--profile", "loam-moist", "--passes", 2, "--json")
    assert run.returncode == 0, run.stderr
    expected = json.loads(run.stdout)
    assert [p["sinkage_m"] for p in out["passes"]] == [p["sinkage_m"] for p in expected["passes"]]
    assert [r["sigma_z_kPa"] for r in out["profile"]] == \
        [r["sigma_z_kPa"] for r in expected["profile"]]
    assert [r["risk"] for r in out["profile"]] == [r["risk"] for r in expected["profile"]]
    assert out["red_to_depth_m"] == expected["red_to_depth_m"]


def test_the_dict_is_the_command_lines_json_key_by_key(cli):
    # Issue 26: one toJson in core; Python returns what `compaction --json` prints, every key.
    out = ts.compaction("sandy-loam", "B", load_N=800.0, slip=0.2, profile="clay-wet", passes=2,
                        depths_m=[0.1, 0.2, 0.4])
    run = cli("compaction", "--soil", "sandy-loam", "--wheel", "B", "--load", 800, "--slip", 0.2,
              "--profile", "clay-wet", "--passes", 2, "--depths", "0.1,0.2,0.4", "--json")
    assert run.returncode == 0, run.stderr
    assert out == json.loads(run.stdout)
    assert out["status"] == "completed"


def test_arrays_broadcast_and_each_element_is_its_own_run():
    loads = np.array([60.0, 120.0, 240.0])
    out = ts.compaction("sandy-loam", "A", load_N=loads[:, None], slip=np.array([0.1, 0.3]),
                        profile="clay-wet", depth_m=0.25)
    assert out["sigma_z_kPa"].shape == (3, 2)
    # The stress at 0.25 m grows with the load at each slip.
    assert np.all(np.diff(out["sigma_z_kPa"], axis=0) > 0)
    # 0.25 m is one of the default depths: a scalar run has the same row.
    single = ts.compaction("sandy-loam", "A", load_N=240.0, slip=0.3, profile="clay-wet")
    row = [r for r in single["profile"] if abs(r["depth_m"] - 0.25) < 1e-12][0]
    assert out["sigma_z_kPa"][2, 1] == row["sigma_z_kPa"]
    assert np.all(out["ok"])


def test_without_a_profile_there_is_no_risk():
    out = ts.compaction("sandy-loam", "A", load_N=[60.0, 90.0])
    assert np.all(np.isnan(out["red_to_depth_m"]))
    assert "risk" not in out["results"][0]["profile"][0]


def test_bad_settings_raise_with_the_field():
    with pytest.raises(ValueError, match="passes"):
        ts.compaction("sandy-loam", "A", passes=0)
    with pytest.raises(ValueError, match="clay_kg_kg"):
        ts.compaction("sandy-loam", "A", profile={
            "name": "x", "layers": [{"top_m": 0, "bottom_m": 1, "clay_kg_kg": 30,
                                     "matric_suction_hPa": 100, "bulk_density_Mg_m3": 1.4}]})


def test_sobol_on_the_compaction_outputs_is_the_command_lines(cli):
    parameters = {"n": (0.5, 1.0), "kphi": (800.0, 2000.0)}
    out = ts.sobol("sandy-loam", "B", parameters, slip=0.2, load_N=800.0,
                   outputs=["rut_depth_m", "red_to_depth_m"], samples=64,
                   compaction={"passes": 2, "profile": "clay-wet"})
    run = cli("gsa", "--soil", "sandy-loam", "--wheel", "B", "--load", 800, "--slip", 0.2,
              "--param", "n=0.5:1.0", "--param", "kphi=800:2000", "--samples", 64,
              "--outputs", "rut_depth_m,red_to_depth_m", "--passes", 2, "--profile", "clay-wet",
              "--json")
    assert run.returncode == 0, run.stderr
    expected = json.loads(run.stdout)
    for output in ("rut_depth_m", "red_to_depth_m"):
        assert out["ST"][output][:, 0].tolist() == [row[0] for row in expected["ST"][output]]
    # The sinkage exponent drives the rut.
    assert out["ST"]["rut_depth_m"][0, 0] > out["ST"]["rut_depth_m"][1, 0]
