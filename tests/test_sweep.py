#!/usr/bin/python3
"""Tests of post/sweep.py and post/plot_sweep.py on tests/sweep_deck.lua (a cantilever under a
suddenly applied tip load): a parallel sweep with a failing and a check-failing run, resume,
the job-list and Slurm paths giving the same manifest, and the metric reductions.

    /usr/bin/python3 tests/test_sweep.py path/to/tirefe
"""
import csv
import importlib.util
import json
import os
import shutil
import subprocess
import sys

import numpy as np

import script_tests

TIREFE = None  # the tirefe binary: script_tests.run sets it from the command line
HERE = os.path.dirname(os.path.abspath(__file__))
POST = os.path.join(os.path.dirname(HERE), "post")
SWEEP = os.path.join(POST, "sweep.py")
DECK = os.path.join(HERE, "sweep_deck.lua")
FREQUENCY = 1.875104 ** 2 / (2 * np.pi) * np.sqrt(100.0)  # first bending mode of the deck's beam [Hz]

spec_loader = importlib.util.spec_from_file_location("sweep", SWEEP)
sweep = importlib.util.module_from_spec(spec_loader)
spec_loader.loader.exec_module(sweep)


def write_spec(folder, output, binary_in_spec=True):
    """Six grid runs, one run the deck refuses (failed), one whose self-check fails; the binary
    under test named in the spec, or else to be given by --tirefe."""
    spec = {
        "deck": DECK,
        "output": output,
        "grid": {"elements": [4, 6, 8], "load_parameter": [0.005, 0.01]},
        "runs": [{"elements": 4, "load_parameter": -1},
                 {"elements": 4, "load_parameter": 0.01, "max_deflection": 1e-6}],
        "jobs": 2,
        "metrics": {
            "peak_deflection": {"channel": "tip_uy", "reduce": "min"},
            "swing": {"channel": "tip_uy", "reduce": "peak_to_peak", "window": [0.5, 2.0]},
            "frequency": {"channel": "tip_uy", "reduce": "dominant_frequency"},
        },
    }
    if binary_in_spec:
        spec["tirefe"] = TIREFE
    path = os.path.join(folder, output + ".json")
    with open(path, "w") as f:
        json.dump(spec, f, indent=1)
    return path


def sweep_command(*arguments, environment=None):
    return subprocess.run([sys.executable, SWEEP, *arguments], capture_output=True, text=True, env=environment)


def manifest_rows(folder, output):
    with open(os.path.join(folder, output, "manifest.csv"), newline="") as f:
        return [{k: v for k, v in row.items() if k != "wall_time_s"} for row in csv.DictReader(f)]


def test_parallel_sweep_records_failures_and_metrics(folder):
    result = sweep_command("run", write_spec(folder, "parallel"))
    assert result.returncode == 1, result.stdout + result.stderr  # not every run is ok
    rows = {row["run_id"]: row for row in manifest_rows(folder, "parallel")}
    assert len(rows) == 8
    statuses = sorted(row["status"] for row in rows.values())
    assert statuses == ["check_failed", "failed"] + ["ok"] * 6, statuses
    failed = rows["elements-4_load_parameter--1"]
    assert failed["status"] == "failed"
    assert "load_parameter must be positive" in failed["message"], failed["message"]
    assert failed["peak_deflection"] == ""
    check = rows["elements-4_load_parameter-0.01_max_deflection-1e-06"]
    assert check["status"] == "check_failed" and "0 passed, 1 failed" in check["message"], check
    for row in rows.values():
        if row["status"] != "ok":
            continue
        # A suddenly applied load: the tip swings to twice the static P L^3 / (3 EI) at f1.
        load = float(row["load_parameter"])
        peak = float(row["peak_deflection"])
        assert abs(peak / (-2 * load / 3) - 1) < 0.03, (row["run_id"], peak)
        assert abs(float(row["swing"]) / (2 * load / 3) - 1) < 0.03, (row["run_id"], row["swing"])
        assert abs(float(row["frequency"]) / FREQUENCY - 1) < 0.02, (row["run_id"], row["frequency"])
    # Two at a time: some runs overlapped in time.
    with open(os.path.join(folder, "parallel", "manifest.json")) as f:
        records = json.load(f)
    spans = sorted((r["started_unix"], r["started_unix"] + r["wall_time_s"]) for r in records)
    assert any(later[0] < earlier[1] for earlier, later in zip(spans, spans[1:])), spans


def test_resume_skips_finished_runs(folder):
    spec = write_spec(folder, "parallel")  # the folder of the previous test
    status = os.path.join(folder, "parallel", "runs", "elements-6_load_parameter-0.01", "status.json")
    before = os.stat(status).st_mtime_ns
    result = sweep_command("run", spec)
    assert "8 already finished (skipped), 0 to run" in result.stdout, result.stdout
    assert os.stat(status).st_mtime_ns == before
    shutil.rmtree(os.path.dirname(status))
    result = sweep_command("run", spec)
    assert "7 already finished (skipped), 1 to run" in result.stdout, result.stdout
    assert os.path.exists(status)
    result = sweep_command("run", spec, "--retry-failed")
    assert "6 already finished (skipped), 2 to run" in result.stdout, result.stdout


