"""Checks tirefe_tire.fmu from Python, with no other tool: loads the archive, presses the
wheel 10 mm onto the road in 0.2 s through the FMI functions (communication steps of 1 ms,
the inputs z and vz handed over at the start of each), holds it 0.1 s and prints the
vertical force the tire then exerts on the wheel.

    python3 check_fmu.py [FMU]      (default build/tirefe_tire.fmu)
"""
import sys

import tirefe


def press(path="build/tirefe_tire.fmu", depth=0.01, duration=0.2, hold=0.1, h=1e-3):
    def z(t):
        s = min(t / duration, 1.0)
        return -depth * s * s * (3 - 2 * s)

    def vz(t):
        s = min(t / duration, 1.0)
        return -depth * 6 * s * (1 - s) / duration

    with tirefe.Fmu(path) as fmu:
        fmu.set(pressure=180e3)
        result = fmu.simulate(duration + hold, h, {"z": z, "vz": vz})
    return result["time"][-1], result["Fz"][-1]


if __name__ == "__main__":
    t, fz = press(*sys.argv[1:2])
    print(f"t = {t:.3f} s  Fz = {fz:.1f} N")
