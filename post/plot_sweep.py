#!/usr/bin/python3
"""Plots one column of a sweep manifest against another, one line per value of a third
(runs without a value, e.g. failed ones, are left out). Writes <manifest>_<y>_vs_<x>.png
next to the manifest unless -o names the PNG.

    /usr/bin/python3 post/plot_sweep.py results/sweep/manifest.csv --x load_parameter --y peak_deflection \\
        [--group elements] [--x-unit UNIT] [--y-unit UNIT] [-o plot.png]

Axis units: as given, else as the runs recorded them (manifest.json: the unit of each
metric's result or channel), else read off a parameter's name (speed_kmh: km/h).
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


# Units read off a parameter's name, e.g. speed_kmh or pressure_kpa (deck parameters carry
# no unit in the result files).
NAME_SUFFIX_UNITS = {"kmh": "km/h", "kpa": "kPa", "mpa": "MPa", "hz": "Hz", "s": "s", "ms": "ms", "n": "N",
                     "m": "m", "mm": "mm", "deg": "deg", "kg": "kg"}


def recorded_units(manifest):
    """Units of the metrics as the runs recorded them (manifest.json beside manifest.csv)."""
    path = os.path.join(os.path.dirname(manifest), "manifest.json")
    units = {"wall_time_s": "s"}
    if os.path.exists(path):
        with open(path) as f:
            for record in json.load(f):
                for name, unit in record.get("units", {}).items():
                    units.setdefault(name, unit)
    return units


def axis_label(column, units, given):
    """'column [unit]': the unit given on the command line, recorded by the runs, or read off the
    column's name; "unit not recorded" if none of them says."""
    unit = given or units.get(column)
    if not unit and "_" in column:
        unit = NAME_SUFFIX_UNITS.get(column.rsplit("_", 1)[-1].lower())
    return f"{column} [{unit or 'unit not recorded'}]"


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("manifest", help="manifest.csv written by post/sweep.py")
    parser.add_argument("--x", required=True, help="column on the horizontal axis (a parameter)")
    parser.add_argument("--y", required=True, help="column on the vertical axis (a metric)")
    parser.add_argument("--group", help="one line per value of this column")
    parser.add_argument("--x-unit", help="unit of the x column (default: as the runs recorded it, or from its name)")
    parser.add_argument("--y-unit", help="unit of the y column (default: as the runs recorded it, or from its name)")
    parser.add_argument("-o", "--output", help="PNG to write")
    arguments = parser.parse_args()

    with open(arguments.manifest, newline="") as f:
        rows = list(csv.DictReader(f))
    for column in filter(None, (arguments.x, arguments.y, arguments.group)):
        if rows and column not in rows[0]:
            sys.exit(f"plot_sweep: no column '{column}' in {arguments.manifest} (columns: {', '.join(rows[0])})")

    lines = {}
    for row in rows:
        x, y = number(row[arguments.x]), number(row[arguments.y])
        if x is None or y is None:
            continue
        group = row[arguments.group] if arguments.group else ""
        lines.setdefault(group, []).append((x, y))
    if not lines:
        sys.exit(f"plot_sweep: no run has numbers in both '{arguments.x}' and '{arguments.y}'")

    figure, axis = plt.subplots(figsize=(7, 4.5))
    for group in sorted(lines, key=lambda g: (number(g) is None, number(g) or 0.0, g)):
        points = sorted(lines[group])
        label = f"{arguments.group} = {group}" if arguments.group else None
        axis.plot([p[0] for p in points], [p[1] for p in points], "o-", label=label)
    units = recorded_units(arguments.manifest)
    axis.set_xlabel(axis_label(arguments.x, units, arguments.x_unit))
    axis.set_ylabel(axis_label(arguments.y, units, arguments.y_unit))
    axis.grid(True, alpha=0.3)
    if arguments.group:
        axis.legend(fontsize=8)
    figure.tight_layout()
    stem = os.path.splitext(arguments.manifest)[0]
    output = arguments.output or f"{stem}_{arguments.y}_vs_{arguments.x}.png"
    figure.savefig(output, dpi=120)
    plt.close(figure)
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
