"""A hostile Python host of the package `tirefe`, the Python side of the bad-deck catalogue:
objects used before they are made, after they are closed or freed, twice, with arguments of
the wrong type or out of range; decks named like options; deck runs one after another with
signals in between and during. Each misuse must raise the exception it names with a message
that says what to fix (or return what it names); nothing may crash the interpreter, hang or
be taken silently. Prints one line per probe that got something else and a summary; exits 1
if any probe failed.

    python_abuser.py PACKAGES_DIR    (FMU names tirefe_tire.fmu; FMU_BINARY, FMU_GUID and
                                      FMU_RESOURCES its unpacked binary, GUID and resources)
"""
import math
import os
import pathlib
import pickle
import signal
import subprocess
import sys
import tempfile
import time

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(SOURCE, "tests/xdmf_deck.lua")
probes, failures = 0, []


def expect(what, call, error, text, one_line=True):
    """'call' must raise 'error' (None: return) with 'text' in its one-line message (a
    TypeError of pybind11 for arguments of the wrong type lists the signature and the call
    on lines of their own: one_line=False)."""
    global probes
    probes += 1
    try:
        result = call()
        got, message = None, repr(result)
    except BaseException as raised:  # KeyboardInterrupt and the like are probes too
        got, message = type(raised), str(raised)
    if os.environ.get("PYTHON_ABUSER_VERBOSE"):
        print(f"{what:60s} {got.__name__ if got else 'returned'}: {message[:150]}")
    fits = got is None if error is None else got is not None and issubclass(got, error)
    if not fits or text not in message or (error is not None and one_line and "\n" in message):
        failures.append(what)
        print(f"FAILED: {what}: {got.__name__ if got else 'returned'}: {message[:300]!r} "
              f"(expected {error.__name__ if error else 'a return'} with {text!r})")


