#!/usr/bin/env python3
"""Plots of a drum-cleat run (inputs/drum_cleat.lua), written next to its HDF5 file:

  <stem>_forces.png     spindle Fx and Fz over the whole run, and the spin rate
  <stem>_impact.png     Fx and Fz around the last cleat passage at full speed
  <stem>_spectrum.png   FFT magnitude of Fx and Fz from the cleat's arrival to the next passage
  <stem>_snapshots.png  the deformed tire on the cleat at a few instants

    /usr/bin/python3 post/plot_drum_cleat.py results/drum_cleat.h5
"""
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


class Run:
    """The histories, parameters and fields of one drum-cleat result file."""

    def __init__(self, path):
        self.path = path
        with h5py.File(path, "r") as result:
            self.parameters = dict(result["parameters"].attrs) if "parameters" in result else {}
            history = result["history"]
            self.time = history["time"][:]
            self.fx = history["spindle_fx"][:]
            self.fz = history["spindle_fz"][:]
            self.spin = history["spin_rate"][:]
            self.drum_angle = history["drum_surface_angle"][:]
            self.coordinates = result["mesh/coordinates"][:]
            self.tread = result["mesh/blocks/tire_tread"][:] if "mesh/blocks/tire_tread" in result else None
            self.spindle = int(result["mesh/node_sets/tire_spindle"][0])
            fields = result.get("fields/displacement")
            self.frame_times = result["fields/time"][:] if fields is not None else np.zeros(0)
            self.frames = fields[:] if fields is not None else None

    def parameter(self, name, default):
        value = self.parameters.get(name, default)
        return value.decode() if isinstance(value, bytes) else value

    @property
    def drum_radius(self):
        return 0.5 * float(self.parameter("drum_diameter", 1.7))

    def passages(self):
        """(on, off) times of the cleat's edges passing the top of the drum, from the drum angle."""
        half = 0.5 * float(self.parameter("cleat_length", 0.66)) / self.drum_radius
        start = math.radians(float(self.parameter("cleat_start_deg", -90.0)))
        valid = np.isfinite(self.drum_angle)
        time, angle = self.time[valid], self.drum_angle[valid]
        events = []
        for edge in (-half, +half):  # leading edge, then trailing edge (the drum turns clockwise)
            relative = np.unwrap(start + edge + angle) - math.pi / 2  # 0 at the top, decreasing
            crossings = []
            turns = np.floor(relative / (2 * math.pi))
            for i in np.nonzero(np.diff(turns))[0]:
                target = (turns[i]) * 2 * math.pi
                fraction = (relative[i] - target) / (relative[i] - relative[i + 1])
                crossings.append(time[i] + fraction * (time[i + 1] - time[i]))
            events.append(crossings)
        on, off = events
        pairs = []
        for t_on in on:
            later = [t for t in off if t > t_on]
            if later:
                pairs.append((t_on, later[0]))
        return pairs

    def last_full_speed_passage(self):
        full_speed = 2.0 + float(self.parameter("spin_up_time", 4.0))
        ring = float(self.parameter("ring_time", 0.1))
        chosen = None
        for on, off in self.passages():
            if on >= full_speed and off + ring <= self.time[-1]:
                chosen = (on, off)
        if chosen is None and self.passages():
            chosen = self.passages()[-1]
        return chosen


def plot_forces(run, stem):
    figure, axes = plt.subplots(3, 1, figsize=(9, 7), sharex=True)
    axes[0].plot(run.time, run.fz, linewidth=0.7)
    axes[0].set_ylabel("Fz [N]")
    axes[1].plot(run.time, run.fx, linewidth=0.7, color="tab:red")
    axes[1].set_ylabel("Fx [N]")
    axes[2].plot(run.time, run.spin, linewidth=0.7, color="tab:green")
    axes[2].set_ylabel("spin rate [rad/s]")
    axes[2].set_xlabel("time [s]")
    for on, off in run.passages():
        for axis in axes:
            axis.axvspan(on, off, color="0.85", linewidth=0)
    for axis in axes:
        axis.grid(True, alpha=0.3)
    figure.suptitle("spindle forces on the dead axle (grey: cleat under the tire)")
    figure.tight_layout()
    path = stem + "_forces.png"
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def plot_impact(run, stem, passage):
    on, off = passage
    window = (run.time >= on - 0.03) & (run.time <= off + 0.25)
    figure, axes = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for axis, values, label, colour in ((axes[0], run.fz, "Fz [N]", "tab:blue"), (axes[1], run.fx, "Fx [N]", "tab:red")):
        axis.plot(run.time[window] * 1e3, values[window], color=colour, linewidth=1.0)
        axis.axvspan(on * 1e3, off * 1e3, color="0.88", linewidth=0, label="cleat under the patch centre")
        axis.set_ylabel(label)
        axis.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[1].set_xlabel("time [ms]")
    speed = float(run.parameter("speed_kmh", 51.3))
    figure.suptitle(f"cleat impact at {speed:g} km/h")
    figure.tight_layout()
    path = stem + "_impact.png"
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def spectrum(time, values, start, end):
    """FFT magnitude of the detrended, Hann-windowed signal resampled on a uniform grid."""
    window = (time >= start) & (time <= end)
    t, y = time[window], values[window]
    step = np.min(np.diff(t))
    grid = np.arange(t[0], t[-1], step)
    sampled = np.interp(grid, t, y)
    sampled = sampled - np.polyval(np.polyfit(grid, sampled, 1), grid)
    padded = 8 * len(grid)
    magnitude = np.abs(np.fft.rfft(sampled * np.hanning(len(grid)), padded)) * 2 / len(grid)
    return np.fft.rfftfreq(padded, step), magnitude


