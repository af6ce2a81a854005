"""A free wheel pressed onto a flat road and rolled from rest, through tirefe_tire.fmu driven
by a generic FMI master (tests/fmi_master.c: inputs from a CSV file, handed over at the
start of each communication step) at several communication steps, against a reference run
of the same tire through the C API (tirefe.Tire.advance, the spindle on the exact motion
from each step the FMU takes inside to the next, under the same step control). Prints, per communication step, the force
errors against the reference and the CPU time per simulated second: the table of
docs/fmu.md.

    fmu_rolling.py FMU_DIR FMI_MASTER PYTHON_PACKAGES [--speed 27.78] [--ramp 5] [--steps 0.5,1,2,5,10]
                   [--road FILE --track left|right | --cleat] [--start-x X] [--alpha -0.1]

FMU_DIR: the unpacked FMU; PYTHON_PACKAGES: the folder holding the tirefe package
(build/python). tests/test_fmu.py runs a short version of it.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass

import numpy as np

PRESS_DEPTH = 0.015  # [m], about 2.6 kN on the 145 SR-12
PRESS_TIME = 0.2     # [s]
SETTLE = 0.05        # [s] held before rolling
SAMPLE = 0.01        # [s] where the runs are compared (a multiple of every communication step)
# The cleat of inputs/drum_cleat.lua on a flat road: 25 mm high, 0.66 m long, edges rounded 5 mm.
CLEAT_HEIGHT, CLEAT_LENGTH, CLEAT_EDGE_RADIUS = 0.025, 0.66, 0.005


@dataclass
class Case:
    """A press and roll: to 'speed' [m/s] in 'ramp' [s], then 'cruise' [s] at it; on a flat
    road, or on a road file (its track) with the wheel at 'start_x' of it when it starts."""
    speed: float = 100 / 3.6
    ramp: float = 5.0
    cruise: float = 0.25
    road: str = ""
    track: str = ""
    start_x: float = 0.0
    edge_radius: float = 0.0
    hht_alpha: float = -0.1
    max_step: float = 5e-4  # the tire's steps (the FMU's default)

    @property
    def duration(self):
        return PRESS_TIME + SETTLE + self.ramp + self.cruise

    def fmu_settings(self):
        settings = [f"hht_alpha={self.hht_alpha!r}", f"max_step={self.max_step!r}"]
        if self.road:
            settings += [f"road={os.path.abspath(self.road)}", f"road_edge_radius={self.edge_radius!r}"]
        if self.track:
            settings.append(f"road_track={self.track}")
        return settings

    def tire_options(self):
        """tirefe.Tire's options for the same tire and road (its x starts at 0)."""
        options = {"hht_alpha": self.hht_alpha}
        if self.road:
            options.update(road=os.path.abspath(self.road), road_track=self.track or None, road_start=-self.start_x,
                           road_edge_radius=self.edge_radius)
        return options


def smootherstep(s):
    """0 to 1 as s goes from 0 to 1, with zero rate and rate of change at both ends."""
    s = np.clip(s, 0.0, 1.0)
    return s ** 3 * (10.0 - 15.0 * s + 6.0 * s * s)


def smootherstep_rate(s):
    s = np.clip(s, 0.0, 1.0)
    return 30.0 * s * s * (1.0 - s) ** 2


def motion(t, speed, ramp):
    """The wheel centre at times t, from where it starts: x, z and their rates. Pressed down
    in PRESS_TIME, then after SETTLE rolled from rest to 'speed' [m/s] over 'ramp' [s], then
    at that speed; the depth and the speed are smootherstep functions of time, so that the
    accelerations have no jumps, as a vehicle's wheel centre has none on a smooth road."""
    t = np.asarray(t, dtype=float)
    s = t / PRESS_TIME
    z = -PRESS_DEPTH * smootherstep(s)
    vz = -PRESS_DEPTH * smootherstep_rate(s) / PRESS_TIME
    start = PRESS_TIME + SETTLE
    r = np.clip((t - start) / ramp, 0.0, 1.0)
    vx = speed * smootherstep(r)
    # x: the integral of the speed (of r^3 (10 - 15 r + 6 r^2) over the ramp), then at the speed.
    x = speed * ramp * r ** 4 * (2.5 - 3.0 * r + r * r) + speed * np.maximum(t - start - ramp, 0.0)
    return x, z, vx, vz


