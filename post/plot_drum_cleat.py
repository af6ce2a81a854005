#!/usr/bin/env python3
"""Plots of a drum-cleat run (inputs/drum_cleat.lua), written next to its HDF5 file:

  <stem>_forces.png     spindle Fx and Fz over the whole run, the spin rate and the drum speed
  <stem>_impact.png     Fx, Fz and the spin rate around the last cleat passage at full speed,
                        with the four windows the ringing is read in
  <stem>_spectrum.png   the Hann-windowed spectrum of each of those windows, with the deck's
                        readings (spectrum peak, matrix pencil) and the measured frequencies
                        (only for a run under the test's conditions: 51.3 km/h, 3800 N,
                        208 kPa, the 25 x 660 mm cleat on the 1.7 m drum)
  <stem>_snapshots.png  the deformed tire on the cleat at a few instants

    /usr/bin/python3 post/plot_drum_cleat.py results/drum_cleat.h5

The spectra are computed here with numpy's FFT (zero-padded) from the same samples the deck
read; the script checks that each window's FFT peak is the deck's spectrum reading within
an FFT bin and exits with status 3 if not.
"""
import argparse
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
            self.results = dict(result["results"].attrs) if "results" in result else {}
            self.heading = result.attrs.get("heading", "")  # x of the spindle forces' wheel axes
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

    def drum_speed_kmh(self):
        """The drum's surface speed [km/h], from its angle history (NaN before the drum exists)."""
        return np.abs(np.gradient(self.drum_angle, self.time)) * self.drum_radius * 3.6

    def measured_applies(self):
        """Whether the measured frequencies hold for this run: the test's speed, load, pressure,
        cleat and drum (lua/cleat_ringing.lua's test conditions), each to 0.1 %."""
        return all(abs(float(self.parameter(name, value)) - value) <= 1e-3 * value
                   for name, value in TEST_CONDITIONS.items())

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
    axes[2].set_ylabel("tire spin rate [rad/s]", color="tab:green")
    axes[2].set_xlabel("time [s]")
    speed_axis = axes[2].twinx()
    speed_axis.plot(run.time, run.drum_speed_kmh(), linewidth=0.9, linestyle="--", color="0.35")
    speed_axis.set_ylabel("drum surface speed [km/h] (dashed)")
    for on, off in run.passages():
        for axis in axes:
            axis.axvspan(on, off, color="0.85", linewidth=0)
    for axis in axes:
        axis.grid(True, alpha=0.3)
    figure.suptitle(f"spindle forces on the dead axle, ISO 8855 wheel axes, heading {run.heading} "
                    "(grey: cleat under the tire)")
    figure.tight_layout()
    path = stem + "_forces.png"
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


# The drum-cleat test that measured the frequencies below (lua/cleat_ringing.lua).
TEST_CONDITIONS = {"speed_kmh": 51.3, "load": 3800.0, "pressure_kpa": 208.0, "cleat_height": 0.025,
                   "cleat_length": 0.66, "drum_diameter": 1.7}

# The ringing windows the deck reads (lua/cleat_ringing.lua), in its /results.
WINDOWS = (("fz_on_top", "fz", "Fz on top of the cleat", 88, (40, 200)),
           ("fz_leaving", "fz", "Fz after leaving it", 85, (40, 200)),
           ("fx_from_hit", "fx", "Fx from the first hit", 35, (15, 200)),
           ("fx_leaving", "fx", "Fx after leaving it", 35, (15, 200)))
WINDOW_COLOURS = ("tab:cyan", "tab:olive", "tab:pink", "tab:purple")


def recorded_windows(run):
    """(name, force, title, measured, band, start, end) of the windows the deck recorded."""
    found = []
    for name, force, title, measured, band in WINDOWS:
        if name + "_from_s" in run.results:
            found.append((name, force, title, measured, band, float(run.results[name + "_from_s"]),
                          float(run.results[name + "_to_s"])))
    return found


