#!/usr/bin/env python3
"""Studies of the drum-cleat results (docs/drum_cleat.md), each a set of runs of
inputs/drum_cleat.lua whose readings of the full-speed cleat passage it tabulates:

  sensitivity  the reference against time steps halved, 150 elements, Newmark instead of
               HHT: each reading's change from the reference;
  phases       the cleat moved by eighths of a node spacing, so that the tread meets it in
               eight places: the spread of every reading (half the range over the mean);
  rim          the rim's rotary inertia over its estimated range, 0.12-0.16 kg m^2
               (docs/calibration.md): each reading's band;
  calibration  what moves what (docs/calibration.md): the tread rubber's shear stiffness and
               dashpot, friction and the rim's inertia changed one at a time, and the paper's
               model with its own and a doubled rim inertia.

By default the short protocol (0.5 s spin-up: the same full-speed impact); --full runs the
8 s protocol.

    /usr/bin/python3 bench/drum_cleat_study.py phases [--full] [--jobs 2] [extra key=value ...]
"""
import argparse
import math
import os
import subprocess
import sys
import time

import h5py

from deck_runs import run_variants

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHORT = ["spin_up_time=0.5", "end_time=3.0"]
# A node spacing of the 100-element 145 SR-12 (0.543 m) seen on the 1.7 m drum [deg].
SPACING_DEG = math.degrees(math.pi * 0.543 / 100 / 0.85)
STUDIES = {
    "sensitivity": {
        "reference": [],
        "dt / 2": ["dt=2.5e-4", "dt_cleat=1.25e-4"],
        "150 elements": ["elements=150"],
        "150 el, dt / 2": ["elements=150", "dt=2.5e-4", "dt_cleat=1.25e-4"],
        "Newmark g=0.6": ["integrator=newmark", "newmark_gamma=0.6"],
    },
    "phases": {f"phase {k}/8": [f"cleat_start_deg={-90 + k / 8 * SPACING_DEG:.6f}"] for k in range(8)},
    "rim": {"0.12 kg m^2": ["rim_inertia=0.12"], "0.15 kg m^2 (the set's)": [], "0.16 kg m^2": ["rim_inertia=0.16"]},
    "calibration": {
        "the calibrated set": [],
        "k_t 5e6 N/m^2": ["tread_shear_stiffness=5e6"],
        "k_t 2e7 N/m^2": ["tread_shear_stiffness=2e7"],
        "k_t 3e7 N/m^2": ["tread_shear_stiffness=3e7"],
        "no shear dashpot": ["tread_shear_damping=0"],
        "friction 1.0": ["friction=1.0"],
        "rim 0.10 kg m^2": ["rim_inertia=0.10"],
        "rim 0.20 kg m^2": ["rim_inertia=0.20"],
        "paper's model": ["tire=tires.145SR12"],
        "paper's model, rim 0.2": ["tire=tires.145SR12", "rim_inertia=0.20"],
    },
}
QUANTITIES = [("fz_on_top_Hz", "Fz on top [Hz]"), ("fz_leaving_Hz", "Fz leaving [Hz]"),
              ("fx_from_hit_Hz", "Fx from hit [Hz]"), ("fx_leaving_Hz", "Fx leaving [Hz]"),
              ("fz_peak_to_peak", "Fz p-p [N]"), ("fx_peak_to_peak", "Fx p-p [N]")]
# Fx after leaving by each estimator, with the pencil's damping ratio: the fore-aft mode's.
CALIBRATION_QUANTITIES = [("fz_on_top_Hz", "Fz on top [Hz]"), ("fz_leaving_Hz", "Fz leaving [Hz]"),
                          ("fx_leaving_spectrum_Hz", "Fx leaving, spectrum"), ("fx_leaving_pencil_Hz", "pencil [Hz]"),
                          ("fx_leaving_damping_ratio", "pencil's damping")]


def run(name, arguments, output_dir):
    file_name = "".join(c if c.isalnum() else "_" for c in name) + ".h5"
    command = [os.path.join(ROOT, "build", "tirefe"), os.path.join(ROOT, "inputs", "drum_cleat.lua"), "--quiet",
               "--output-dir", output_dir, f"output={file_name}"] + arguments
    start = time.monotonic()
    finished = subprocess.run(command, capture_output=True, text=True)
    wall = time.monotonic() - start
    if finished.returncode != 0:
        return name, {"error": finished.stderr.strip().splitlines()[-1] if finished.stderr.strip() else "failed"}
    with h5py.File(os.path.join(output_dir, file_name), "r") as result:
        values = dict(result["results"].attrs)
    values["wall"] = wall
    return name, values


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("study", choices=sorted(STUDIES), nargs="?", default="sensitivity")
    parser.add_argument("--full", action="store_true", help="the 8 s protocol instead of the short one")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--output-dir", default=os.path.join(ROOT, "results", "drum_cleat_study"))
    parser.add_argument("extra", nargs="*", help="key=value for every run")
    options = parser.parse_args()
    os.makedirs(options.output_dir, exist_ok=True)
    protocol = [] if options.full else SHORT
    variants = STUDIES[options.study]
    quantities = CALIBRATION_QUANTITIES if options.study == "calibration" else QUANTITIES
    results = run_variants(lambda name, arguments: run(name, protocol + options.extra + arguments, options.output_dir),
                           variants, options.jobs)
    if results is None:
        return 1
    first = results[next(iter(variants))]
    print(f"{'run':24s}" + "".join(f"{label:>22s}" for _, label in quantities) + f"{'steps':>8s}{'it/step':>8s}"
          f"{'wall s':>8s}")
    for name in variants:
        values = results[name]
        cells = ""
        for key, _ in quantities:
            change = 100.0 * (values[key] / first[key] - 1.0)
            cells += (f"{values[key]:>13.3f}" if "damping" in key else f"{values[key]:>13.1f}") + (f" ({change:+5.1f}%)" if options.study == "sensitivity" else " " * 9)
        steps, iterations = values["dynamic_steps"], values["dynamic_newton_iterations"]
        print(f"{name:24s}{cells}{steps:8.0f}{iterations / steps:8.2f}{values['wall']:8.1f}")
    if options.study in ("phases", "rim"):
        cells = ""
        for key, _ in quantities:
            low, high = min(results[n][key] for n in variants), max(results[n][key] for n in variants)
            cells += f"{low:>8.1f}-{high:<8.1f}" + f"{100 * (high - low) / (high + low):4.1f}%"
        print(f"{'range, +- half of it':24s}{cells}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