def write_inputs(path, case, interval=5e-4):
    """The master's input file: the motion every 'interval' (every communication point)."""
    times = np.arange(0.0, case.duration + 0.5 * interval, interval)
    x, z, vx, vz = motion(times, case.speed, case.ramp)
    np.savetxt(path, np.column_stack([times, case.start_x + x, z, vx, vz]), delimiter=",", header="time,x,z,vx,vz",
               comments="", fmt="%.17g")


def write_cleat_road(path):
    """A CSV road: flat, and the cleat from x = 0."""
    with open(path, "w") as f:
        f.write(f"x,z\n-100,0\n0,0\n0,{CLEAT_HEIGHT}\n{CLEAT_LENGTH},{CLEAT_HEIGHT}\n{CLEAT_LENGTH},0\n100,0\n")


def run_master(master, fmu_dir, inputs, step, duration, folder, settings=()):
    """The master's outputs (a structured array; up to where the FMU stopped, if it did),
    its CPU time per simulated second, and the time where the FMU stopped (None: it did not)."""
    output = os.path.join(folder, f"out_{step:g}.csv")
    command = [master, fmu_dir, "--step", repr(step), "--stop", repr(duration), "--input", inputs, "--output",
               output]
    for setting in settings:
        command += ["--set", setting]
    run = subprocess.run(command, capture_output=True, text=True, timeout=3600)
    if run.returncode not in (0, 3):
        raise RuntimeError(f"fmi_master at {step} s failed ({run.returncode}):\n{run.stderr[-2000:]}")
    cost = float(run.stderr.split("(")[-1].split(" s per simulated s")[0])
    stopped = re.search(r"discarded the step from t = \S+ at t = (\S+)", run.stderr)
    return np.genfromtxt(output, delimiter=",", names=True), cost, float(stopped.group(1)) if stopped else None


def reference(tirefe, case, step):
    """The same tire through the C API, the spindle on the exact motion: a stretch
    (tirefe_advance, under the tire's step control) from each multiple of 'step' to the
    next, its ends on the exact positions and rates. Fx and Fz every SAMPLE (rows of time,
    Fx, Fz; up to where it stopped, if it did), the CPU time per simulated second and where
    it stopped (None: it did not)."""
    tire = tirefe.Tire("tires.145SR12", **case.tire_options())
    steps = int(round(case.duration / step))
    every = int(round(SAMPLE / step))
    rows = [(0.0, *tire.state()["force"][:2])]
    rate = [0.0, 0.0, 0.0]
    stopped = None
    started = time.process_time()
    for k in range(1, steps + 1):
        x, z, vx, vz = (float(v) for v in motion(k * step, case.speed, case.ramp))
        try:
            tire.advance(step, rate, [x, z, 0.0], [vx, vz, 0.0], step)
        except tirefe.StepFailed:
            stopped = (k - 1) * step
            break
        rate = [vx, vz, 0.0]
        if k % every == 0:
            rows.append((k * step, *tire.state()["force"][:2]))
    cost = (time.process_time() - started) / case.duration
    return np.array(rows), cost, stopped


def compare(outputs, reference_rows):
    """The largest and the root-mean-square |Fx| and |Fz| errors [N] of the master's outputs
    at the reference's times (those both reached)."""
    at = np.rint(outputs["time"] / SAMPLE)
    kept = np.isclose(outputs["time"], at * SAMPLE, atol=1e-9) & (at <= len(reference_rows) - 1)
    index = at[kept].astype(int)
    errors = [outputs[name][kept] - reference_rows[index, column] for name, column in (("Fx", 1), ("Fz", 2))]
    return [float(np.max(np.abs(e))) for e in errors] + [float(np.sqrt(np.mean(e * e))) for e in errors]


