#!/usr/bin/python3
"""Parameter sweeps of a tirefe deck: one run per combination of parameter values, run in
parallel, each in its own output folder, summarised in a manifest (docs/sweeps.md).

    sweep.py run SPEC.json [--jobs N] [--retry-failed]   run every combination not yet finished
    sweep.py joblist SPEC.json                           write OUTPUT/joblist.txt, one command per line
    sweep.py slurm SPEC.json                             write OUTPUT/sweep.slurm, a Slurm job array
    sweep.py collect SPEC.json                           build OUTPUT/manifest.csv and manifest.json
    sweep.py one SPEC.json RUN_ID                        run one combination (joblist and slurm call this)

Each takes --output DIR (the sweep's folder) and --tirefe PATH (the binary) over the spec's.
"""
import argparse
import concurrent.futures
import csv
import glob
import hashlib
import itertools
import json
import os
import re
import shlex
import subprocess
import sys
import time

import h5py
import numpy as np

SCRIPT = os.path.abspath(__file__)
REPOSITORY = os.path.dirname(os.path.dirname(SCRIPT))
SPEC_KEYS = {"deck", "tirefe", "output", "grid", "runs", "jobs", "metrics", "timeout", "slurm"}
FINISHED = ("ok", "check_failed", "failed")
EXIT_STATUS = {0: "ok", 3: "check_failed"}  # tirefe: 1 deck or model error, 2 usage error


class MetricError(Exception):
    pass


def value_text(value):
    """A parameter value as tirefe reads it on its command line (key=value)."""
    return json.dumps(value) if isinstance(value, (bool, int, float)) else str(value)


def run_id(parameters):
    """A stable folder name from the parameters (independent of their order)."""
    text = "_".join(f"{key}-{value_text(value)}" for key, value in sorted(parameters.items())) or "defaults"
    text = re.sub(r"[^A-Za-z0-9._+-]", "~", text)
    if len(text) <= 80:
        return text
    digest = hashlib.sha1(json.dumps(parameters, sort_keys=True).encode()).hexdigest()[:10]
    return text[:60] + "-" + digest


class Spec:
    """A sweep specification (JSON); relative paths are taken from the spec's folder."""

    def __init__(self, path):
        self.path = os.path.abspath(path)
        with open(self.path) as f:
            raw = json.load(f)
        unknown = sorted(set(raw) - SPEC_KEYS)
        if unknown or "deck" not in raw:
            sys.exit(f"sweep: {path}: " + (f"unknown keys {unknown}" if unknown else "'deck' is required"))
        folder = os.path.dirname(self.path)
        stem = os.path.splitext(os.path.basename(self.path))[0]
        self.deck = os.path.join(folder, raw["deck"])
        default_tirefe = os.path.join(REPOSITORY, "build", "tirefe")
        self.tirefe = os.path.join(folder, raw["tirefe"]) if "tirefe" in raw else default_tirefe
        self.output = os.path.join(folder, raw.get("output", stem))
        self.output_overridden = False
        self.tirefe_overridden = False
        self.jobs = int(raw.get("jobs", os.cpu_count() or 1))
        self.timeout = raw.get("timeout")
        self.metrics = raw.get("metrics", {})
        self.slurm = raw.get("slurm", {})
        grid = raw.get("grid", {})
        combinations = [dict(zip(grid, values)) for values in itertools.product(*grid.values())] if grid else []
        self.runs = {}
        for parameters in combinations + list(raw.get("runs", [])):
            self.runs.setdefault(run_id(parameters), parameters)  # a duplicate runs once
        if not self.runs:
            sys.exit(f"sweep: {path}: no runs (give a 'grid' and/or a list of 'runs')")

    def folder(self, identifier):
        return os.path.join(self.output, "runs", identifier)

    def command(self, identifier):
        parameters = [f"{key}={value_text(value)}" for key, value in self.runs[identifier].items()]
        return [self.tirefe, self.deck, *parameters, "--output-dir", self.folder(identifier)]

    def record(self, identifier):
        """The finished run's record (status.json), or None."""
        try:
            with open(os.path.join(self.folder(identifier), "status.json")) as f:
                return json.load(f)
        except (OSError, ValueError):
            return None

    def pending(self, retry_failed=False):
        """Runs not finished yet (with retry_failed, also those that did not succeed)."""
        done = ("ok",) if retry_failed else FINISHED
        return [i for i in self.runs if (self.record(i) or {}).get("status") not in done]