def abuse_tire(tirefe):
    blank = tirefe.Tire.__new__(tirefe.Tire)
    for name, call in (("solve", lambda: blank.solve(1e-3, 0.0, 0.0)),
                       ("solve_velocity", lambda: blank.solve_velocity(1e-3, 0.0, 0.0)),
                       ("advance", lambda: blank.advance(1e-3, [0, 0, 0], [0, 0, 0], [0, 0, 0], 1e-3)),
                       ("commit", blank.commit), ("revert", blank.revert), ("state", blank.state),
                       ("road_level", blank.road_level), ("close", blank.close),
                       ("__exit__", lambda: blank.__exit__(None, None, None))):
        expect(f"Tire.__new__(Tire).{name}", call, TypeError, "was not initialized: make tires with tirefe.Tire(")

    tire = tirefe.Tire()
    expect("commit before any solve", tire.commit, RuntimeError, "tirefe_commit: no solved trial step to accept")
    expect("solve", lambda: tire.solve(1e-3, 0.0, -1e-4), None, "")
    expect("commit", tire.commit, None, "")
    expect("commit twice", tire.commit, RuntimeError, "tirefe_commit: no solved trial step to accept")
    expect("revert without a trial", tire.revert, None, "")
    expect("solve with a text time step", lambda: tire.solve("1e-3", 0.0, 0.0), TypeError, "time_step: float", one_line=False)
    expect("solve with None", lambda: tire.solve(None, 0.0, 0.0), TypeError, "incompatible function arguments",
           one_line=False)
    expect("solve over NaN", lambda: tire.solve(math.nan, 0.0, 0.0), ValueError,
           "the time step must be a finite number > 0 (got nan)")
    expect("solve over 1e-12 s", lambda: tire.solve(1e-12, 0.0, 0.0), ValueError,
           "the time step 1e-12 s is below 1e-07 s")
    expect("solve to x = inf", lambda: tire.solve(1e-3, math.inf, 0.0), ValueError,
           "the spindle motion must be finite")
    expect("solve_velocity to NaN", lambda: tire.solve_velocity(1e-3, 0.0, math.nan), ValueError,
           "the spindle velocity must be finite")
    expect("advance with two rates", lambda: tire.advance(1e-3, [0, 0], [0, 0, 0], [0, 0, 0], 1e-3), TypeError,
           "start_velocity: List[float[3]]", one_line=False)
    expect("advance with max_step 0", lambda: tire.advance(1e-3, [0, 0, 0], [0, 0, 0], [0, 0, 0], 0.0), ValueError,
           "the path's duration and max_step must be finite numbers > 0")
    expect("advance over 1e-12 s", lambda: tire.advance(1e-12, [0, 0, 0], [0, 0, 0], [0, 0, 0], 1e-3), ValueError,
           "the time step 1e-12 s is below 1e-07 s")
    expect("solve through the rim", lambda: tire.solve(1e-3, 0.0, -0.4), tirefe.StepFailed, "")
    expect("pickle a tire", lambda: pickle.dumps(tire), TypeError, "cannot pickle")
    expect("close", tire.close, None, "")
    expect("close twice (as a file's close)", tire.close, None, "")
    for name, call in (("solve", lambda: tire.solve(1e-3, 0.0, 0.0)), ("commit", tire.commit),
                       ("state", tire.state), ("road_level", tire.road_level)):
        expect(f"{name} after close", call, ValueError, "the tire is closed")
    with tirefe.Tire() as held:
        pass
    expect("state after the with block", held.state, ValueError, "the tire is closed")

    expect("a tire from a number", lambda: tirefe.Tire(42), TypeError, "source: str", one_line=False)
    expect("a parameter given as text", lambda: tirefe.Tire("tires.145SR12", {"pressure": "180e3"}), TypeError,
           "parameters: Dict[str, float]", one_line=False)
    expect("a NaN parameter", lambda: tirefe.Tire("tires.145SR12", {"pressure": math.nan}), ValueError,
           "override 'pressure' is not a finite number")
    expect("a misspelt parameter", lambda: tirefe.Tire("tires.145SR12", {"k_sww": 1.0}), tirefe.ModelError,
           "unknown key 'k_sww' (did you mean 'k_sw'?")
    expect("a tire file that does not exist", lambda: tirefe.Tire("no_such.tir"), tirefe.ModelError,
           "no_such.tir: cannot open the file")
    expect("a module that does not exist", lambda: tirefe.Tire("tires.nothing"), tirefe.ModelError,
           "module 'tires.nothing' not found")
    expect("a path as a module", lambda: tirefe.Tire("/etc/passwd"), tirefe.ModelError,
           "invalid module name '/etc/passwd'")
    expect("heading +y", lambda: tirefe.Tire(heading="+y"), ValueError, 'heading must be "+x" or "-x", not "+y"')
    expect("a negative friction", lambda: tirefe.Tire(friction=-1.0), ValueError,
           "options.friction must be a finite number >= 0")
    expect("HHT alpha 0.5", lambda: tirefe.Tire(hht_alpha=0.5), tirefe.ModelError, "HHT needs alpha in [-1/3, 0]")
    expect("a road file that does not exist", lambda: tirefe.Tire(road="no_such.csv"), tirefe.ModelError,
           "no_such.csv")
    expect("a road track 'middle'",
           lambda: tirefe.Tire(road=os.path.join(SOURCE, "inputs/roads/chuckhole.csv"), road_track="middle"),
           ValueError, 'options.road_track must be "left", "right" or NULL, not "middle"')
    expect("a road track without a road", lambda: tirefe.Tire(road_track="left"), ValueError,
           'options.road_track is "left" but options.road names no road file: give both, or neither')
    expect("start_z NaN", lambda: tirefe.Tire(start_z=math.nan), ValueError, "options.road_start and options.start_z")


def abuse_static_forces(tirefe):
    expect("static_forces of NaN", lambda: tirefe.static_forces("tires.145SR12", {}, [math.nan]), ValueError,
           "the deflections must be finite")
    expect("static_forces of text", lambda: tirefe.static_forces("tires.145SR12", {}, "abc"), TypeError,
           "deflections: List[float]", one_line=False)
    expect("static_forces with a NaN parameter",
           lambda: tirefe.static_forces("tires.145SR12", {"pressure": math.nan}, [0.01]), ValueError,
           "parameter 'pressure' is not a finite number")
    expect("static_forces of a missing file", lambda: tirefe.static_forces("no.tir", {}, [0.01]), tirefe.ModelError,
           "no.tir: cannot open the file")
    expect("static_forces through the rim", lambda: tirefe.static_forces("tires.145SR12", {}, [1.0]),
           tirefe.ModelError, "could not be solved")


