"""The Python package (import tirefe): the quarter car of examples/quarter_car_drop.py gives
the C host's numbers digit for digit; tirefe.Tire's arrays, revert, advance and errors
(with their messages, also for a tire used wrongly); a deck run with parameters from Python,
its /results read back with h5py, its files its own, Ctrl-C handed back to Python; the static
curve stopped by Ctrl-C; help texts, stubs and version; the k_sw fit of examples/fit_ksw.py
(scipy) against the deck's own fit.

    test_python.py PACKAGES_DIR    (QUARTER_CAR_DROP names the C host, TIREFE_BINARY tirefe)
"""
import ast
import os
import pydoc
import re
import shutil
import signal
import subprocess
import sys
import threading
import time

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
    except tirefe.ModelError as error:
        assert isinstance(error, RuntimeError) and "k_sww" in str(error), error


def test_integrator_by_name(folder):
    """The tire's integrator by name: "hht" with hht_alpha is the scheme hht_alpha alone
    gives (the same forces, bit for bit); generalized-alpha with rho_inf steps; a misspelt
    name is refused with the known ones."""
    tirefe = module()
    forces = []
    for options in ({"hht_alpha": -0.1}, {"integrator": "hht", "hht_alpha": -0.1},
                    {"integrator": "generalized_alpha", "rho_inf": 0.8}):
        with tirefe.Tire("tires.145SR12", **options) as tire:
            for step in range(1, 5):
                force, _ = tire.solve(1e-3, 0.0, -0.25e-3 * step)
                tire.commit()
            forces.append(force)
    assert np.array_equal(forces[0], forces[1]), forces
    assert np.all(np.isfinite(forces[2])) and forces[2][1] * forces[0][1] > 0, forces
    assert not np.array_equal(forces[2], forces[0]), forces
    try:
        tirefe.Tire("tires.145SR12", integrator="generalised_alpha")
        raise AssertionError("a misspelt integrator was taken")
    except tirefe.ModelError as error:
        assert "no integrator named 'generalised_alpha' (known: static, newmark, hht, wbz, generalized_alpha)" in str(
            error), error


def test_errors_say_why(folder):
    """A commit without a trial says so (the message was read before the call that wrote
    it: freed memory, RuntimeError('-')); a Tire whose __init__ never ran raises instead of
    crashing; a closed one says it is closed."""
    tirefe = module()
    with tirefe.Tire("tires.145SR12") as tire:
        tire.solve(1e-3, 0.0, -1e-4)
        tire.commit()
        for _ in range(2):
            try:
                tire.commit()
                raise AssertionError("a commit without a trial step was taken")
            except RuntimeError as error:
                assert str(error) == "tirefe_commit: no solved trial step to accept", repr(str(error))
    try:
        tire.solve(1e-3, 0.0, 0.0)
        raise AssertionError("a closed tire solved")
    except ValueError as error:
        assert "closed" in str(error), error
    blank = tirefe.Tire.__new__(tirefe.Tire)
    for call in (lambda: blank.solve(1e-3, 0.0, 0.0), blank.commit, blank.state, blank.close):
        try:
            call()
            raise AssertionError("an uninitialized Tire was used")
        except TypeError as error:
            assert "not initialized" in str(error) and "tirefe.Tire(" in str(error), error


def test_advance_in_steps_of_its_own(folder):
    """Tire.advance: a smooth 5 mm press (0.2 s) along cubic stretches of one step each ends
    where asked, with the force of the same tire stepped through solve to the stretches'
    ends (the same equations: to round-off); in steps of at most 1 ms, a 10 ms stretch takes
    ten steps."""
    tirefe = module()
    stepped, advanced = tirefe.Tire("tires.145SR12"), tirefe.Tire("tires.145SR12")
    report, rate = {}, 0.0
    for k in range(1, 11):
        s = k / 10
        z, end_rate = -5e-3 * s * s * (3 - 2 * s), -5e-3 * 6 * s * (1 - s) / 0.2
        stepped.solve(0.02, 0.0, z)
        stepped.commit()
        report = advanced.advance(0.02, [0.0, rate, 0.0], [0.0, z, 0.0], [0.0, end_rate, 0.0], 0.02)
        rate = end_rate
    assert report["steps"] == 1 and report["cuts"] == 0, report
    assert abs(advanced.state()["position"][1] + 5e-3) < 1e-15, advanced.state()
    load = stepped.state()["force"][1]
    assert 500 < load < 1500 and abs(advanced.state()["force"][1] - load) < 1e-9 * load, (advanced.state(), load)
    report = advanced.advance(0.01, [0.0, 0.0, 0.0], [0.0, -5e-3, 0.0], [0.0, 0.0, 0.0], 1e-3)
    assert report["steps"] == 10 and report["time"] == advanced.state()["time"], report