# ---- metrics: reductions of history channels ------------------------------------------

def dominant_frequency(time, values, band=None):
    """Frequency of the largest peak of the spectrum within 'band' [Hz] (default: above 0):
    resampled uniformly, straight line removed, Hann window, zero-padded, the peak located
    between bins by a parabola through its log magnitudes."""
    if values.size < 4:
        raise MetricError("too few samples for a spectrum")
    step = np.median(np.diff(time))
    uniform = np.arange(time[0], time[-1] + 0.5 * step, step)
    samples = np.interp(uniform, time, values)
    samples = samples - np.polyval(np.polyfit(uniform - uniform[0], samples, 1), uniform - uniform[0])
    samples = samples * np.hanning(samples.size)
    size = 8 * 2 ** int(np.ceil(np.log2(samples.size)))  # zero padding refines the peak
    spectrum = np.log(np.abs(np.fft.rfft(samples, size)) + 1e-300)
    frequencies = np.fft.rfftfreq(size, step)
    low, high = band if band else (0.0, frequencies[-1])
    inside = np.nonzero((frequencies >= low) & (frequencies <= high))[0]
    inside = inside[(inside > 0) & (inside < frequencies.size - 1)]
    if inside.size == 0:
        raise MetricError(f"no frequency of the spectrum in the band {low}-{high} Hz")
    peak = int(inside[np.argmax(spectrum[inside])])
    below, at, above = spectrum[peak - 1:peak + 2]  # a parabola through the peak's log magnitudes
    offset = 0.5 * (below - above) / (below - 2 * at + above) if below - 2 * at + above < 0 else 0.0
    return float((peak + offset) / (size * step))


def time_mean(time, values):
    trapezoid = getattr(np, "trapezoid", None) or np.trapz  # renamed in numpy 2
    return float(trapezoid(values, time) / (time[-1] - time[0])) if values.size > 1 else float(values[0])


REDUCTIONS = {
    "max": lambda time, values: float(values.max()),
    "min": lambda time, values: float(values.min()),
    "peak_to_peak": lambda time, values: float(values.max() - values.min()),
    "final": lambda time, values: float(values[-1]),
    "mean": time_mean,
    "dominant_frequency": dominant_frequency,
}


def metric_unit(metric, result):
    """The unit of a metric's value: the deck's unit of a result, Hz for a frequency, else the
    channel's unit; None if the file records none."""
    if "result" in metric:
        unit = result["results"].attrs.get(metric["result"] + "_unit") if "results" in result else None
    elif metric["reduce"] == "dominant_frequency":
        unit = "Hz"
    else:
        unit = result["history"][metric["channel"]].attrs.get("unit")
    return unit.decode() if isinstance(unit, bytes) else unit


def metric_value(metric, folder):
    """(value, unit) of a metric of the run in 'folder'."""
    if "result" not in metric and metric.get("reduce") not in REDUCTIONS:
        raise MetricError(f"'reduce' must be one of {', '.join(REDUCTIONS)}, or name a 'result'")
    if "file" in metric:
        path = os.path.join(folder, metric["file"])
    else:
        files = sorted(glob.glob(os.path.join(folder, "*.h5")))
        if len(files) != 1:
            raise MetricError(f"{len(files)} HDF5 files in the run folder: name one with 'file'")
        path = files[0]
    with h5py.File(path, "r") as result:
        if "result" in metric:  # a value the deck recorded with model:result
            values = result["results"].attrs if "results" in result else {}
            if metric["result"] not in values:
                raise MetricError(f"no result '{metric['result']}' in {os.path.basename(path)}")
            return float(values[metric["result"]]), metric_unit(metric, result)
        channel = metric["channel"]
        if channel not in result["history"]:
            raise MetricError(f"no history channel '{channel}' in {os.path.basename(path)}")
        time, values = result["history/time"][:], result["history"][channel][:]
        unit = metric_unit(metric, result)
    if "window" in metric:
        start, end = metric["window"]
        inside = (time >= start) & (time <= end)
        time, values = time[inside], values[inside]
    if values.size == 0:
        raise MetricError("no samples in the time window")
    if metric["reduce"] == "dominant_frequency":
        return dominant_frequency(time, values, metric.get("band")), unit
    return REDUCTIONS[metric["reduce"]](time, values), unit