def plot_impact(run, stem, passage):
    on, off = passage
    window = (run.time >= on - 0.03) & (run.time <= off + 0.25)
    milliseconds = (run.time[window] - on) * 1e3
    figure, axes = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
    series = ((run.fz, "Fz [N]", "tab:blue", "fz"), (run.fx, "Fx [N]", "tab:red", "fx"),
              (run.spin, "tire spin rate [rad/s]", "tab:green", None))
    for axis, (values, label, colour, force) in zip(axes, series):
        axis.plot(milliseconds, values[window], color=colour, linewidth=1.0)
        axis.axvspan(0.0, (off - on) * 1e3, color="0.9", linewidth=0, label="cleat under the patch centre")
        for (name, window_force, title, _, _, start, end), shade in zip(recorded_windows(run), WINDOW_COLOURS):
            if window_force == force:
                axis.axvspan((start - on) * 1e3, (end - on) * 1e3, ymin=0.0, ymax=0.06, color=shade, linewidth=0,
                             label=title + " (read)")
        axis.set_ylabel(label)
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=7, loc="upper right")
    axes[2].set_xlabel("time after the cleat's leading edge reaches the contact patch centre [ms]")
    speed = float(run.parameter("speed_kmh", 51.3))
    figure.suptitle(f"cleat impact at {speed:g} km/h (t = 0 at {on:.4f} s)")
    figure.tight_layout()
    path = stem + "_impact.png"
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def window_samples(time, values, start, end):
    """The deck's preparation (src/post/signal_window.hpp): uniform resampling at the median
    spacing from the first sample in [start, end], least-squares line removed."""
    inside = (time >= start) & (time <= end)
    t, y = time[inside], values[inside]
    step = float(np.median(np.diff(t)))
    grid = t[0] + step * np.arange(int(np.floor((t[-1] - t[0]) / step * (1 + 1e-12))) + 1)
    sampled = np.interp(grid, t, y)
    return step, sampled - np.polyval(np.polyfit(grid - grid[0], sampled, 1), grid - grid[0])


def spectrum(step, samples, padding=64):
    """Single-sided amplitude of the Hann-windowed samples, FFT zero-padded 'padding' times."""
    weights = np.hanning(len(samples))
    padded = padding * len(samples)
    magnitude = np.abs(np.fft.rfft(samples * weights, padded)) * 2 / weights.sum()
    return np.fft.rfftfreq(padded, step), magnitude


def window_spectrum(run, force, band, start, end):
    """A window's spectrum (frequency, amplitude) and its peak within the band read."""
    step, samples = window_samples(run.time, run.fx if force == "fx" else run.fz, start, end)
    frequency, magnitude = spectrum(step, samples)
    in_band = (frequency >= band[0]) & (frequency <= band[1])
    return frequency, magnitude, frequency[in_band][np.argmax(magnitude[in_band])]


def disagreement(run, name, title, fft_peak, bin_width):
    """A line if the FFT peak and the deck's spectrum reading of window 'name' differ by
    more than one FFT bin, else None."""
    deck_spectrum = float(run.results[name + "_spectrum_Hz"])
    if abs(fft_peak - deck_spectrum) > bin_width:
        return f"{title}: numpy FFT peak {fft_peak:.2f} Hz, deck {deck_spectrum:.2f} Hz"
    return None


def earlier_passage_disagreements(run):
    """The FFT check of the windows the deck read in the passage before the last
    (results with "before_" in front): they are printed, so they are checked too."""
    found = []
    for name, force, title, _, band in WINDOWS:
        key = "before_" + name
        if key + "_from_s" in run.results:
            frequency, _, fft_peak = window_spectrum(run, force, band, float(run.results[key + "_from_s"]),
                                                     float(run.results[key + "_to_s"]))
            found.append(disagreement(run, key, title + " (the passage before)", fft_peak, frequency[1]))
    return [line for line in found if line]


