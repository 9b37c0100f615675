"""terrastudio.forces against the command line's batch mode, soil files and itself."""

import csv
import json
import threading
import time

import numpy as np
import pytest
import terrastudio as ts

SOIL, WHEEL = "sandy-loam", "A"


def cli_batch(cli, tmp_path, header, rows, *flags):
    points = tmp_path / "points.csv"
    with open(points, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    out = tmp_path / "out.csv"
    run = cli("wheel", "--soil", SOIL, "--wheel", WHEEL, "--input", points, "--output", out, *flags)
    assert run.returncode == 0, run.stderr
    with open(out) as f:
        return list(csv.DictReader(f))


OUTPUTS = ("Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm", "Mz_Nm", "Fb_N", "Fs_N", "sinkage_m")


def test_matches_the_cli_batch_with_the_load_given(cli, tmp_path):
    # The CLI solves each row through analysis::evaluatePoint, the module through the batch of
    # core/gsa: both start the entry-angle solve cold, so the numbers agree to the last digit the
    # CLI prints (shortest round trip), up to the solver's own tolerance.
    slips = np.array([0.0, 0.05, 0.2, 0.35, 0.6, 0.9, -0.3])
    betas = np.array([0.0, 5.0, 10.0, 0.0, 20.0, 30.0, 15.0])
    loads = np.array([58.86, 40.0, 58.86, 80.0, 58.86, 30.0, 58.86])
    rows = cli_batch(cli, tmp_path, ["slip", "slip_angle_deg", "load_N"],
                     zip(slips, betas, loads))
    out = ts.forces(SOIL, WHEEL, slip=slips, slip_angle_deg=betas, load_N=loads)
    assert out["ok"].all()
    assert [r["status"] for r in rows] == ["ok"] * len(rows)
    for name in OUTPUTS:
        expected = np.array([float(r[name]) for r in rows])
        np.testing.assert_allclose(out[name], expected, rtol=1e-9, atol=1e-9, err_msg=name)
    expected = np.array([float(r["entry_angle_deg_out"]) for r in rows])
    np.testing.assert_allclose(out["entry_angle_deg"], expected, rtol=1e-9)


def test_matches_the_cli_batch_with_the_entry_angle_given(cli, tmp_path):
    slips = np.linspace(-0.5, 0.95, 9)
    thetas = np.linspace(5.0, 45.0, 9)
    rows = cli_batch(cli, tmp_path, ["slip", "entry_angle_deg"], zip(slips, thetas),
                     "--slip-angle", "7.5")
    out = ts.forces(SOIL, WHEEL, slip=slips, slip_angle_deg=7.5, entry_angle_deg=thetas)
    for name in OUTPUTS:
        expected = np.array([float(r[name]) for r in rows])
        # θ_f given: the same formulas on the same doubles; the CLI prints the shortest text that
        # reads back as the same double.
        np.testing.assert_array_equal(out[name], expected, err_msg=name)


def test_no_equilibrium_is_flagged_not_raised(cli, tmp_path):
    out = ts.forces(SOIL, WHEEL, slip=[0.2, 0.2], load_N=[58.86, 5000.0])
    assert out["ok"].tolist() == [True, False]
    assert ts.STATUS[out["status"][1]] == "no equilibrium"
    assert np.isnan(out["Fx_N"][1]) and np.isfinite(out["Fx_N"][0])
    rows = cli_batch(cli, tmp_path, ["slip", "load_N"], [(0.2, 5000.0)])
    assert rows[0]["status"] == "no-equilibrium"


def test_overrides_equal_soil_files(tmp_path):
    # Per-sample fields in file units give what a soil file with those values gives.
    phi = np.array([22.0, 27.5, 33.0])
    k = np.array([0.01, 0.02, 0.035])
    out = ts.forces(SOIL, WHEEL, slip=0.3, load_N=58.86, phi_deg=phi, K_m=k)
    base = ts.soil(SOIL).to_dict()
    for i in range(3):
        path = tmp_path / f"soil{i}.json"
        path.write_text(json.dumps({**base, "phi_deg": phi[i], "K_m": k[i]}))
        one = ts.forces(str(path), WHEEL, slip=0.3, load_N=58.86)
        for name in OUTPUTS:
            assert one[name] == out[name][i], name


def test_broadcasting_follows_numpy():
    slip = np.linspace(0.05, 0.9, 5)[:, None]
    phi = np.array([25.0, 30.0])[None, :]
    out = ts.forces(SOIL, WHEEL, slip=slip, entry_angle_deg=20.0, phi_deg=phi)
    assert out["Fx_N"].shape == (5, 2) and out["ok"].shape == (5, 2)
    for j in range(2):
        column = ts.forces(SOIL, WHEEL, slip=slip[:, 0], entry_angle_deg=20.0, phi_deg=phi[0, j])
        np.testing.assert_array_equal(out["Fx_N"][:, j], column["Fx_N"])
    scalar = ts.forces(SOIL, WHEEL, slip=0.2, entry_angle_deg=20.0)
    assert scalar["Fx_N"].shape == ()
    with pytest.raises(ValueError, match=r"do not broadcast.*slip \(3,\).*phi_deg \(2,\)"):
        ts.forces(SOIL, WHEEL, slip=[0.1, 0.2, 0.3], entry_angle_deg=20.0, phi_deg=[25.0, 30.0])


def test_threads_do_not_change_the_numbers():
    slip = np.linspace(0.0, 0.9, 200)
    one = ts.forces(SOIL, WHEEL, slip=slip, load_N=58.86, threads=1)
    two = ts.forces(SOIL, WHEEL, slip=slip, load_N=58.86, threads=2)
    for name in OUTPUTS:
        np.testing.assert_array_equal(one[name], two[name])


def test_the_gil_is_released():
    # A Python thread keeps running while the core computes.
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    slip = np.linspace(0.0, 0.9, 20000)
    thread = threading.Thread(target=tick)
    thread.start()
    time.sleep(0.01)
    start = time.perf_counter()
    ts.forces(SOIL, WHEEL, slip=slip, load_N=58.86, threads=1)
    end = time.perf_counter()
    stop.set()
    thread.join()
    during = [t for t in ticks if start < t < end]
    assert end - start > 0.05
    assert len(during) >= 10, (len(during), end - start)


def test_model_options_are_the_clis(cli, tmp_path):
    rows = cli_batch(cli, tmp_path, ["slip", "entry_angle_deg"], [(0.3, 25.0)],
                     "--exit-angle", "-3", "--bulldozing", "hegedus", "--model", "quadratic")
    out = ts.forces(SOIL, WHEEL, slip=0.3, entry_angle_deg=25.0, exit_angle_deg=-3.0,
                    bulldozing="hegedus", model="quadratic")
    for name in OUTPUTS:
        assert out[name] == float(rows[0][name]), name


def test_bad_input_names_the_sample_field_value_and_range():
    with pytest.raises(ValueError, match=r"slip\[1\]: 1.5 is outside the allowed range \[-1, 1\]"):
        ts.forces(SOIL, WHEEL, slip=[0.1, 1.5], load_N=58.86)
    with pytest.raises(ValueError, match=r"phi_deg\[0\]: 75 is outside the allowed range"):
        ts.forces(SOIL, WHEEL, slip=[0.1, 0.2], load_N=58.86, phi_deg=[75.0, 30.0])
    with pytest.raises(ValueError, match="give the load"):
        ts.forces(SOIL, WHEEL, slip=0.1)
    with pytest.raises(ValueError, match="not both"):
        ts.forces(SOIL, WHEEL, slip=0.1, load_N=50.0, entry_angle_deg=20.0)
    with pytest.raises(ValueError, match="phii_deg: is not a soil field"):
        ts.forces(SOIL, WHEEL, slip=0.1, load_N=50.0, phii_deg=20.0)
    with pytest.raises(ValueError, match="bulldozing"):
        ts.forces(SOIL, WHEEL, slip=0.1, load_N=50.0, bulldozing="nope")


def test_invalid_soil_samples_can_be_flagged():
    out = ts.forces(SOIL, WHEEL, slip=0.2, load_N=58.86, phi_deg=[30.0, 75.0],
                    invalid_soil="flag")
    assert out["ok"].tolist() == [True, False]
    assert ts.STATUS[out["status"][1]] == "soil outside its allowed range"


def test_lyasko_slip_sinkage_scales_the_sinkage_only(cli, tmp_path):
    # S of h = h0 (1 + S s) (docs/model.md, Eq. S.1) from the soil's field: with S = 2 the sinkage
    # at s = 0.5 is twice the thesis model's, at s = 0 the same, and no force moves.
    slips = np.array([0.0, 0.5])
    off = ts.forces(SOIL, WHEEL, slip=slips, load_N=58.86)
    on = ts.forces(ts.soil(SOIL, slip_sinkage=2.0), WHEEL, slip=slips, load_N=58.86)
    np.testing.assert_allclose(on["sinkage_m"], off["sinkage_m"] * np.array([1.0, 2.0]),
                               rtol=1e-15)
    for name in ("Fx_N", "Fz_N", "My_Nm", "entry_angle_deg"):
        np.testing.assert_array_equal(on[name], off[name], err_msg=name)
    rows = cli_batch(cli, tmp_path, ["slip", "load_N"], [(0.5, 58.86)], "--set", "slip_sinkage=2")
    np.testing.assert_allclose(float(rows[0]["sinkage_m"]), on["sinkage_m"][1], rtol=1e-9)
    with pytest.raises(ValueError, match=r"slip_sinkage.*12.*allowed range \[0, 10\]"):
        ts.soil(SOIL, slip_sinkage=12.0)
