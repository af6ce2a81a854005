"""A free wheel pressed onto a flat road and rolled from rest, through tirefe_tire.fmu driven
by a generic FMI master (tests/fmi_master.c: inputs from a CSV file, handed over at the
start of each communication step) at several communication steps, against a reference run
of the same tire through the C API (tirefe.Tire.advance, the spindle on the exact motion
from each step the FMU takes inside to the next, under the same step control). Prints, per communication step, the force
errors against the reference and the CPU time per simulated second: the table of
docs/coupling.md.

    fmu_rolling.py FMU_DIR FMI_MASTER PYTHON_PACKAGES [--speed 27.78] [--ramp 5] [--steps 0.5,1,2,5,10]

FMU_DIR: the unpacked FMU; PYTHON_PACKAGES: the folder holding the tirefe package
(build/python). tests/test_fmu.py runs a short version of it.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

PRESS_DEPTH = 0.015  # [m], about 2.4 kN on the 145 SR-12
PRESS_TIME = 0.2     # [s]
SETTLE = 0.05        # [s] held before rolling
MAX_STEP = 1e-3      # the FMU's default max_step, the reference's step
SAMPLE = 0.01        # [s] where the runs are compared (a multiple of every communication step)


def smootherstep(s):
    """0 to 1 as s goes from 0 to 1, with zero rate and rate of change at both ends."""
    s = np.clip(s, 0.0, 1.0)
    return s ** 3 * (10.0 - 15.0 * s + 6.0 * s * s)


def smootherstep_rate(s):
    s = np.clip(s, 0.0, 1.0)
    return 30.0 * s * s * (1.0 - s) ** 2


def motion(t, speed, ramp):
    """The wheel centre at times t: x, z and their rates. Pressed down in PRESS_TIME, then
    after SETTLE rolled from rest to 'speed' [m/s] over 'ramp' [s], then at that speed; the
    depth and the speed are smootherstep functions of time, so that the accelerations have
    no jumps, as a vehicle's wheel centre has none on a smooth road."""
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


def write_inputs(path, duration, speed, ramp, interval=5e-4):
    """The master's input file: the motion every 'interval' (every communication point)."""
    times = np.arange(0.0, duration + 0.5 * interval, interval)
    x, z, vx, vz = motion(times, speed, ramp)
    np.savetxt(path, np.column_stack([times, x, z, vx, vz]), delimiter=",", header="time,x,z,vx,vz", comments="",
               fmt="%.17g")


def run_master(master, fmu_dir, inputs, step, duration, folder, settings=()):
    """The master's outputs (a structured array) and its CPU time per simulated second."""
    output = os.path.join(folder, f"out_{step:g}.csv")
    command = [master, fmu_dir, "--step", repr(step), "--stop", repr(duration), "--input", inputs, "--output",
               output]
    for setting in settings:
        command += ["--set", setting]
    run = subprocess.run(command, capture_output=True, text=True, timeout=3600)
    if run.returncode != 0:
        raise RuntimeError(f"fmi_master at {step} s failed ({run.returncode}):\n{run.stderr[-2000:]}")
    cost = float(run.stderr.split("(")[-1].split(" s per simulated s")[0])
    return np.genfromtxt(output, delimiter=",", names=True), cost


def reference(tirefe, duration, speed, ramp, step):
    """The same tire through the C API, the spindle on the exact motion: a stretch
    (tirefe_advance, under the tire's step control) from each multiple of 'step' to the
    next, its ends on the exact positions and rates. Fx and Fz every SAMPLE (rows of time,
    Fx, Fz) and the CPU time per simulated second."""
    tire = tirefe.Tire("tires.145SR12", hht_alpha=-0.1)
    steps = int(round(duration / step))
    every = int(round(SAMPLE / step))
    rows = [(0.0, *tire.state()["force"][:2])]
    rate = [0.0, 0.0, 0.0]
    started = time.process_time()
    for k in range(1, steps + 1):
        x, z, vx, vz = (float(v) for v in motion(k * step, speed, ramp))
        tire.advance(step, rate, [x, z, 0.0], [vx, vz, 0.0], step)
        rate = [vx, vz, 0.0]
        if k % every == 0:
            rows.append((k * step, *tire.state()["force"][:2]))
    cost = (time.process_time() - started) / duration
    return np.array(rows), cost