def crg_sections(path):
    """The long sections of an LRFI OpenCRG file without placement keys or reference-line
    channels, read here by hand: {v: heights along u (None: missing)}, v = -1.5 to 1.5 m in
    steps of 0.5 m as inputs/roads/handmade_straight.crg has them."""
    with open(path) as f:
        data = f.read().split("$$$$$$$$10", 1)[1].splitlines()[1:]
    rows = [[None if line[i:i + 10].strip().startswith("*") else float(line[i:i + 10]) for i in range(0, 70, 10)]
            for line in data if line.strip()]
    return {-1.5 + 0.5 * k: [row[k] for row in rows] for k in range(7)}


def test_opencrg_road(folder):
    """road=.crg with road_lateral: the track 0.75 m left of the reference line (halfway
    between two long sections) gives the forces of the same track written as a CSV profile,
    bit for bit, over a 0.2 m roll up its rise from u = 1 m; an offset outside the road, a
    track through a missing value, a NaN, or road_track on a .crg: one message naming it."""
    tirefe = module()
    crg = os.path.join(SOURCE, "inputs", "roads", "handmade_straight.crg")
    sections = crg_sections(crg)
    csv = os.path.join(folder, "track_0.75.csv")
    with open(csv, "w") as f:
        f.write("x,z\n" + "".join(f"{u}.0,{0.5 * a + 0.5 * b!r}\n" for u, (a, b) in enumerate(zip(sections[0.5],
                                                                                                   sections[1.0]))))
    forces = []
    for road, lateral in ((crg, 0.75), (csv, 0.0)):
        tire = tirefe.Tire("tires.145SR12", hht_alpha=-0.1, road=road, road_lateral=lateral, road_start=-1.0,
                           start_z=-5e-3)
        history, rate = [tire.state()["force"]], 0.0
        for k in range(1, 21):  # 1 m/s, reached smoothly in 50 ms
            t = 0.01 * k
            s = min(t / 0.05, 1.0)
            x = 0.05 * s ** 3 * (1 - 0.5 * s) if t <= 0.05 else 0.025 + (t - 0.05)
            end_rate = s * s * (3 - 2 * s)
            tire.advance(0.01, [rate, 0.0, 0.0], [x, -5e-3, 0.0], [end_rate, 0.0, 0.0], 1e-3)
            rate = end_rate
            history.append(tire.state()["force"])
        forces.append(np.array(history))
        tire.close()
    assert np.array_equal(forces[0], forces[1]), np.abs(forces[0] - forces[1]).max()
    # The track rises 5.6 mm per metre from u = 1 m: the roll loads the wheel.
    assert forces[0][-1, 1] - forces[0][0, 1] > 50.0, forces[0][:, 1]
    refusals = (
        ({"road_lateral": 1.6}, tirefe.ModelError,
         "handmade_straight.crg:38: the track's lateral position v = 1.6 m lies outside the road's long sections "
         "(v from -1.5 to 1.5 m)"),
        ({"road_lateral": 1.5}, tirefe.ModelError, "no height at u = 7 m (a missing value): the track at v = 1.5 m"),
        ({"road_lateral": float("nan")}, ValueError, "options.road_lateral must be a finite offset"),
        ({"road_track": "left"}, ValueError, "the track of the OpenCRG road"),
    )
    for options, kind, says in refusals:
        try:
            tirefe.Tire("tires.145SR12", road=crg, **options)
            raise AssertionError(f"opened on {options}")
        except kind as error:
            assert says in str(error) and str(error).count("\n") == 0, (options, str(error))
    try:
        tirefe.Tire("tires.145SR12", road=csv, road_lateral=0.5)
        raise AssertionError("road_lateral taken for a CSV road")
    except ValueError as error:
        assert "road_lateral picks the track of an OpenCRG road" in str(error) and "track_0.75.csv" in str(error), error


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


def test_run_deck_lists_its_own_files(folder):
    """An .h5 file written into the output folder just before the run, and not by it, is
    not one of its files."""
    tirefe = module()
    output = os.path.join(folder, "own")
    os.makedirs(output)
    with h5py.File(os.path.join(output, "other.h5"), "w") as other:
        other["x"] = [1.0]
    run = tirefe.run_deck(os.path.join(SOURCE, "tests/xdmf_deck.lua"), {"end_time": 1.55}, output)
    assert run["status"] == 0 and [os.path.basename(f) for f in run["files"]] == ["xdmf.h5"], run