def study(fmu_dir, master, tirefe, steps, case, folder):
    """Per communication step: (step, largest Fx and Fz errors, their rms, CPU s per
    simulated s, where the FMU stopped or None), against the C API run in the steps the FMU
    takes (its max_step, or the communication step when shorter); and the references by
    their steps: (rows, CPU, where they stopped or None)."""
    inputs = os.path.join(folder, "inputs.csv")
    write_inputs(inputs, case)
    references = {}
    rows = []
    for step in steps:
        internal = min(step, case.max_step)
        if internal not in references:
            references[internal] = reference(tirefe, case, internal)
        outputs, cost, stopped = run_master(master, fmu_dir, inputs, step, case.duration, folder, case.fmu_settings())
        rows.append((step, *compare(outputs, references[internal][0]), cost, stopped))
    return rows, references


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("fmu_dir")
    parser.add_argument("master")
    parser.add_argument("python_packages")
    parser.add_argument("--speed", type=float, default=100 / 3.6, help="final speed [m/s] (default 100 km/h)")
    parser.add_argument("--ramp", type=float, default=5.0, help="time to reach it [s]")
    parser.add_argument("--cruise", type=float, default=0.25, help="time at that speed [s]")
    parser.add_argument("--steps", default="0.5,1,2,5,10", help="communication steps [ms]")
    parser.add_argument("--alpha", type=float, default=-0.1, help="the tire's HHT alpha (0: Newmark)")
    parser.add_argument("--max-step", type=float, default=5e-4, help="the tire's largest step [s]")
    parser.add_argument("--road", default="", help="a road file (.rdf, .csv) instead of the flat road")
    parser.add_argument("--track", default="", help="its track: left or right")
    parser.add_argument("--cleat", action="store_true",
                        help="the road: flat with the drum-cleat deck's cleat (25 x 660 mm) from x = 0")
    parser.add_argument("--start-x", type=float, default=0.0, help="the wheel's x on the road at the start [m]")
    arguments = parser.parse_args()
    sys.path.insert(0, arguments.python_packages)
    import tirefe
    steps = [float(s) * 1e-3 for s in arguments.steps.split(",")]
    with tempfile.TemporaryDirectory() as folder:
        case = Case(arguments.speed, arguments.ramp, arguments.cruise, arguments.road, arguments.track,
                    arguments.start_x, 0.0, arguments.alpha, arguments.max_step)
        if arguments.cleat:
            case.road, case.edge_radius = os.path.join(folder, "cleat.csv"), CLEAT_EDGE_RADIUS
            write_cleat_road(case.road)
        rows, references = study(arguments.fmu_dir, arguments.master, tirefe, steps, case, folder)
    coarse = references[max(references)][0]
    load = coarse[int(round((PRESS_TIME + SETTLE) / SAMPLE)), 2]
    road = "a flat road" if not case.road else ("the cleat" if arguments.cleat else f"{case.road} {case.track}")
    print(f"press {PRESS_DEPTH * 1e3:g} mm (Fz {load:.0f} N), roll from rest to {case.speed:g} m/s in "
          f"{case.ramp:g} s, {case.cruise:g} s at it, on {road} from x = {case.start_x:g} m: {case.duration:g} s "
          f"simulated, HHT alpha {case.hht_alpha:g}, the tire's steps at most {case.max_step * 1e3:g} ms")
    for step, (_, cost, stopped) in sorted(references.items()):
        print(f"C API reference in steps of {step * 1e3:g} ms: {cost:.3f} s of CPU per simulated s"
              + (f"; its step failed at t = {stopped:g} s" if stopped is not None else ""))
    if len(references) > 1:
        fine, reached = references[min(references)][0], min(len(coarse), len(references[min(references)][0]))
        difference = np.abs(fine[:reached, 1:] - coarse[:reached, 1:]).max(axis=0)
        print(f"the references differ by up to {difference[0]:.2f} N in Fx and {difference[1]:.2f} N in Fz "
              "(the tire's own time step)")
    print("| communication step | Fx error: largest, rms | Fz error: largest, rms | CPU per simulated second |")
    print("|---|---|---|---|")
    for step, fx_max, fz_max, fx_rms, fz_rms, cost, stopped in rows:
        print(f"| {step * 1e3:g} ms | {fx_max:.2f} N, {fx_rms:.2f} N | {fz_max:.2f} N, {fz_rms:.2f} N "
              f"({fz_max / load * 100:.2f} % of the load) | {cost:.3f} s |"
              + (f" discarded at t = {stopped:g} s" if stopped is not None else ""))


if __name__ == "__main__":
    main()
