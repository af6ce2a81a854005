#!/usr/bin/env python3
"""Convergence of the pothole's strikes (docs/vehicle.md, "The strike"): inputs/vehicle_pothole.lua
for a tire set, at its own time step through the chuckhole and that step halved twice, at a
Newton tolerance 100 times tighter and with 200 elements instead of 100. For each left wheel
it prints the strike's time, its raw and 200 Hz peaks, the change of each from the finest
step's, and the strike's energy account (the road's work on the tire over the strike, the
balance's error over it and its largest error in one step).

    /usr/bin/python3 bench/pothole_study.py [--tire tires.145SR12_tread_layer] [--jobs 2]
"""
import argparse
import os
import subprocess
import sys
import time

import h5py

from deck_runs import run_variants

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VARIANTS = {
    "reference": [],
    "dt_pothole / 2": ["dt_pothole=1e-4"],
    "dt_pothole / 4": ["dt_pothole=5e-5"],
    "tolerance / 100": ["newton_tolerance=1e-8"],
    "200 elements": ["elements=200"],
}
FINEST = "dt_pothole / 4"
PEAKS = [("strike_fz_peak", "Fz peak"), ("strike_fx_low", "Fx low"), ("strike_fx_high", "Fx high"),
         ("strike_fz_peak_filtered", "Fz 200 Hz"), ("strike_fx_low_filtered", "Fx low 200 Hz"),
         ("strike_fx_high_filtered", "Fx high 200 Hz")]


def run(name, arguments, output_dir):
    folder = os.path.join(output_dir, "".join(c if c.isalnum() else "_" for c in name))
    command = [os.path.join(ROOT, "build", "tirefe"), os.path.join(ROOT, "inputs", "vehicle_pothole.lua"), "--quiet",
               "--output-dir", folder] + arguments
    start = time.monotonic()
    finished = subprocess.run(command, capture_output=True, text=True)
    if finished.returncode != 0:
        return name, {"error": finished.stderr.strip().splitlines()[-1] if finished.stderr.strip() else "failed"}
    values = {"wall": time.monotonic() - start}
    for corner in ("LF", "LR"):
        with h5py.File(os.path.join(folder, f"vehicle_pothole_{corner}.h5"), "r") as result:
            values[corner] = dict(result["results"].attrs)
    return name, values


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--tire", default="tires.145SR12")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--output-dir", default=os.path.join(ROOT, "results", "pothole_study"))
    options = parser.parse_args()
    results = run_variants(lambda name, arguments: run(name, [f"tire={options.tire}"] + arguments, options.output_dir),
                           VARIANTS, options.jobs)
    if results is None:
        return 1
    for corner in ("LF", "LR"):
        finest = results[FINEST][corner]
        print(f"{corner}, {options.tire}: peaks [N] and their change from the finest step's")
        print(f"{'run':18s}{'strike s':>10s}" + "".join(f"{label:>22s}" for _, label in PEAKS) +
              f"{'road work J':>13s}{'error J':>9s}{'step J':>8s}{'wall s':>8s}")
        for name in VARIANTS:
            values = results[name][corner]
            cells = "".join(f"{values[key]:>13.0f} ({100 * (values[key] / finest[key] - 1):+5.1f}%)" for key, _ in PEAKS)
            print(f"{name:18s}{values['strike_time']:10.4f}{cells}{values['strike_surface_work']:13.1f}"
                  f"{values['strike_energy_error']:9.2f}{values['strike_step_error']:8.3f}{results[name]['wall']:8.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