def test_ctrl_c_after_and_during_a_deck(folder):
    """After a deck, Ctrl-C raises KeyboardInterrupt again (the run's handlers are gone); one
    during a deck stops it after its step, its file closed and readable, and raises
    KeyboardInterrupt; the next deck runs to its end."""
    tirefe = module()
    deck = os.path.join(SOURCE, "tests/xdmf_deck.lua")
    output = os.path.join(folder, "signals")
    assert tirefe.run_deck(deck, {"end_time": 1.55}, output)["status"] == 0
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    try:
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(1)
        raise AssertionError("Ctrl-C after a deck raised nothing")
    except KeyboardInterrupt:
        pass
    # From another process: run_deck holds the GIL, so no Python thread of this one runs.
    interrupter = subprocess.Popen(["sh", "-c", f"sleep 1; kill -INT {os.getpid()}"])
    started = time.monotonic()
    try:
        tirefe.run_deck(deck, {"end_time": 100.0}, output)
        raise AssertionError("Ctrl-C during a deck raised nothing")
    except KeyboardInterrupt:
        pass
    finally:
        interrupter.wait()
    assert time.monotonic() - started < 10  # the whole run takes half a minute
    with h5py.File(os.path.join(output, "xdmf.h5"), "r") as results:
        assert 1.0 < results["/history/time"][-1] < 50.0, results["/history/time"][-1]
    again = tirefe.run_deck(deck, {"end_time": 1.55}, output)
    assert again["status"] == 0, again


def test_static_forces_stop_for_ctrl_c(folder):
    """A million presses (half an hour) stop within seconds of Ctrl-C."""
    tirefe = module()
    timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    started = time.monotonic()
    try:
        tirefe.static_forces("tires.145SR12", {}, [0.01] * 1000000)
        raise AssertionError("a million presses ended before Ctrl-C")
    except KeyboardInterrupt:
        pass
    finally:
        timer.cancel()
    assert time.monotonic() - started < 10, time.monotonic() - started


def test_help_stubs_and_version(folder):
    """help() describes every call with its arguments; the stubs (_core.pyi) name every public
    name of the compiled part and parse; __version__ is PEP 440 (a release and the commit as
    a local label)."""
    tirefe = module()
    text = pydoc.render_doc(tirefe.Tire, renderer=pydoc.plaintext)
    for words in ("solve(self: tirefe._core.Tire, time_step: float", "advance(", "StepFailed", "ISO 8855"):
        assert words in text, words
    assert "Fmu" in pydoc.render_doc(tirefe, renderer=pydoc.plaintext)
    assert "start-of-step" in (tirefe.Fmu.step.__doc__ or "")
    with open(os.path.join(TIREFE, "tirefe", "_core.pyi")) as f:
        stubs = ast.parse(f.read())
    stubbed = {node.name for node in stubs.body if isinstance(node, (ast.ClassDef, ast.FunctionDef))}
    stubbed |= {node.target.id for node in stubs.body if isinstance(node, ast.AnnAssign)}
    public = {name for name in dir(tirefe._core) if not name.startswith("_")} | {"__version__"}
    assert public <= stubbed, public - stubbed
    assert os.path.isfile(os.path.join(TIREFE, "tirefe", "py.typed"))
    assert re.fullmatch(r"\d+\.\d+\.\d+(\+g[0-9a-f]+)?", tirefe.__version__), tirefe.__version__


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


def test_step_budget(folder):
    """Tire(max_iterations=..., max_residual=...) holds a step budget: one iteration a step,
    Fz within 1e-3 N of the converged step's (5e-6 N in tests/test_step_budget.cpp), the
    unconverged steps and their residual in budget_report(); no budget by default; a bad
    budget is a ValueError naming the field."""
    tirefe = module()
    plain = tirefe.Tire(hht_alpha=-0.1, start_z=-0.01)
    fixed = tirefe.Tire(hht_alpha=-0.1, start_z=-0.01, max_iterations=1, max_residual=float("inf"))
    for step in range(1, 21):  # rolling off and pressed 1 mm further, as tests/test_step_budget.cpp does
        s = step / 20
        motion = (1e-3, 2.5e-6 * step * step, -0.01 - 1e-3 * s * s * (3 - 2 * s))
        converged, _ = plain.solve(*motion)
        plain.commit()
        limited, _ = fixed.solve(*motion)
        fixed.commit()
    assert converged[1] > 1000.0 and abs(limited[1] - converged[1]) < 1e-3, (limited, converged)
    report = fixed.budget_report()
    assert report["steps"] == 20 and report["unconverged"] > 0 and report["overruns"] == 0, report
    assert report["worst_residual"] > 1e-9 and report["worst_time"] > 0.0, report
    assert plain.budget_report()["unconverged"] == 0, plain.budget_report()
    try:
        tirefe.Tire(max_iterations=-1)
        raise AssertionError("a negative iteration budget was taken")
    except ValueError as error:
        assert "max_iterations" in str(error), error


if __name__ == "__main__":
    script_tests.run(globals(), "tirefe_python_")
