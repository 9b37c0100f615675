"""Sobol' indices and Morris screening from Python: the core's estimator on a function with
known indices, and the wheel study against an estimate computed here from ts.forces."""

import json
import math

import numpy as np
import pytest
import terrastudio as ts

SOIL, WHEEL = "sandy-loam", "A"


def ishigami(x, a=7.0, b=0.1):
    return np.sin(x[:, 0]) + a * np.sin(x[:, 1]) ** 2 + b * x[:, 2] ** 4 * np.sin(x[:, 0])


def test_ishigami_indices_within_their_confidence_intervals():
    # Exact indices of Ishigami (a = 7, b = 0.1; Saltelli et al. 2008, section 4.7).
    a, b = 7.0, 0.1
    v1 = 0.5 * (1 + b * math.pi**4 / 5) ** 2
    v2 = a**2 / 8
    v13 = b**2 * math.pi**8 * (1 / 18 - 1 / 50)
    v = v1 + v2 + v13
    s1 = np.array([v1 / v, v2 / v, 0.0])
    st = np.array([(v1 + v13) / v, v2 / v, v13 / v])
    pi = math.pi
    parameters = {"x1": (-pi, pi), "x2": (-pi, pi), "x3": (-pi, pi)}
    samples = 4096
    x = ts.sobol_design(parameters, samples, seed=3)
    assert x.shape == (samples * 5, 3)
    r = ts.sobol_indices(parameters, ishigami(x), samples=samples, seed=3)
    assert r["parameters"] == ["x1", "x2", "x3"]
    for estimate, conf, exact in ((r["S1"][:, 0], r["S1_conf"][:, 0], s1),
                                  (r["ST"][:, 0], r["ST_conf"][:, 0], st)):
        assert np.all(conf > 0) and np.all(conf < 0.1)
        assert np.all(np.abs(estimate - exact) <= conf), (estimate, conf, exact)


def saltelli_estimate(y, samples, d):
    """First-order (Saltelli 2010) and total (Jansen 1999) indices from a design's outputs in
    row order A_j, B_j, AB_1,j … AB_d,j, as docs/sensitivity.md writes them: f_B centred on the
    mean m of the A and B outputs, V their variance (over 2N values)."""
    y = y.reshape(samples, d + 2)
    fa, fb, fab = y[:, 0], y[:, 1], y[:, 2:]
    both = np.concatenate([fa, fb])
    m, var = both.mean(), both.var()
    s1 = np.mean((fb - m)[:, None] * (fab - fa[:, None]), axis=0) / var
    st = 0.5 * np.mean((fa[:, None] - fab) ** 2, axis=0) / var
    return s1, st


def test_wheel_indices_equal_an_estimate_from_forces_with_per_sample_overrides():
    parameters = {"phi_deg": (22.0, 34.0), "K_m": (0.008, 0.035), "n": (0.6, 1.0)}
    slips = [0.15, 0.5]
    samples = 128
    res = ts.sobol(SOIL, WHEEL, parameters, slip=slips, load_N=58.86,
                   outputs=["Fx_N", "sinkage_m"], samples=samples, seed=7, resamples=200)
    assert res["parameters"] == list(parameters)
    assert res["S1"]["Fx_N"].shape == (3, 2)
    assert res["dropped"] == [0, 0]
    x = ts.sobol_design(parameters, samples, seed=7)
    for p, s in enumerate(slips):
        out = ts.forces(SOIL, WHEEL, slip=s, load_N=58.86, phi_deg=x[:, 0], K_m=x[:, 1],
                        n=x[:, 2])
        assert out["ok"].all()
        for name in ("Fx_N", "sinkage_m"):
            s1, st = saltelli_estimate(out[name], samples, 3)
            np.testing.assert_allclose(res["S1"][name][:, p], s1, rtol=1e-9, atol=1e-12)
            np.testing.assert_allclose(res["ST"][name][:, p], st, rtol=1e-9, atol=1e-12)
    # Sinkage is set by the pressure-sinkage law: n and K (shear) should rank as the physics says,
    # n (Eq. 2.3) far above K (which enters only through the slip sinkage of the shear).
    assert res["ST"]["sinkage_m"][2, 0] > res["ST"]["sinkage_m"][1, 0]


