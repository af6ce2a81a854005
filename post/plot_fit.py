#!/usr/bin/python3
"""Plots a fit written by tirefe.fit{ output = ... }: the measured data against the fitted
model (a continuous curve when the fit was given curve_points), in the data file's units,
the objective per iteration, and every parameter per iteration (relative to its initial
value). Writes <file>_fit.png next to the file unless -o names the PNG.

    /usr/bin/python3 post/plot_fit.py results/k_sw_fit.h5 [-o fit.png]
"""
import argparse
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def fitted_values_line(fit):
    names = [text(name) for name in fit["parameters/name"][:]]
    values = fit["parameters/value"][:]
    errors = fit["parameters/standard_error"][:]
    parts = []
    for name, value, error in zip(names, values, errors):
        if np.isnan(value):
            parts.append(f"{name}: -")
        elif np.isnan(error):
            parts.append(f"{name} = {value:.6g}")
        else:
            parts.append(f"{name} = {value:.6g} ± {error:.2g}")
    return ", ".join(parts)


def in_file_units(dataset, values):
    """SI values of /fit/x or /fit/data in the data file's unit, and the axis label with that
    unit (e.g. deflection [mm])."""
    label = text(dataset.attrs.get("label", "value"))
    unit = dataset.attrs.get("file_unit")
    if unit is None:
        return values, label if "[" in label else f"{label} [-]"
    return values / float(dataset.attrs.get("to_si", 1.0)), f"{label.split(' [')[0]} [{text(unit)}]"


def plot_curve(axis, fit):
    """The data, and the fitted model as a continuous curve where the fit evaluated it on a
    fine grid (/fit/curve), else through its values at the data points; in the data's units."""
    data, y_label = in_file_units(fit["data"], fit["data"][:])
    prediction, _ = in_file_units(fit["data"], fit["prediction"][:])
    if "x" in fit:
        x, x_label = in_file_units(fit["x"], fit["x"][:])
    else:
        x, x_label = np.arange(1, data.size + 1), "data point [-]"
    order = np.argsort(x, kind="stable")
    axis.plot(x, data, "o", label="data")
    if "curve" in fit and "x" in fit:
        curve_x, _ = in_file_units(fit["x"], fit["curve/x"][:])
        curve_y, _ = in_file_units(fit["data"], fit["curve/prediction"][:])
        axis.plot(curve_x, curve_y, "-", label="fitted model")
        if prediction.size == data.size:
            axis.plot(x[order], prediction[order], "x", color="tab:orange", label="fitted model at the data points")
    elif prediction.size == data.size:
        axis.plot(x[order], prediction[order], "x--", label="fitted model at the data points (joined)")
    axis.set_xlabel(x_label)
    axis.set_ylabel(y_label)
    axis.grid(True, alpha=0.3)
    axis.legend()


def plot_history(objective_axis, parameter_axis, fit):
    history = fit["history"]
    iteration = history["iteration"][:]
    objective = history["objective"][:]
    positive = objective > 0
    objective_axis.semilogy(iteration[positive], objective[positive], ".-")
    label = text(fit["data"].attrs.get("label", ""))  # with the SI unit the fit worked in
    objective_axis.set_ylabel(f"objective S [{label.split('[')[-1].rstrip(']')}^2]" if "[" in label
                              else "objective S [-]")
    objective_axis.grid(True, alpha=0.3)
    values = history["values"][:]
    initial = fit["parameters/initial"][:]
    for column, name in enumerate(fit["parameters/name"][:]):
        scale = initial[column] if initial[column] != 0 else 1.0
        parameter_axis.plot(iteration, values[:, column] / scale, ".-", label=text(name))
    parameter_axis.set_ylabel("value / initial [-]")
    parameter_axis.set_xlabel("iteration [-]")
    parameter_axis.grid(True, alpha=0.3)
    parameter_axis.legend(fontsize=8)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", help="HDF5 file written by tirefe.fit")
    parser.add_argument("-o", "--output", help="PNG to write (default: <file>_fit.png)")
    arguments = parser.parse_args()
    output = arguments.output or os.path.splitext(arguments.file)[0] + "_fit.png"
    with h5py.File(arguments.file, "r") as result:
        fit = result["fit"]
        figure = plt.figure(figsize=(11, 5))
        grid = figure.add_gridspec(2, 2, width_ratios=(1.3, 1))
        plot_curve(figure.add_subplot(grid[:, 0]), fit)
        objective_axis = figure.add_subplot(grid[0, 1])
        plot_history(objective_axis, figure.add_subplot(grid[1, 1], sharex=objective_axis), fit)
        status = text(result.attrs.get("status", ""))
        method = text(result.attrs.get("method", ""))
        evaluations = result.attrs.get("evaluations", 0)
        figure.suptitle(f"{method}: {status} after {evaluations} evaluations\n{fitted_values_line(fit)}", fontsize=10)
    figure.tight_layout()
    figure.savefig(output, dpi=120)
    plt.close(figure)
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
