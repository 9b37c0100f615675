"""Progress callbacks and Ctrl-C (KeyboardInterrupt) in the module's long calls."""

import _thread

import numpy as np
import pytest
import terrastudio as ts

SOIL, WHEEL = "sandy-loam", "A"
# Long enough that the work outlives several 50 ms wake-ups of the calling thread on any machine
# (about 1 s on two idle cores).
MANY = np.linspace(0.0, 0.9, 200_000)


def test_progress_rises_to_one_and_does_not_change_the_numbers():
    seen = []
    slips = np.linspace(0.0, 0.9, 20_000)
    out = ts.forces(SOIL, WHEEL, slip=slips, load_N=58.86, progress=seen.append)
    plain = ts.forces(SOIL, WHEEL, slip=slips, load_N=58.86)
    np.testing.assert_array_equal(out["Fx_N"], plain["Fx_N"])
    assert seen, "no progress reported"
    assert seen[-1] == 1.0
    assert all(0.0 <= a <= b <= 1.0 for a, b in zip(seen, seen[1:]))


def test_ctrl_c_stops_forces_with_keyboard_interrupt():
    seen = []

    def interrupt_once(fraction):
        seen.append(fraction)
        if len(seen) == 1:
            _thread.interrupt_main()  # what Ctrl-C does: SIGINT's flag, seen at the next wake-up

    with pytest.raises(KeyboardInterrupt):
        ts.forces(SOIL, WHEEL, slip=MANY, load_N=58.86, progress=interrupt_once)
    assert 1.0 not in seen  # stopped before the end: the final report never came
    # The module is usable afterwards (the worker was joined, the GIL is back).
    assert ts.forces(SOIL, WHEEL, slip=0.3, load_N=58.86)["ok"]


def test_an_exception_in_the_progress_callback_stops_the_call_and_propagates():
    def fail(_fraction):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        ts.forces(SOIL, WHEEL, slip=MANY, load_N=58.86, progress=fail)


def test_a_sobol_study_reports_progress_and_stops_on_ctrl_c():
    parameters = {"phi_deg": (20, 35), "c_kPa": (0, 5)}
    seen = []
    res = ts.sobol(SOIL, WHEEL, parameters, slip=[0.3], samples=256, seed=1, resamples=50,
                   progress=seen.append)
    assert seen and seen[-1] == 1.0
    assert res["S1"]["Fx_N"].shape == (2, 1)

    calls = []

    def interrupt_once(fraction):
        calls.append(fraction)
        if len(calls) == 1:
            _thread.interrupt_main()

    with pytest.raises(KeyboardInterrupt):
        ts.sobol(SOIL, WHEEL, parameters, slip=[0.1, 0.3, 0.6], samples=16384, seed=1,
                 resamples=50, progress=interrupt_once)


def test_run_passes_progress_through_the_analysis_layer():
    seen = []
    out = ts.run("forces", SOIL, WHEEL, progress=seen.append)
    assert out["status"] == "completed"
    assert seen and seen[-1] == 1.0