def test_slip_angle_list_adds_an_axis():
    res = ts.sobol(SOIL, WHEEL, {"phi_deg": (25, 32), "c_kPa": (0.5, 3)}, slip=[0.2, 0.4, 0.6],
                   slip_angle_deg=[0.0, 10.0], entry_angle_deg=25.0, outputs="Fs_N",
                   samples=32, resamples=0)
    assert res["S1"]["Fs_N"].shape == (2, 2, 3)
    assert res["slip_angle_deg"] == [0.0, 10.0]


def test_morris_ranks_like_sobol():
    parameters = {"phi_deg": (20.0, 35.0), "c_kPa": (0.0, 5.0), "gamma_kN_m3": (14.0, 16.0)}
    res = ts.morris(SOIL, WHEEL, parameters, slip=[0.3], entry_angle_deg=25.0, trajectories=40,
                    resamples=100)
    mu_star = res["mu_star"]["Fx_N"][:, 0]
    # F_x barely depends on γ (bulldozing only); φ and c set the shear strength (Eq. 2.21).
    assert mu_star[2] < 0.1 * min(mu_star[0], mu_star[1])
    assert np.all(res["sigma"]["Fx_N"] >= 0)


def test_study_errors_are_value_errors_with_the_field():
    with pytest.raises(ValueError, match="phi_deg"):
        ts.sobol(SOIL, WHEEL, {"phi_deg": (20, 95)}, samples=16)
    with pytest.raises(ValueError, match="not a soil field"):
        ts.sobol(SOIL, WHEEL, {"phii": (20, 30)}, samples=16)
    with pytest.raises(ValueError, match='did you mean "Fx_N"'):
        ts.sobol(SOIL, WHEEL, {"phi_deg": (20, 30)}, outputs=["Fx"], samples=16)
    with pytest.raises(ValueError, match="samples"):
        ts.sobol(SOIL, WHEEL, {"phi_deg": (20, 30)}, samples=1)
    with pytest.raises(ValueError):
        ts.morris(SOIL, WHEEL, {"phi_deg": {"normal": [28, 2]}}, trajectories=4)


def test_correlated_parameters():
    res = ts.sobol(SOIL, WHEEL, {"c_kPa": (1.0, 2.0)}, slip=[0.3], entry_angle_deg=25.0,
                   correlated={"keys": ["phi_deg", "K_m"], "mean": [29.0, 0.025],
                               "covariance": [[1.0, 0.001], [0.001, 1e-5]]},
                   samples=64, resamples=0)
    assert res["parameters"] == ["c_kPa", "phi_deg", "K_m"]


def test_a_saved_posterior_is_the_command_lines_correlated_group(tmp_path, cli):
    # `identify --save-soil` writes the posterior in the identification's names; ts.sobol(posterior=)
    # reads them as soil keys and samples it
    # as `gsa --posterior` does: the same indices.
    data, soil = tmp_path / "data.csv", tmp_path / "identified.json"
    made = cli("synth", "--soil", SOIL, "--wheel", WHEEL, "--load", "30,58.86,90", "--slips",
               "0.05:0.85:15", "--noise", "fx=1%,fz=1%,my=1%", "--out", data)
    assert made.returncode == 0, made.stderr
    fit = cli("identify", "--data", data, "--wheel", WHEEL, "--jmax", "0.02", "--save-soil", soil)
    assert fit.returncode == 0, fit.stderr
    res = ts.sobol(soil, WHEEL, {}, slip=[0.3], samples=64, resamples=0, posterior=soil,
                   model="quadratic")
    assert res["parameters"] == ["a0", "a1", "kphi", "n", "c_kPa", "phi_deg", "K_m"]
    run = cli("gsa", "--posterior", soil, "--wheel", WHEEL, "--slip", 0.3, "--samples", 64,
              "--resamples", 0, "--model", "quadratic", "--json")
    assert run.returncode == 0, run.stderr
    expected = json.loads(run.stdout)
    np.testing.assert_allclose(res["S1"]["Fx_N"], np.array(expected["S1"]["Fx_N"]), rtol=1e-12)
    with open(soil) as f:
        document = json.load(f)
    again = ts.sobol(soil, WHEEL, {}, slip=[0.3], samples=64, resamples=0,
                     posterior=document["posterior"], model="quadratic")
    np.testing.assert_array_equal(again["S1"]["Fx_N"], res["S1"]["Fx_N"])
    with pytest.raises(ValueError, match="phi_deg is varied twice"):
        ts.sobol(soil, WHEEL, {"phi_deg": (20, 30)}, posterior=soil, samples=8)
    with pytest.raises(ValueError, match="not both"):
        ts.sobol(soil, WHEEL, {}, posterior=soil, correlated=res, samples=8)