def plot_spectrum(run, stem, passage):
    on, off = passage
    end = min(on + math.pi * run.drum_radius * 2 / (float(run.parameter("speed_kmh", 51.3)) / 3.6) - 0.01, run.time[-1])
    figure, axis = plt.subplots(figsize=(8, 4.5))
    for values, label, colour in ((run.fz, "Fz", "tab:blue"), (run.fx, "Fx", "tab:red")):
        frequency, magnitude = spectrum(run.time, values, on, end)
        keep = frequency <= 250
        axis.plot(frequency[keep], magnitude[keep], label=label, color=colour)
    for measured in (35, 85, 88):
        axis.axvline(measured, color="0.5", linestyle=":", linewidth=0.8)
    axis.set_xlabel("frequency [Hz]  (dotted: measured 35, 85, 88 Hz)")
    axis.set_ylabel("amplitude [N]")
    axis.set_title(f"spindle forces from the cleat's arrival to the next passage ({on:.3f}-{end:.3f} s)")
    axis.grid(True, alpha=0.3)
    axis.legend()
    figure.tight_layout()
    path = stem + "_spectrum.png"
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def drum_outline(run, angle):
    """Drum surface with the cleat, rotated by the drum's angle (radians, counter-clockwise)."""
    radius = run.drum_radius
    height = float(run.parameter("cleat_height", 0.025))
    half = 0.5 * float(run.parameter("cleat_length", 0.66)) / radius
    centre = math.radians(float(run.parameter("cleat_start_deg", -90.0))) + angle
    phi = np.linspace(0, 2 * math.pi, 2000)
    relative = np.angle(np.exp(1j * (phi - centre)))
    r = np.where(np.abs(relative) <= half, radius + height, radius)
    return r * np.cos(phi), r * np.sin(phi)


def plot_snapshots(run, stem, passage):
    if run.frames is None or len(run.frame_times) == 0:
        return None
    on, off = passage
    wanted = [on - 0.01, on + 0.004, 0.5 * (on + off), off + 0.004]
    figure, axes = plt.subplots(1, len(wanted), figsize=(4 * len(wanted), 4.4))
    for axis, moment in zip(axes, wanted):
        frame = int(np.argmin(np.abs(run.frame_times - moment)))
        time = run.frame_times[frame]
        position = run.coordinates + run.frames[frame][:, :2]
        angle = float(np.interp(time, run.time, np.nan_to_num(run.drum_angle)))
        x, y = drum_outline(run, angle)
        axis.fill(x, y, color="0.85")
        axis.plot(x, y, color="0.3", linewidth=0.8)
        if run.tread is not None:
            ring = list(run.tread[:, 0]) + [run.tread[-1, 1]]
            axis.plot(position[ring, 0], position[ring, 1], "-", color="tab:blue", linewidth=1.2)
        spindle = position[run.spindle]
        for node in (run.tread[:, 0] if run.tread is not None else []):
            axis.plot([spindle[0], position[node, 0]], [spindle[1], position[node, 1]], color="0.7", linewidth=0.3)
        axis.set_xlim(spindle[0] - 0.32, spindle[0] + 0.32)
        axis.set_ylim(spindle[1] - 0.36, spindle[1] + 0.3)
        axis.set_aspect("equal")
        axis.set_title(f"t = {time:.4f} s", fontsize=9)
        axis.axis("off")
    figure.suptitle("deformed tire on the cleat (true scale)")
    figure.tight_layout()
    path = stem + "_snapshots.png"
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 2
    run = Run(argv[1])
    stem = os.path.splitext(argv[1])[0]
    written = [plot_forces(run, stem)]
    passage = run.last_full_speed_passage()
    if passage:
        written += [plot_impact(run, stem, passage), plot_spectrum(run, stem, passage), plot_snapshots(run, stem, passage)]
    else:
        print("no cleat passage in the run: only the force history is plotted")
    for path in written:
        if path:
            print("wrote", path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
