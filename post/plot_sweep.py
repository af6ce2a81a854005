#!/usr/bin/python3
"""Plots one column of a sweep manifest against another, one line per value of a third
(runs without a value, e.g. failed ones, are left out). Writes <manifest>_<y>_vs_<x>.png
next to the manifest unless -o names the PNG.

    /usr/bin/python3 post/plot_sweep.py results/sweep/manifest.csv --x load_parameter --y peak_deflection \\
        [--group elements] [-o plot.png]
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


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
    axis.set_xlabel(arguments.x)
    axis.set_ylabel(arguments.y)
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
