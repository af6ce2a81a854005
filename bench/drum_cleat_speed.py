#!/usr/bin/env python3
"""Run time of the main job: inputs/drum_cleat.lua, the literal 8 s protocol.

Runs the deck 'runs' times with each tirefe binary given (alternately, so that a noisy
shared machine loads them alike) and prints, per run and as the minimum over the runs:
the wall time and the CPU time (user + system) of the whole deck, the CPU time of the run's
own thread (the process's first; sampled from /proc every 10 ms: the result file's writer
thread works beside it, and the wall time follows this thread), the dynamic steps, Newton
iterations per step and the CPU time per Newton iteration of the dynamic run (from the
deck's /results: dynamic_steps, dynamic_newton_iterations, dynamic_cpu_time). On a shared
machine the CPU time is the steadier of the two.

    /usr/bin/python3 bench/drum_cleat_speed.py [--runs 2] [--tirefe build/tirefe ...] [key=value ...]

Give --tirefe twice (a build before a change and one after) to compare them; key=value
goes to every run (tire=tires.145SR12 for the paper's model). A binary in a checkout's
build/ folder runs that checkout's deck, so that each build runs the deck of its own code.
"""
import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def deck_of(tirefe):
    """The deck of the checkout whose build/ folder holds the binary, or this one's."""
    own = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(tirefe))), "inputs", "drum_cleat.lua")
    return own if os.path.isfile(own) else os.path.join(ROOT, "inputs", "drum_cleat.lua")


def thread_cpu(pid):
    """CPU time [s] so far of the process's first thread (the run's own), or None once it is gone."""
    try:
        with open(f"/proc/{pid}/task/{pid}/stat") as stat:
            fields = stat.read().rsplit(")", 1)[1].split()
    except OSError:
        return None
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def run(tirefe, extra, output_dir):
    command = [tirefe, deck_of(tirefe), "--quiet", "--output-dir", output_dir] + extra
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    with tempfile.TemporaryFile("w+") as errors:
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=errors, text=True)
        # The run's thread, sampled until it ends (the last sample at most 10 ms early).
        run_thread = 0.0
        while process.poll() is None:
            run_thread = thread_cpu(process.pid) or run_thread
            time.sleep(0.01)
        wall = time.monotonic() - start
        errors.seek(0)
        stderr = errors.read()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu_whole = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if process.returncode != 0:
        sys.exit(f"{' '.join(command)} failed:\n{stderr}")
    with h5py.File(os.path.join(output_dir, "drum_cleat.h5"), "r") as result:
        values = result["results"].attrs
        steps, iterations = float(values["dynamic_steps"]), float(values["dynamic_newton_iterations"])
        cpu = float(values["dynamic_cpu_time"])
    return {"wall": wall, "cpu": cpu_whole, "run_thread": run_thread, "steps": steps, "per_step": iterations / steps,
            "per_iteration": 1e6 * cpu / iterations}


def line(label, measured):
    return (f"{label:40s} {measured['wall']:7.2f} s {measured['cpu']:7.2f} s {measured['run_thread']:7.2f} s"
            f" {measured['steps']:7.0f} {measured['per_step']:7.2f} {measured['per_iteration']:7.1f} us")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=2)
    parser.add_argument("--tirefe", action="append", help="a tirefe binary (default build/tirefe); repeatable")
    parser.add_argument("extra", nargs="*", help="key=value for every run")
    options = parser.parse_args()
    binaries = options.tirefe or [os.path.join(ROOT, "build", "tirefe")]
    print(f"{'run':40s} {'wall':>9s} {'CPU':>9s} {'thread':>9s} {'steps':>7s} {'it/step':>7s} {'per iteration':>10s}")
    results = {binary: [] for binary in binaries}
    with tempfile.TemporaryDirectory() as folder:
        for repeat in range(options.runs):
            for binary in binaries:
                measured = run(binary, options.extra, folder)
                results[binary].append(measured)
                print(line(f"{binary} #{repeat + 1}", measured), flush=True)
    for binary, runs in results.items():
        best = {key: min(run[key] for run in runs) for key in runs[0]}
        print(line(f"{binary}, minimum of {len(runs)}", best))
    return 0


if __name__ == "__main__":
    sys.exit(main())