def abuse_run_deck(tirefe, folder):
    out = os.path.join(folder, "out")
    expect("run_deck into ''", lambda: tirefe.run_deck(DECK, {}, ""), ValueError, "output_dir is empty: give a path")
    expect("run_deck of ''", lambda: tirefe.run_deck("", {}, out), ValueError, "deck is empty: give a path")
    expect("run_deck of '--help' (a file name, not an option)", lambda: tirefe.run_deck("--help", {}, out)["error"],
           None, "no deck file './--help'")
    expect("run_deck with a parameter named '--restart'", lambda: tirefe.run_deck(DECK, {"--restart": "x"}, out),
           ValueError, "parameter name '--restart' is no name a deck declares")
    expect("run_deck with a parameter named 'a=b'", lambda: tirefe.run_deck(DECK, {"a=b": 1}, out), ValueError,
           "parameter name 'a=b' is no name a deck declares")
    expect("run_deck with an undeclared parameter", lambda: tirefe.run_deck(DECK, {"no_such_parameter": 1}, out)["error"],
           None, "command-line parameter 'no_such_parameter' is not declared by the deck")
    expect("run_deck with a parameter that is no number",
           lambda: tirefe.run_deck(DECK, {"end_time": "soon"}, out)["error"], None,
           "command-line parameter 'end_time=soon' must be a number")
    expect("run_deck into a file", lambda: tirefe.run_deck(DECK, {"end_time": 1.55}, "/etc/passwd")["error"], None,
           "a file of that name")
    dashed = tirefe.run_deck(DECK, {"end_time": 1.55}, os.path.join(folder, "-dashed"))
    expect("run_deck into a folder named '-dashed'", lambda: dashed["status"], None, "0")


class Terminated(Exception):
    pass


def on_sigterm(number, frame):
    raise Terminated("SIGTERM")


def abuse_signals(tirefe, folder):
    """Runs one after another; Python's handlers are its own again after each: Ctrl-C
    raises KeyboardInterrupt, a handler of the host's own runs, and the next run goes to its
    end instead of stopping at once."""
    out = os.path.join(folder, "signals")
    previous = signal.signal(signal.SIGTERM, on_sigterm)
    try:
        for run in (1, 2):
            expect(f"run {run} of a deck to its end", lambda: tirefe.run_deck(DECK, {"end_time": 1.55}, out)["status"],
                   None, "0")
            expect(f"the host's SIGTERM handler after run {run}", lambda: signal.getsignal(signal.SIGTERM) is on_sigterm,
                   None, "True")
            expect(f"SIGTERM after run {run}", lambda: (os.kill(os.getpid(), signal.SIGTERM), time.sleep(1)),
                   Terminated, "SIGTERM")
            expect(f"Ctrl-C after run {run}", lambda: (os.kill(os.getpid(), signal.SIGINT), time.sleep(1)),
                   KeyboardInterrupt, "")
        # During a run (from another process: run_deck holds the GIL): the run stops after
        # its step and the host's handler raises; the next run is not stopped by it.
        for number, error in ((signal.SIGTERM, Terminated), (signal.SIGINT, KeyboardInterrupt)):
            name = signal.Signals(number).name
            killer = subprocess.Popen(["sh", "-c", f"sleep 1; kill -{name[3:]} {os.getpid()}"])
            started = time.monotonic()
            expect(f"{name} during a deck", lambda: tirefe.run_deck(DECK, {"end_time": 100.0}, out), error, "")
            killer.wait()
            expect(f"{name} stops the deck within seconds", lambda: time.monotonic() - started < 10, None, "True")
            expect(f"the run after {name} goes to its end",
                   lambda: tirefe.run_deck(DECK, {"end_time": 1.55}, out)["status"], None, "0")
    finally:
        signal.signal(signal.SIGTERM, previous)