# ---- running --------------------------------------------------------------------------

def last_line(path):
    with open(path, errors="replace") as f:
        lines = [line.strip() for line in f if line.strip()]
    errors = [line for line in lines if line.startswith("tirefe: ")]
    return (errors or lines or [""])[-1]


def execute(spec, identifier):
    """Runs one combination and writes its status.json; returns the record."""
    folder = spec.folder(identifier)
    os.makedirs(folder, exist_ok=True)
    command = spec.command(identifier)
    log_path = os.path.join(folder, "log.txt")
    started, start = time.time(), time.monotonic()
    with open(log_path, "w") as log:
        log.write("$ " + shlex.join(command) + "\n")
        log.flush()
        try:
            code = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, timeout=spec.timeout).returncode
        except subprocess.TimeoutExpired:
            code = None
            log.write(f"sweep: stopped after the time limit of {spec.timeout} s\n")
        except OSError as error:
            code = None
            log.write(f"sweep: cannot run {command[0]}: {error}\n")
    record = {"run_id": identifier, "parameters": spec.runs[identifier], "status": EXIT_STATUS.get(code, "failed"),
              "exit_code": code, "started_unix": round(started, 3), "wall_time_s": round(time.monotonic() - start, 3),
              "message": "", "metrics": {}, "units": {}}
    if record["status"] != "ok":
        record["message"] = last_line(log_path)
    if record["status"] != "failed":
        for name, metric in spec.metrics.items():
            try:
                record["metrics"][name], unit = metric_value(metric, folder)
                if unit:
                    record["units"][name] = unit
            except (MetricError, OSError, KeyError, ValueError) as error:
                record["metrics"][name] = None
                record["message"] = (record["message"] + "; " if record["message"] else "") + f"metric {name}: {error}"
    temporary = os.path.join(folder, "status.json.tmp")
    with open(temporary, "w") as f:
        json.dump(record, f, indent=1)
    os.replace(temporary, os.path.join(folder, "status.json"))  # whole or absent, never half written
    return record


