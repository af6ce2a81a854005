"""The Python module (import tirefe): the quarter car of examples/quarter_car_drop.py gives
the C host's numbers digit for digit; tirefe.Tire's arrays, revert and errors; a deck
run with parameters from Python, its /results read back with h5py; the k_sw fit of
examples/fit_ksw.py (scipy) against the deck's own fit.

    test_python.py MODULE_DIR    (QUARTER_CAR_DROP names the C host, TIREFE_BINARY tirefe)
"""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

import script_tests

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def module():
    sys.path.insert(0, TIREFE)
    import tirefe
    return tirefe


def test_quarter_car_as_in_c(folder):
    env = dict(os.environ, PYTHONPATH=TIREFE)
    python = subprocess.run([sys.executable, os.path.join(SOURCE, "examples/quarter_car_drop.py")], env=env,
                            capture_output=True, text=True, timeout=100, cwd=folder)
    assert python.returncode == 0, python.stderr
    c = subprocess.run([os.environ["QUARTER_CAR_DROP"]], capture_output=True, text=True, timeout=100, cwd=folder)
    assert python.stdout == c.stdout, (python.stdout, c.stdout)


def test_tire_class(folder):
    tirefe = module()
    tire = tirefe.Tire("tires.145SR12", {"pressure": 180e3})
    assert tire.road_level() < -0.2
    for step in range(1, 9):
        force, jacobian = tire.solve(1e-3, 0.0, -0.25e-3 * step)
        tire.commit()
    assert force.shape == (3,) and jacobian.shape == (3, 3)
    # ISO wheel axes: lifting the wheel unloads the tire (dFz/dz < 0); free spin: no spin row or column.
    assert jacobian[1, 1] < 0 and jacobian[2, 2] == 0.0, jacobian
    before = tire.state()
    down, _ = tire.solve(1e-3, 0.0, -2.2e-3)
    tire.solve(1e-3, 0.0, -1.8e-3)
    tire.revert()
    again, _ = tire.solve(1e-3, 0.0, -2.2e-3)
    assert np.array_equal(down, again), (down, again)
    tire.revert()
    try:
        tire.solve(1e-3, 0.0, -0.4)
        raise AssertionError("a step through the rim was solved")
    except tirefe.StepFailed as failure:
        assert "Newton" in str(failure) or "step" in str(failure), failure
    after = tire.state()
    assert after["time"] == before["time"] and np.array_equal(after["force"], before["force"])
    try:
        tire.solve(0.0, 0.0, 0.0)
        raise AssertionError("a zero time step was taken")
    except ValueError as error:
        assert "time step" in str(error), error
    try:
        tirefe.Tire("tires.145SR12", {"k_sww": 1.0})
        raise AssertionError("a misspelt parameter was taken")
    except RuntimeError as error:
        assert "k_sww" in str(error), error


def test_run_deck(folder):
    tirefe = module()
    deck = os.path.join(folder, "deck.lua")
    shutil.copy(os.path.join(SOURCE, "tests/xdmf_deck.lua"), deck)
    with open(deck, "a") as f:
        f.write('model:result{ name = "depth_mm", value = p.depth * 1000, unit = "mm" }\n')
    run = tirefe.run_deck(deck, {"end_time": 1.55, "depth": 0.012}, os.path.join(folder, "out"))
    assert run["status"] == 0 and run["error"] == "", run
    assert [os.path.basename(f) for f in run["files"]] == ["xdmf.h5"], run
    with h5py.File(run["files"][0], "r") as results:
        assert abs(results["/results"].attrs["depth_mm"] - 12.0) < 1e-12
        assert results["/history/time"][-1] > 1.5
    bad = tirefe.run_deck(deck, {"no_such_parameter": 1}, os.path.join(folder, "out"))
    assert bad["status"] == 1 and "no_such_parameter" in bad["error"], bad


def test_headings_alike(folder):
    """A driven wheel heading -x of the tire's plane, pressed and pushed along its heading,
    feels what one heading +x feels (the tire is mirror-symmetric): numpy arrays in ISO
    wheel axes whatever the heading, to 1e-9."""
    tirefe = module()
    replies = []
    for heading in ("+x", "-x"):
        tire = tirefe.Tire("tires.145SR12", free_spin=False, heading=heading)
        for step in range(1, 7):
            tire.solve(0.05, 0.0, -0.5e-3 * min(step, 4))
            tire.commit()
        force, jacobian = tire.solve(0.05, 2e-4, -2.2e-3, 0.0)
        assert force[0] < 0 and force[1] > 0, force  # pushed ahead against friction; carrying the wheel
        replies.append((force, jacobian, tire.state()))
    (plus, plus_jacobian, plus_state), (minus, minus_jacobian, minus_state) = replies
    assert np.allclose(minus, plus, rtol=0, atol=1e-9 * plus[1]), (plus, minus)
    assert np.allclose(minus_jacobian, plus_jacobian, rtol=0, atol=1e-9 * abs(plus_jacobian[1, 1]))
    assert np.allclose(minus_state["position"], [0.0, -2e-3, 0.0], rtol=0, atol=1e-12), minus_state
    try:
        tirefe.Tire("tires.145SR12", heading="forward")
        raise AssertionError("a heading other than +x or -x was taken")
    except ValueError as error:
        assert '"+x" or "-x"' in str(error), error


def test_ksw_fit_as_in_cpp(folder):
    """examples/fit_ksw.py (scipy.optimize on tirefe.static_forces) against the deck's own
    fit (inputs/fit_ksw_145SR12.lua, tirefe.fit): the same k_sw to 0.1 N m. The minimum is
    sharp numerically, though not statistically (standard error 12 N m, docs/fitting.md)."""
    import re
    env = dict(os.environ, PYTHONPATH=TIREFE)
    python = subprocess.run([sys.executable, os.path.join(SOURCE, "examples/fit_ksw.py")], env=env,
                            capture_output=True, text=True, timeout=100, cwd=folder)
    assert python.returncode == 0, python.stderr
    k_python = float(re.search(r"k_sw = (\S+) N m", python.stdout).group(1))
    deck = subprocess.run([os.environ["TIREFE_BINARY"], os.path.join(SOURCE, "inputs/fit_ksw_145SR12.lua"),
                           "--output-dir", os.path.join(folder, "fit"), "--quiet"],
                          capture_output=True, text=True, timeout=100)
    assert deck.returncode == 0, deck.stderr
    k_cpp = float(re.search(r"k_sw_sign \+1: converged .* k_sw = (\S+) N m", deck.stdout).group(1))
    assert abs(k_python - k_cpp) < 0.1, (k_python, k_cpp)


if __name__ == "__main__":
    script_tests.run(globals(), "tirefe_python_")