def abuse_fmu(tirefe):
    from tirefe import _core
    blank = _core.FmiInstance.__new__(_core.FmiInstance)
    for name, call in (("do_step", lambda: blank.do_step(0.0, 1e-3)), ("free", blank.free),
                       ("get_real", lambda: blank.get_real([4])), ("take_messages", blank.take_messages)):
        expect(f"FmiInstance.__new__(FmiInstance).{name}", call, TypeError, "this FmiInstance was not initialized")
    expect("FmiInstance of a missing binary", lambda: _core.FmiInstance("/no/such.so", "g", "", "x", False),
           RuntimeError, "cannot load the FMU's binary /no/such.so")
    expect("FmiInstance of a library that is no FMU",
           lambda: _core.FmiInstance(_core.__file__, "g", "", "x", False), RuntimeError,
           "the FMU's binary does not export fmi2Instantiate")
    binary, guid = os.environ["FMU_BINARY"], os.environ["FMU_GUID"]
    resources = pathlib.Path(os.environ["FMU_RESOURCES"]).as_uri()
    expect("FmiInstance with another GUID", lambda: _core.FmiInstance(binary, "{x}", resources, "x", False),
           RuntimeError, "fmi2Instantiate failed: the GUID is not this FMU's")
    fmu = _core.FmiInstance(binary, guid, resources, "abused", False)
    expect("set_real with more values than references", lambda: fmu.set_real([10], [1.0, 2.0]), ValueError,
           "as many values as value references")
    expect("do_step before initialization", lambda: fmu.do_step(0.0, 1e-3), None, "3")
    expect("the FMU's message for it", lambda: fmu.take_messages()[-1][2], None,
           "fmi2DoStep is not allowed in instantiated")
    expect("free", fmu.free, None, "")
    expect("free twice", fmu.free, None, "")
    expect("do_step after free", lambda: fmu.do_step(0.0, 1e-3), ValueError, "the FMU instance is freed")

    expect("Fmu of a file that is none", lambda: tirefe.Fmu("/no/such.fmu"), tirefe.FmuError, "/no/such.fmu")
    with tempfile.NamedTemporaryFile(suffix=".fmu") as text:
        text.write(b"not a zip archive")
        text.flush()
        expect("Fmu of a text file", lambda: tirefe.Fmu(text.name), tirefe.FmuError, "not an FMU archive")
    fmu = tirefe.Fmu(os.environ["FMU"])
    expect("Fmu.step before initialize", lambda: fmu.step(1e-3), tirefe.FmuError, "initialize() the FMU")
    expect("Fmu.set of a misspelt name", lambda: fmu.set(presure=1.0), KeyError, "has no variable 'presure'")
    expect("Fmu.set of text to a Real", lambda: fmu.set(pressure="high"), TypeError,
           "pressure is a Real variable: 'high' is not one")
    expect("Fmu.set of a number to a String", lambda: fmu.set(tire=3), TypeError, "tire is a String variable: 3 is not")
    expect("Fmu.set of a number to a Boolean", lambda: fmu.set(free_spin=1), TypeError,
           "free_spin is a Boolean variable: 1 is not one")
    expect("Fmu.set of the output Fz", lambda: fmu.set(Fz=1.0), tirefe.FmuError,
           "setting Fz = 1.0: Error: no settable Real with value reference 4")
    expect("Fmu.simulate in steps of -1 ms", lambda: fmu.simulate(0.01, -1e-3), ValueError,
           "simulate in steps of -0.001 s: give a finite step_size > 0")
    expect("Fmu.simulate to t = NaN", lambda: fmu.simulate(math.nan, 1e-3), ValueError,
           "simulate from 0.0 s to nan s: give finite times")
    expect("Fmu.simulate with an input of text", lambda: fmu.simulate(0.01, 1e-3, {"z": "abc"}), ValueError,
           "input z: give a function of time or (times, values) of equal length")
    expect("Fmu.simulate with an output as input", lambda: fmu.simulate(0.01, 1e-3, {"Fz": lambda t: 0.0}),
           ValueError, "Fz is not an input of the FMU")
    fmu.close()
    expect("Fmu.close twice", fmu.close, None, "")
    expect("Fmu.get after close", lambda: fmu.get("Fz"), tirefe.FmuError,
           "the FMU is closed: load it again with tirefe.Fmu(path)")
    expect("Fmu.step after close", lambda: fmu.step(1e-3), tirefe.FmuError, "the FMU is closed")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.path.insert(0, os.path.abspath(sys.argv[1]))
    import tirefe
    with tempfile.TemporaryDirectory(prefix="tirefe_python_abuser_") as folder:
        abuse_tire(tirefe)
        abuse_static_forces(tirefe)
        abuse_run_deck(tirefe, folder)
        abuse_signals(tirefe, folder)
        abuse_fmu(tirefe)
    print(f"{probes} probes, {len(failures)} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
