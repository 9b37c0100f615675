"""Studies on a Dask cluster: a 2-worker LocalCluster gives the local numbers bit for bit."""

import distributed  # Debian's python3-distributed (scripts/deps.sh): a missing one fails the test
import numpy as np
import pytest
import terrastudio as ts

SOIL, WHEEL = "sandy-loam", "A"
PARAMETERS = {"phi_deg": (20.0, 35.0), "c_kPa": (0.0, 5.0), "K_m": (0.005, 0.04),
              "n": (0.5, 1.1)}


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=40)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def assert_same(local, remote, keys):
    for key in keys:
        for output, value in local[key].items():
            np.testing.assert_array_equal(remote[key][output], value, err_msg=f"{key} {output}")
    assert remote["evaluations"] == local["evaluations"]


def test_sobol_on_two_workers_is_bit_identical(client):
    kwargs = dict(slip=[0.1, 0.3, 0.6], load_N=58.86, outputs=["Fx_N", "sinkage_m"],
                  samples=256, seed=1, resamples=200)
    local = ts.sobol(SOIL, WHEEL, PARAMETERS, **kwargs)
    remote = ts.sobol(SOIL, WHEEL, PARAMETERS, client=client, **kwargs)
    assert_same(local, remote, ("S1", "ST", "S1_conf", "ST_conf"))
    # Uneven chunks, a modified soil and a slip angle travel too.
    soil = ts.soil(SOIL, phi_deg=28.123456789)
    kwargs.update(slip_angle_deg=7.0, samples=64)
    local = ts.sobol(soil, WHEEL, PARAMETERS, **kwargs)
    remote = ts.sobol(soil, WHEEL, PARAMETERS, client=client, chunks=5, **kwargs)
    assert_same(local, remote, ("S1", "ST", "S1_conf", "ST_conf"))


def test_morris_on_two_workers_is_bit_identical(client):
    kwargs = dict(slip=[0.2, 0.5], entry_angle_deg=25.0, trajectories=32, resamples=100)
    local = ts.morris(SOIL, WHEEL, PARAMETERS, **kwargs)
    remote = ts.morris(SOIL, WHEEL, PARAMETERS, client=client, **kwargs)
    assert_same(local, remote, ("mu_star", "mu", "sigma", "mu_star_conf"))


def test_chunks_cover_the_rows_in_whole_groups():
    from terrastudio._dask import chunk_bounds

    bounds = chunk_bounds(60, 6, 4)
    assert bounds[0][0] == 0 and bounds[-1][1] == 60
    assert all(b % 6 == 0 and e % 6 == 0 and b < e for b, e in bounds)
    assert all(bounds[i][1] == bounds[i + 1][0] for i in range(len(bounds) - 1))
    assert chunk_bounds(12, 6, 10) == [(0, 6), (6, 12)]


def misaligned(a):
    """A copy of `a` whose data start one byte past an 8-byte boundary, as a numpy array rebuilt
    from a pickle or a byte buffer may (dask's transport)."""
    a = np.ascontiguousarray(a)
    buffer = bytearray(a.nbytes + 1)
    out = np.frombuffer(buffer, dtype=a.dtype, count=a.size, offset=1).reshape(a.shape)
    out[...] = a
    assert not out.flags.aligned or a.dtype.itemsize == 1
    return out


class MisaligningClient:
    """Runs the tasks here, and hands their arrays back misaligned: the bindings must copy such
    arrays before reading them (reading a double at an odd address is undefined behaviour; UBSan
    stopped the ASan run of this file there, docs/reliability.md)."""

    def nthreads(self):
        return {"here": 1}

    def scatter(self, values, broadcast=False):
        return values

    def submit(self, function, *args, pure=True):
        return function(*args)

    def gather(self, parts):
        return [tuple(misaligned(a) for a in part) for part in parts]


def test_misaligned_chunks_and_inputs_give_the_same_numbers():
    kwargs = dict(slip=[0.2, 0.5], load_N=58.86, outputs=["Fx_N"], samples=32, seed=2,
                  resamples=50)
    local = ts.sobol(SOIL, WHEEL, PARAMETERS, **kwargs)
    remote = ts.sobol(SOIL, WHEEL, PARAMETERS, client=MisaligningClient(), chunks=3, **kwargs)
    assert_same(local, remote, ("S1", "ST", "S1_conf", "ST_conf"))
    slips = np.array([0.05, 0.2, 0.4, 0.8])
    aligned = ts.forces(SOIL, WHEEL, slips, load_N=58.86)
    shifted = ts.forces(SOIL, WHEEL, misaligned(slips), load_N=misaligned(np.full(4, 58.86)))
    for key in ("Fx_N", "My_Nm", "sinkage_m"):
        np.testing.assert_array_equal(shifted[key], aligned[key], err_msg=key)
    # A user's own model outputs, misaligned, into the estimator.
    parameters = {"x1": (0.0, 1.0), "x2": (0.0, 1.0)}
    x = ts.sobol_design(parameters, 64, seed=1)
    y = x[:, 0] + 2.0 * x[:, 1]
    a = ts.sobol_indices(parameters, y, samples=64, seed=1, resamples=50)
    b = ts.sobol_indices(parameters, misaligned(y), samples=64, seed=1, resamples=50)
    np.testing.assert_array_equal(a["S1"], b["S1"])


def test_a_mission_study_on_two_workers_is_bit_identical(client):
    # Soils drawn from their spread, chassis masses and two wheels (docs/field.md, "Mission
    # studies"): each case one task; the summaries are the local ones bit for bit.
    cases = ts.mission_cases("field-slope-wet", 3, soil_spread={"phi_deg": 2.0, "c_kPa": 0.3},
                             chassis_mass_kg=(18.0, 26.0), wheels=["A", "B"], seed=7)
    local = ts.mission_study("field-slope-wet", cases, duration_s=4.0, model="quadratic")
    remote = ts.mission_study("field-slope-wet", cases, client=client, duration_s=4.0,
                              model="quadratic")
    assert remote == local
    assert all(row["status"] == "completed" for row in local)
    assert len({row["energy_J"] for row in local}) == 3  # three different missions