def test_joblist_with_xargs_then_collect_gives_the_same_manifest(folder):
    spec = write_spec(folder, "joblist", binary_in_spec=False)  # each job line carries --tirefe on
    result = sweep_command("joblist", spec, "--tirefe", TIREFE)
    assert result.returncode == 0, result.stderr
    joblist = os.path.join(folder, "joblist", "joblist.txt")
    with open(joblist) as f:
        lines = f.read().splitlines()
    assert len(lines) == 8 and all(f"--tirefe {TIREFE}" in line for line in lines), lines
    with open(joblist) as f:
        subprocess.run(["xargs", "-P", "2", "-I{}", "sh", "-c", "{}"], stdin=f, capture_output=True)
    assert sweep_command("collect", spec).returncode == 1  # same statuses: not all ok
    assert manifest_rows(folder, "joblist") == manifest_rows(folder, "parallel")


def test_slurm_array_then_collect_gives_the_same_manifest(folder):
    spec = write_spec(folder, "slurm", binary_in_spec=False)
    assert sweep_command("slurm", spec, "--tirefe", TIREFE).returncode == 0
    script = os.path.join(folder, "slurm", "sweep.slurm")
    with open(script) as f:
        text = f.read()
    assert "#SBATCH --array=0-7" in text and f"--tirefe {TIREFE}" in text, text
    for task in range(8):  # what Slurm does: one task per array index
        subprocess.run(["bash", script], env={**os.environ, "SLURM_ARRAY_TASK_ID": str(task)}, capture_output=True)
    sweep_command("collect", spec)
    assert manifest_rows(folder, "slurm") == manifest_rows(folder, "parallel")


def test_metric_reductions_on_known_series(folder):
    time = np.sort(np.random.default_rng(7).uniform(0.0, 3.0, 400))  # uneven steps, as after step cuts
    signal = np.cos(2 * np.pi * 4.1 * time) + 0.3 * np.sin(2 * np.pi * 11.0 * time)
    assert abs(sweep.dominant_frequency(time, signal) - 4.1) < 0.01
    # The band excludes 4.1 Hz; the weaker line is read less exactly off the interpolated samples.
    assert abs(sweep.dominant_frequency(time, signal, [8.0, 20.0]) - 11.0) < 0.02
    ramp = np.linspace(0.0, 2.0, 21)
    assert abs(sweep.REDUCTIONS["mean"](ramp, 3 * ramp) - 3.0) < 1e-12
    assert sweep.REDUCTIONS["peak_to_peak"](ramp, np.sin(np.pi * ramp)) == 2 * np.sin(np.pi * 0.5)
    assert sweep.run_id({"b": 2, "a": "x y"}) == "a-x~y_b-2"


def test_plot_sweep_writes_a_png(folder):
    manifest = os.path.join(folder, "parallel", "manifest.csv")
    output = os.path.join(folder, "plot.png")
    # load_parameter = P L^2 / EI is a pure number: its unit is given.
    result = subprocess.run([sys.executable, os.path.join(POST, "plot_sweep.py"), manifest, "--x", "load_parameter",
                             "--x-unit", "1", "--y", "peak_deflection", "--group", "elements", "-o", output],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    with open(output, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_plot_sweep_labels_every_axis_with_its_unit(folder):
    """The runs record each metric's unit (the channel's, Hz for a frequency) in manifest.json;
    a parameter's unit is read off its name or given."""
    loader = importlib.util.spec_from_file_location("plot_sweep", os.path.join(POST, "plot_sweep.py"))
    plot_sweep = importlib.util.module_from_spec(loader)
    loader.loader.exec_module(plot_sweep)
    units = plot_sweep.recorded_units(os.path.join(folder, "parallel", "manifest.csv"))
    assert plot_sweep.axis_label("peak_deflection", units, None) == "peak_deflection [m]"
    assert plot_sweep.axis_label("swing", units, None) == "swing [m]"
    assert plot_sweep.axis_label("frequency", units, None) == "frequency [Hz]"
    assert plot_sweep.axis_label("wall_time_s", units, None) == "wall_time_s [s]"
    assert plot_sweep.axis_label("speed_kmh", units, None) == "speed_kmh [km/h]"
    assert plot_sweep.axis_label("pressure_kPa", units, None) == "pressure_kPa [kPa]"
    assert plot_sweep.axis_label("load_parameter", units, "1") == "load_parameter [1]"
    assert plot_sweep.axis_label("load_parameter", units, None) == "load_parameter [unit not recorded]"


def test_the_documented_cleat_sweep_runs_as_written(folder):
    """docs/sweeps.md's spec is inputs/sweeps/cleat_speeds.json, and every run of it is ok with every metric."""
    root = os.path.dirname(HERE)
    spec = os.path.join(root, "inputs", "sweeps", "cleat_speeds.json")
    with open(os.path.join(root, "docs", "sweeps.md")) as f:
        documented = f.read().split("```json\n", 1)[1].split("```", 1)[0]
    with open(spec) as f:
        assert f.read() == documented
    output = os.path.join(folder, "cleat_speeds")
    result = sweep_command("run", spec, "--output", output, "--tirefe", TIREFE)  # the build under test
    assert result.returncode == 0, result.stdout + result.stderr
    with open(os.path.join(output, "manifest.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 6 and all(row["status"] == "ok" for row in rows), rows
    for row in rows:
        assert float(row["final_time"]) == 3.2
        assert 75 < float(row["fz_leaving_Hz"]) < 95, row  # the vertical mode, not the passage rate
        assert 40 < float(row["fz_dominant_Hz"]) < 200, row
        assert float(row["fz_max"]) > 5000 and float(row["fx_peak_to_peak"]) > 1000, row
    row = next(r for r in rows if r["speed_kmh"] == "51.3" and r["pressure_kpa"] == "208")
    assert abs(float(row["fx_leaving_Hz"]) - 35.4) < 1.0, row  # docs/drum_cleat.md, short protocol


if __name__ == "__main__":
    script_tests.run(globals(), "tirefe_sweep_")  # in order: later tests reuse the first sweep's folder
