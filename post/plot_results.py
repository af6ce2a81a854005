#!/usr/bin/env python3
"""Plots a tirefe result file: every history channel against time, and the deformed
shape at a few field frames. PNG files are written next to the HDF5 file.

    python3 post/plot_results.py results/run.h5
"""
import argparse
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

STEP_CHANNELS = {"time", "step_size", "newton_iterations", "cuts", "residual"}


def plot_history(result, stem):
    history = result["history"]
    time = history["time"][:]
    channels = [name for name in history if name not in STEP_CHANNELS]
    if not channels:
        return None
    figure, axes = plt.subplots(len(channels), 1, figsize=(7, 2.2 * len(channels)), sharex=True, squeeze=False)
    for axis, name in zip(axes[:, 0], channels):
        unit = history[name].attrs.get("unit", "")
        unit = unit.decode() if isinstance(unit, bytes) else unit
        axis.plot(time, history[name][:], marker=".")
        axis.set_ylabel(f"{name}\n[{unit or '-'}]")  # no unit: a count or a pure number
        axis.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    figure.suptitle(result.attrs.get("title", ""))
    figure.tight_layout()
    path = stem + "_history.png"
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def plot_shapes(result, stem, frames=5):
    if "fields" not in result or result["fields/displacement"].shape[0] == 0:
        return None
    coordinates = result["mesh/coordinates"][:]
    displacement = result["fields/displacement"]
    times = result["fields/time"][:]
    chosen = np.unique(np.linspace(0, displacement.shape[0] - 1, frames).astype(int))
    figure, axis = plt.subplots(figsize=(6, 6))
    blocks = result["mesh/blocks"]
    for frame in chosen:
        position = coordinates + displacement[frame][:, :2]
        for name in blocks:
            for element in blocks[name][:]:
                axis.plot(position[element, 0], position[element, 1], "-", color=plt.cm.viridis(frame / max(chosen[-1], 1)))
        axis.plot([], [], color=plt.cm.viridis(frame / max(chosen[-1], 1)), label=f"t = {times[frame]:.3g} s")
    axis.plot(coordinates[:, 0], coordinates[:, 1], "k:", linewidth=0.8, label="reference")
    axis.set_aspect("equal")
    axis.grid(True, alpha=0.3)
    axis.legend(fontsize=8)
    axis.set_xlabel("x [m]")
    axis.set_ylabel("y [m]")
    figure.tight_layout()
    path = stem + "_shapes.png"
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("result", help="a tirefe result file (.h5)")
    path = parser.parse_args().result
    stem = os.path.splitext(path)[0]
    try:
        result = h5py.File(path, "r")
    except OSError as error:
        parser.error(f"{path}: not a readable HDF5 result file ({error})")
    with result:
        for written in (plot_history(result, stem), plot_shapes(result, stem)):
            if written:
                print(f"wrote {written}")


if __name__ == "__main__":
    main()