def plot_spectrum(run, stem):
    """One panel per ringing window of the last passage; returns the path and the windows,
    of both passages read, whose FFT peak disagrees with the deck's spectrum reading by more
    than one FFT bin."""
    windows = recorded_windows(run)
    if not windows:
        return None, []
    figure, axes = plt.subplots(2, 2, figsize=(11, 7.5))
    disagreements = earlier_passage_disagreements(run)
    for axis, (name, force, title, measured, band, start, end) in zip(axes.ravel(), windows):
        frequency, magnitude, fft_peak = window_spectrum(run, force, band, start, end)
        keep = frequency <= 200
        axis.plot(frequency[keep], magnitude[keep], color="tab:red" if force == "fx" else "tab:blue")
        deck_spectrum = float(run.results[name + "_spectrum_Hz"])
        deck_pencil = float(run.results[name + "_pencil_Hz"])
        line = disagreement(run, name, title, fft_peak, frequency[1])
        if line:
            disagreements.append(line)
        axis.axvline(deck_spectrum, color="k", linewidth=0.9, label=f"spectrum peak {deck_spectrum:.1f} Hz")
        axis.axvline(deck_pencil, color="tab:orange", linestyle="--", linewidth=1.2,
                     label=f"matrix pencil {deck_pencil:.1f} Hz "
                           f"(damping {float(run.results[name + '_damping_ratio']):.3f})")
        if run.measured_applies():
            axis.axvline(measured, color="0.5", linestyle=":", linewidth=1.2, label=f"measured {measured} Hz")
        axis.axvspan(0, band[0], color="0.93", linewidth=0)
        axis.set_xlim(0, 200)
        axis.set_title(f"{title}: {(start - run.results.get('cleat_on_s', start)) * 1e3:.0f} to "
                       f"{(end - run.results.get('cleat_on_s', start)) * 1e3:.0f} ms", fontsize=9)
        axis.set_xlabel("frequency [Hz]")
        axis.set_ylabel(f"{force.upper()[0]}{force[1]} amplitude [N]")
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=7)
    speed = float(run.parameter("speed_kmh", 51.3))
    note = "" if run.measured_applies() else "\nno measured frequencies: they are for 51.3 km/h, 3800 N, 208 kPa, " \
                                             "25 x 660 mm cleat on the 1.7 m drum"
    figure.suptitle(f"spectra of the ringing windows, {speed:g} km/h (Hann, zero-padded; grey: outside the band read; "
                    f"times from the leading edge at the patch centre){note}", fontsize=9)
    figure.tight_layout()
    path = stem + "_spectrum.png"
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path, disagreements


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
        # Millimetres from the spindle's place at this frame.
        origin = position[run.spindle].copy()
        position = (position - origin) * 1e3
        x, y = (x - origin[0]) * 1e3, (y - origin[1]) * 1e3
        axis.fill(x, y, color="0.85")
        axis.plot(x, y, color="0.3", linewidth=0.8)
        if run.tread is not None:
            ring = list(run.tread[:, 0]) + [run.tread[-1, 1]]
            axis.plot(position[ring, 0], position[ring, 1], "-", color="tab:blue", linewidth=1.2)
        spindle = position[run.spindle]
        for node in (run.tread[:, 0] if run.tread is not None else []):
            axis.plot([spindle[0], position[node, 0]], [spindle[1], position[node, 1]], color="0.7", linewidth=0.3)
        axis.set_xlim(spindle[0] - 320, spindle[0] + 320)
        axis.set_ylim(spindle[1] - 360, spindle[1] + 300)
        axis.set_aspect("equal")
        axis.set_title(f"{(time - on) * 1e3:+.0f} ms from the leading edge (t = {time:.4f} s)", fontsize=9)
        axis.set_xlabel("x from the spindle [mm]")
        axis.set_ylabel("y from the spindle [mm]")
    figure.suptitle("deformed tire on the cleat (true scale)")
    figure.tight_layout()
    path = stem + "_snapshots.png"
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path


def main(argv):
    parser = argparse.ArgumentParser(prog=os.path.basename(argv[0]), description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("result", help="the HDF5 result file of a drum-cleat run (inputs/drum_cleat.lua)")
    path = parser.parse_args(argv[1:]).result
    try:
        run = Run(path)
    except OSError as error:  # one line naming the file, no traceback
        sys.exit(f"{parser.prog}: {path}: not a readable HDF5 result file ({error})")
    except KeyError as error:  # another deck's result file
        sys.exit(f"{parser.prog}: {path}: not a drum-cleat result file ({error.args[0]}; "
                 "post/plot_results.py plots any result file)")
    stem = os.path.splitext(path)[0]
    written = [plot_forces(run, stem)]
    passage = run.last_full_speed_passage()
    disagreements = []
    if "cleat_on_s" in run.results:
        passage = (float(run.results["cleat_on_s"]), float(run.results["cleat_off_s"]))
    if passage:
        spectrum_path, disagreements = plot_spectrum(run, stem)
        written += [plot_impact(run, stem, passage), spectrum_path, plot_snapshots(run, stem, passage)]
    else:
        print("no cleat passage in the run: only the force history is plotted")
    for path in written:
        if path:
            print("wrote", path)
    for line in disagreements:
        print("spectrum disagrees with the deck's reading:", line)
    return 3 if disagreements else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
