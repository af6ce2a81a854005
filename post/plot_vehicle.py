#!/usr/bin/env python3
"""Plots the spindle forces of a vehicle run around an event (the pothole) and their
spectra: Fx and Fz of the given corner result files (inputs/vehicle_pothole.lua writes
vehicle_pothole_<corner>.h5) in a time window, and the amplitude spectrum of each force
in that window (mean removed, Hann window), where wheel hop (~10 Hz) and the first
vertical tire mode (~90 Hz) show. Writes <first file stem>_spindle.png. START and END are
run times [s]; the plot counts time from the front wheel reaching the chuckhole (from the
deck's parameters).

    /usr/bin/python3 post/plot_vehicle.py START END results/vehicle_pothole_LF.h5 results/vehicle_pothole_LR.h5
"""
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def spectrum(time, values):
    """Amplitude spectrum of a signal on a uniform grid (resampled if the steps were cut)."""
    grid = np.linspace(time[0], time[-1], len(time))
    uniform = np.interp(grid, time, values)
    uniform = (uniform - uniform.mean()) * np.hanning(len(uniform))
    amplitude = 2.0 * np.abs(np.fft.rfft(uniform)) / (0.5 * len(uniform))
    return np.fft.rfftfreq(len(uniform), grid[1] - grid[0]), amplitude


def deck_parameter(result, name, default):
    value = result["parameters"].attrs.get(name, default) if "parameters" in result else default
    return float(value)


def front_wheel_at_pothole(result):
    """The time the front wheel reaches the chuckhole [s] (inputs/vehicle_pothole.lua: 2 s of
    inflation and pressing, then settle, ramp and lead into the cruise)."""
    return 2.0 + sum(deck_parameter(result, name, default) for name, default in
                     (("settle", 1.0), ("ramp", 5.0), ("lead", 1.0)))


def main(arguments):
    if len(arguments) < 3:
        print(__doc__)
        return 2
    start, end, files = float(arguments[0]), float(arguments[1]), arguments[2:]
    figure, axes = plt.subplots(2, 2, figsize=(11, 7))
    with h5py.File(files[0], "r") as result:
        impact = front_wheel_at_pothole(result)
        speed = deck_parameter(result, "speed_kmh", 48.0)
    for path in files:
        with h5py.File(path, "r") as result:
            history = result["history"]
            time = history["time"][:]
            window = (time >= start) & (time <= end)
            label = os.path.splitext(os.path.basename(path))[0].split("_")[-1]
            heading = result.attrs.get("heading", "+x")
            for row, channel in enumerate(("spindle_fx", "spindle_fz")):
                force = history[channel][:][window]  # ISO 8855 wheel axes: the tire's force on the wheel
                axes[row, 0].plot((time[window] - impact) * 1e3, force, label=label)
                frequency, amplitude = spectrum(time[window], force)
                axes[row, 1].semilogy(frequency, amplitude, label=label)
    figure.suptitle(f"spindle forces, ISO 8855 wheel axes (heading {heading})")
    for row, name in enumerate(("Fx (longitudinal)", "Fz (vertical)")):
        axes[row, 0].set_ylabel(name + " [N]")
        axes[row, 1].set_ylabel("amplitude [N]")
        axes[row, 1].set_xlim(0, 200)
        for axis in axes[row]:
            axis.grid(True, alpha=0.3)
            axis.legend()
    for row in range(2):
        axes[row, 0].set_xlabel(f"time after the front wheel reaches the chuckhole (t = {impact:g} s) [ms]")
        axes[row, 1].set_xlabel("frequency [Hz]")
    figure.suptitle(f"spindle forces on the car, chuckhole at {speed:g} km/h "
                    f"(spectra over {start:g}-{end:g} s)", fontsize=10)
    figure.tight_layout()
    output = os.path.splitext(files[0])[0] + "_spindle.png"
    figure.savefig(output, dpi=120)
    print(output)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
