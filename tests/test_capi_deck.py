"""A deck's tire driven through the C API (tirefe_open_deck, tests/capi_deck_host.c on
tests/host_tire_deck.lua): the host's trial step gives the deck's own model:spindle_force
bit for bit, committed steps land in the deck's result file, and a deck that names no tire
or gets an undeclared parameter is refused with its file, line and what to fix.

    test_capi_deck.py CAPI_DECK_HOST
"""
import os
import subprocess

import h5py

import script_tests

DECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "host_tire_deck.lua")


def run(deck, folder):
    return subprocess.run([TIREFE, deck, os.path.join(folder, "out")], capture_output=True, text=True, timeout=100)


def test_host_drives_the_decks_tire(folder):
    result = run(DECK, folder)
    assert result.returncode == 0, result.stderr
    deck_fy = float(result.stdout.split("deck fy ")[1].split()[0])
    host_fz = float(result.stdout.split("host fz ")[1].split()[0])
    # model:spindle_force gives the plane's reaction (the force holding the spindle down),
    # the C API the force the tire exerts on the wheel in ISO wheel axes: Fz = -fy.
    assert host_fz == -deck_fy and host_fz > 1000.0, (deck_fy, host_fz)  # pressed 12 mm: kN, carrying the wheel
    assert "time 2.005000" in result.stdout, result.stdout
    assert "road level: 4" in result.stdout, result.stdout  # TIREFE_INVALID_CALL
    assert ("unknown parameter: 2 " + DECK + ":8: command-line parameter 'no_such_parameter' is not declared"
            in result.stdout), result.stdout
    with h5py.File(os.path.join(folder, "out", "host_tire_deck.h5"), "r") as results:
        assert abs(results["/history/time"][-1] - 2.005) < 1e-12, results["/history/time"][-1]


def test_deck_without_host_tire(folder):
    deck = os.path.join(folder, "no_tire.lua")
    with open(deck, "w") as f:
        f.write('local p = tirefe.parameters{ depth = 0.0 }\nlocal model = tirefe.model{ title = "no tire" }\n')
    result = run(deck, folder)
    assert result.returncode == 1, result
    assert result.stderr.startswith("capi_deck_host: " + deck + ": "), result.stderr
    assert "host_tire = { model = model, spindle = tire.spindle }" in result.stderr, result.stderr
    assert result.stderr.count("\n") == 1, result.stderr


if __name__ == "__main__":
    script_tests.run(globals(), "tirefe_capi_deck_")