def compare(outputs, reference_rows):
    """The largest and the root-mean-square |Fx| and |Fz| errors [N] of the master's outputs
    at the reference's times."""
    at = np.rint(outputs["time"] / SAMPLE)
    kept = np.isclose(outputs["time"], at * SAMPLE, atol=1e-9) & (at <= len(reference_rows) - 1)
    index = at[kept].astype(int)
    errors = [outputs[name][kept] - reference_rows[index, column] for name, column in (("Fx", 1), ("Fz", 2))]
    return [float(np.max(np.abs(e))) for e in errors] + [float(np.sqrt(np.mean(e * e))) for e in errors]


def study(fmu_dir, master, tirefe, steps, duration, speed, ramp, folder):
    """Per communication step: (step, largest Fx and Fz errors, their rms, CPU s per
    simulated s), against the C API run in the steps the FMU takes (its max_step, or the
    communication step when shorter); and the references by their steps: (rows, CPU)."""
    inputs = os.path.join(folder, "inputs.csv")
    write_inputs(inputs, duration, speed, ramp)
    references = {}
    rows = []
    for step in steps:
        internal = min(step, MAX_STEP)
        if internal not in references:
            references[internal] = reference(tirefe, duration, speed, ramp, internal)
        outputs, cost = run_master(master, fmu_dir, inputs, step, duration, folder)
        rows.append((step, *compare(outputs, references[internal][0]), cost))
    return rows, references


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("fmu_dir")
    parser.add_argument("master")
    parser.add_argument("python_packages")
    parser.add_argument("--speed", type=float, default=100 / 3.6, help="final speed [m/s] (default 100 km/h)")
    parser.add_argument("--ramp", type=float, default=5.0, help="time to reach it [s]")
    parser.add_argument("--steps", default="0.5,1,2,5,10", help="communication steps [ms]")
    arguments = parser.parse_args()
    sys.path.insert(0, arguments.python_packages)
    import tirefe
    duration = PRESS_TIME + SETTLE + arguments.ramp + 0.25
    steps = [float(s) * 1e-3 for s in arguments.steps.split(",")]
    with tempfile.TemporaryDirectory() as folder:
        rows, references = study(arguments.fmu_dir, arguments.master, tirefe, steps, duration, arguments.speed,
                                 arguments.ramp, folder)
    coarse = references[max(references)][0]
    load = coarse[-1, 2]
    print(f"press {PRESS_DEPTH * 1e3:g} mm (Fz {load:.0f} N at the end), roll from rest to "
          f"{arguments.speed:g} m/s in {arguments.ramp:g} s, {duration:g} s simulated")
    for step, (rows_of, cost) in sorted(references.items()):
        print(f"C API reference in steps of {step * 1e3:g} ms: {cost:.3f} s of CPU per simulated s")
    if len(references) > 1:
        fine = references[min(references)][0]
        difference = np.abs(fine[:, 1:] - coarse[:, 1:]).max(axis=0)
        print(f"the references differ by up to {difference[0]:.2f} N in Fx and {difference[1]:.2f} N in Fz "
              "(the tire's own time step)")
    print("| communication step | Fx error: largest, rms | Fz error: largest, rms | CPU per simulated second |")
    print("|---|---|---|---|")
    for step, fx_max, fz_max, fx_rms, fz_rms, cost in rows:
        print(f"| {step * 1e3:g} ms | {fx_max:.2f} N, {fx_rms:.2f} N | {fz_max:.2f} N, {fz_rms:.2f} N "
              f"({fz_max / load * 100:.2f} % of the load) | {cost:.3f} s |")


if __name__ == "__main__":
    main()
