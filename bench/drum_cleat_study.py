#!/usr/bin/env python3
"""Sensitivity of the drum-cleat results to the discretisation and the integrator.

Runs inputs/drum_cleat.lua in variants (the reference, time steps halved, 150 elements,
Newmark instead of HHT) and prints the ringing frequencies and peak-to-peak forces of the
full-speed cleat passage with their change from the reference, plus the cost of each run.
By default the short protocol (0.5 s spin-up: the same full-speed impact, docs/drum_cleat.md);
--full runs the 8 s protocol.

    /usr/bin/python3 bench/drum_cleat_study.py [--full] [--jobs 2] [extra key=value ...]
"""
import argparse
import concurrent.futures
import os
import subprocess
import sys
import time

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHORT = ["spin_up_time=0.5", "end_time=3.0"]
VARIANTS = {
    "reference": [],
    "dt / 2": ["dt=2.5e-4", "dt_cleat=1.25e-4"],
    "150 elements": ["elements=150"],
    "150 el, dt / 2": ["elements=150", "dt=2.5e-4", "dt_cleat=1.25e-4"],
    "Newmark g=0.6": ["integrator=newmark", "newmark_gamma=0.6"],
    "Newmark g=0.5": ["integrator=newmark", "newmark_gamma=0.5"],
}
QUANTITIES = [("fz_on_top_Hz", "Fz on top [Hz]"), ("fz_leaving_Hz", "Fz leaving [Hz]"),
              ("fx_from_hit_Hz", "Fx from hit [Hz]"), ("fx_leaving_Hz", "Fx leaving [Hz]"),
              ("fz_peak_to_peak", "Fz p-p [N]"), ("fx_peak_to_peak", "Fx p-p [N]")]


def run(name, arguments, output_dir):
    file_name = name.replace(" ", "_").replace("/", "") + ".h5"
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
    parser.add_argument("--full", action="store_true", help="the 8 s protocol instead of the short one")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--output-dir", default=os.path.join(ROOT, "results", "drum_cleat_study"))
    parser.add_argument("extra", nargs="*", help="key=value for every variant")
    options = parser.parse_args()
    os.makedirs(options.output_dir, exist_ok=True)
    protocol = [] if options.full else SHORT
    with concurrent.futures.ThreadPoolExecutor(options.jobs) as pool:
        futures = [pool.submit(run, name, protocol + options.extra + arguments, options.output_dir)
                   for name, arguments in VARIANTS.items()]
        results = dict(future.result() for future in futures)

    reference = results["reference"]
    print(f"{'variant':14s}" + "".join(f"{label:>22s}" for _, label in QUANTITIES) +
          f"{'steps':>8s}{'it/step':>8s}{'wall s':>8s}")
    for name in VARIANTS:
        values = results[name]
        if "error" in values:
            print(f"{name:14s}  failed: {values['error']}")
            continue
        cells = ""
        for key, _ in QUANTITIES:
            change = 100.0 * (values[key] / reference[key] - 1.0)
            cells += f"{values[key]:>13.1f}" + (f" ({change:+5.1f}%)" if name != "reference" else " " * 9)
        steps, iterations = values["dynamic_steps"], values["dynamic_newton_iterations"]
        print(f"{name:14s}{cells}{steps:8.0f}{iterations / steps:8.2f}{values['wall']:8.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
