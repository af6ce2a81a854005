"""The C example host of docs/coupling.md (examples/quarter_car_drop.c): a 300 kg quarter
car dropped onto the tire through the C API settles where the tire carries its weight,
and a bad tire source ends it with the library's message and status 1; its C++ twin
(examples/spindle_host.cpp, SPINDLE_HOST) gets the same numbers in the plane.

    test_capi.py QUARTER_CAR_DROP
"""
import os
import re
import subprocess
import sys

import script_tests

WEIGHT = 300.0 * 9.81  # N


def run(*arguments):
    return subprocess.run([TIREFE, *arguments], capture_output=True, text=True, timeout=100)


def test_settles_on_the_tire(folder):
    result = run("tires.145SR12", "1000")
    assert result.returncode == 0, result.stderr
    match = re.search(r"z = (\S+) m  Fz = (\S+) N  carried (\S+) N", result.stdout)
    assert match, result.stdout
    z, fz, carried = (float(match.group(i)) for i in (1, 2, 3))
    # At rest the tire carries the wheel with the weight (Fz = +m g in ISO wheel axes), up
    # to Newmark's step-to-step ringing of a few percent that the mean over 20 steps removes.
    assert abs(carried - WEIGHT) < 0.005 * WEIGHT, (carried, WEIGHT)
    assert abs(fz - WEIGHT) < 0.05 * WEIGHT, (fz, WEIGHT)
    # The 145 SR-12 deflects about 17 mm under 2.9 kN.
    assert -0.02 < z < -0.015, z


def test_bad_source(folder):
    result = run("no_such_tire.tir", "10")
    assert result.returncode == 1, result
    assert result.stderr.startswith("quarter_car_drop: ") and "no_such_tire.tir" in result.stderr, result.stderr
    assert result.stderr.count("\n") == 1, result.stderr


def test_cpp_host_in_the_plane(folder):
    """The C++ host of docs/spindle.md (examples/spindle_host.cpp) drops the same quarter
    car through the internal exchange, in the plane: its height y is the C host's z and
    the weight it carries (-R_y) the C host's Fz, digit for digit."""
    cpp = subprocess.run([os.environ["SPINDLE_HOST"]], capture_output=True, text=True, timeout=100)
    assert cpp.returncode == 0, cpp.stderr
    plane = re.search(r"y = (\S+) m  carried (\S+) N", cpp.stdout)
    wheel = re.search(r"z = (\S+) m  Fz = \S+ N  carried (\S+) N", run("tires.145SR12", "1000").stdout)
    assert plane and wheel, (cpp.stdout, wheel)
    assert plane.groups() == wheel.groups(), (plane.groups(), wheel.groups())
    assert abs(float(plane.group(2)) - WEIGHT) < 0.005 * WEIGHT, plane.group(2)


if __name__ == "__main__":
    script_tests.run(globals(), "tirefe_capi_")