def write_manifest(spec):
    """manifest.json (every record) and manifest.csv (one row per run, in spec order)."""
    records = []
    for identifier, parameters in spec.runs.items():
        missing = {"run_id": identifier, "parameters": parameters, "status": "not_run", "exit_code": None,
                   "started_unix": None, "wall_time_s": None, "message": "", "metrics": {}}
        records.append(spec.record(identifier) or missing)
    parameter_names = list(dict.fromkeys(key for parameters in spec.runs.values() for key in parameters))
    header = ["run_id", "status", *parameter_names, *spec.metrics, "wall_time_s", "message"]
    os.makedirs(spec.output, exist_ok=True)
    with open(os.path.join(spec.output, "manifest.json"), "w") as f:
        json.dump(records, f, indent=1)
    with open(os.path.join(spec.output, "manifest.csv"), "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        for record in records:
            row = {**record["parameters"], **record["metrics"], **record}
            writer.writerow(["" if row.get(column) is None else row.get(column, "") for column in header])
    counts = {status: sum(r["status"] == status for r in records) for status in (*FINISHED, "not_run")}
    print(f"{counts['ok']} ok, {counts['failed']} failed, {counts['check_failed']} check_failed, "
          f"{counts['not_run']} not run; manifest in {spec.output}")
    return records


def command_run(spec, arguments):
    if not os.access(spec.tirefe, os.X_OK):
        sys.exit(f"sweep: no tirefe binary at {spec.tirefe} (build it, or set 'tirefe' in the spec or --tirefe)")
    pending = spec.pending(arguments.retry_failed)
    jobs = arguments.jobs or spec.jobs
    print(f"sweep: {len(spec.runs)} runs, {len(spec.runs) - len(pending)} already finished (skipped), "
          f"{len(pending)} to run, {jobs} at a time")
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        for future in concurrent.futures.as_completed([pool.submit(execute, spec, i) for i in pending]):
            record = future.result()
            print(f"  {record['status']:<12} {record['run_id']}  {record['wall_time_s']:.2f} s  {record['message']}",
                  flush=True)
    records = write_manifest(spec)
    return 0 if all(record["status"] == "ok" for record in records) else 1


def command_one(spec, arguments):
    if arguments.run_id not in spec.runs:
        sys.exit(f"sweep: {spec.path} has no run '{arguments.run_id}'")
    record = execute(spec, arguments.run_id)
    print(f"{record['status']} {record['run_id']} {record['message']}")
    return 0 if record["status"] == "ok" else 1


def script_command(spec, command):
    """This script's command line for a subcommand on the spec, with any --output and --tirefe override."""
    return [sys.executable, SCRIPT, command, spec.path, *(["--output", spec.output] if spec.output_overridden else []),
            *(["--tirefe", spec.tirefe] if spec.tirefe_overridden else [])]


def one_command(spec, identifier):
    return shlex.join(script_command(spec, "one") + [identifier])


def command_joblist(spec, arguments):
    os.makedirs(spec.output, exist_ok=True)
    path = os.path.join(spec.output, "joblist.txt")
    pending = spec.pending()
    with open(path, "w") as f:
        f.writelines(one_command(spec, identifier) + "\n" for identifier in pending)
    print(f"wrote {path} ({len(pending)} runs); e.g. xargs -d '\\n' -P {spec.jobs} -I{{}} sh -c {{}} < {path}, "
          f"then: {shlex.join(script_command(spec, 'collect'))}")
    return 0


def command_slurm(spec, arguments):
    pending = spec.pending()
    if not pending:
        print("sweep: every run has finished; nothing to submit")
        return 0
    os.makedirs(spec.output, exist_ok=True)
    path = os.path.join(spec.output, "sweep.slurm")
    options = [f"--job-name={os.path.splitext(os.path.basename(spec.path))[0]}", f"--array=0-{len(pending) - 1}",
               f"--output={os.path.join(spec.output, 'slurm-%A_%a.out')}", "--cpus-per-task=1"]
    options += [f"--{key}={value}" for key, value in spec.slurm.items()]
    lines = ["#!/bin/bash", *(f"#SBATCH {option}" for option in options),
             f"# One sweep run per array task. When the array has finished: "
             f"{shlex.join(script_command(spec, 'collect'))}",
             "RUNS=(" + " ".join(shlex.quote(identifier) for identifier in pending) + ")",
             f"exec {shlex.join(script_command(spec, 'one'))} \"${{RUNS[$SLURM_ARRAY_TASK_ID]}}\""]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"wrote {path} ({len(pending)} array tasks); submit with: sbatch {path}")
    return 0


def command_collect(spec, arguments):
    records = write_manifest(spec)
    return 0 if all(record["status"] == "ok" for record in records) else 1


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)
    for name, handler in (("run", command_run), ("joblist", command_joblist), ("slurm", command_slurm),
                          ("collect", command_collect), ("one", command_one)):
        sub = commands.add_parser(name)
        sub.add_argument("spec", help="sweep specification (JSON)")
        sub.add_argument("--output", help="the sweep's folder instead of the spec's 'output'")
        sub.add_argument("--tirefe", help="the tirefe binary instead of the spec's 'tirefe'")
        sub.set_defaults(handler=handler)
        if name == "run":
            sub.add_argument("--jobs", type=int, help="runs at a time (default: the spec's, else the CPU count)")
            sub.add_argument("--retry-failed", action="store_true", help="run failed and check_failed runs again")
        if name == "one":
            sub.add_argument("run_id")
    arguments = parser.parse_args()
    spec = Spec(arguments.spec)
    if arguments.output:
        spec.output, spec.output_overridden = os.path.abspath(arguments.output), True
    if arguments.tirefe:
        spec.tirefe, spec.tirefe_overridden = os.path.abspath(arguments.tirefe), True
    sys.exit(arguments.handler(spec, arguments))


if __name__ == "__main__":
    main()
