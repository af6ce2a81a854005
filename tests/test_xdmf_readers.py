#!/usr/bin/python3
"""The XDMF index of a result file read back as its readers read it, on tests/xdmf_deck.lua (a
tire with a tread layer on a spinning drum with a cleat): meshio's TimeSeriesReader (Debian's
python3-meshio) against the HDF5 datasets, the deformation against its definition, the drum's
outline against its motion; a reader opening the index while the run writes it; and the Python
examples of docs/output.md.

    /usr/bin/python3 tests/test_xdmf_readers.py path/to/tirefe
"""
import math
import os
import re
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ElementTree

import h5py
import meshio
import numpy as np

import script_tests

TIREFE = None  # the tirefe binary: script_tests.run sets it from the command line
HERE = os.path.dirname(os.path.abspath(__file__))
DOCS = os.path.join(os.path.dirname(HERE), "docs", "output.md")
DECK = os.path.join(HERE, "xdmf_deck.lua")
DRUM_RADIUS, SPEED, RAMP, START = 0.85, 5.0, 0.2, 1.5  # as the deck has them


def run_deck(folder, *arguments):
    result = subprocess.run([TIREFE, DECK, "--quiet", "--output-dir", folder, *arguments], capture_output=True,
                            text=True)
    assert result.returncode == 0, result.stdout + result.stderr


def drum_angle(t):
    """The deck's drum: clockwise, its rate ramped from 0 at START to SPEED / R over RAMP."""
    omega = SPEED / DRUM_RADIUS
    running = max(t - START, 0.0)
    ramp = min(running, RAMP)
    return -(0.5 * omega * ramp * ramp / RAMP + omega * max(running - RAMP, 0.0))


def collections(index):
    """The index's temporal collections: name -> list of frame grids."""
    domain = ElementTree.parse(index).getroot().find("Domain")
    return [(grid.get("Name"), list(grid.findall("Grid"))) for grid in domain.findall("Grid")]


def dataset_path(item):
    return item.text.strip().split(":")[1]


def test_meshio_reads_the_finished_run(folder):
    run_deck(os.path.join(folder, "run"))
    index, h5 = os.path.join(folder, "run", "xdmf.xmf"), os.path.join(folder, "run", "xdmf.h5")
    with meshio.xdmf.TimeSeriesReader(index) as reader, h5py.File(h5, "r") as f:
        points, cells = reader.read_points_cells()
        reference = f["mesh/coordinates"][:]
        assert points.shape == reference.shape == (1 + 40, 2), points.shape
        assert np.array_equal(points, reference)
        # The drawn blocks in order (the pressure and the tread contact repeat the tread: drawn
        # once), per block.
        drawn = [("line", "tire_tread"), ("triangle", "tire_sidewall")]
        assert [(c.type, len(c.data)) for c in cells] == [(kind, 40) for kind, _ in drawn], cells
        for block, (kind, name) in zip(cells, drawn):
            assert np.array_equal(block.data, f["mesh/blocks/" + name][:]), name

        times = f["fields/time"][:]
        assert reader.num_steps == len(times) == 44, reader.num_steps
        displacement, velocity, deformation = (f["fields/" + name][:] for name in
                                               ("displacement", "velocity", "deformation"))
        for k in range(reader.num_steps):
            t, point_data, cell_data = reader.read_data(k)
            assert t == times[k], (k, t, times[k])
        # The last frame: 3-component vectors with z = 0, the rotation as a scalar, exactly the rows.
        assert set(point_data) == {"displacement", "velocity", "rotation", "deformation"}, set(point_data)
        for name, rows in (("displacement", displacement), ("velocity", velocity), ("deformation", deformation)):
            assert point_data[name].shape == (41, 3), (name, point_data[name].shape)
            assert np.array_equal(point_data[name][:, :2], rows[-1][:, :2]), name
            assert not point_data[name][:, 2].any(), name
        assert np.array_equal(point_data["rotation"], displacement[-1][:, 2])
        node = 17  # one tread node, by value: u_x of the last frame
        assert point_data["displacement"][node, 0] == displacement[-1, node, 0] != 0.0
        assert [list(np.unique(b)) for b in cell_data["block"]] == [[0], [1]], cell_data["block"]

        # The deformation by its definition: x - x_s - R(theta_s) (X - X_s), theta - theta_s.
        spindle = int(f["mesh/node_sets/tire_spindle"][0])
        u = displacement[-1]
        theta = u[spindle, 2]
        rotation = np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])
        arm = reference - reference[spindle]
        expected = arm + u[:, :2] - u[spindle, :2] - arm @ rotation.T
        assert np.abs(deformation[-1][:, :2] - expected).max() < 1e-14
        assert np.abs(deformation[-1][:, 2] - (u[:, 2] - theta)).max() < 1e-14
        # The tire rolled three and a half radians: its displacement is the spin, the deformation is not.
        assert abs(theta) > 3.0
        assert np.abs(u[:, :2]).max() > 0.4 and np.abs(deformation[-1][:, :2]).max() < 0.03


def test_views_made_after_the_run_are_those_made_during_it(folder):
    """views=false: the run makes no views; `tirefe --views` then makes every view the index
    names (frames, drum), the same data as the run that made them (the first test's), and a
    second call makes none."""
    later = os.path.join(folder, "later")
    run_deck(later, "views=false")
    h5, index = os.path.join(later, "xdmf.h5"), os.path.join(later, "xdmf.xmf")
    with h5py.File(h5, "r") as f:
        assert "frames" not in f["fields"] and "frames" not in f["surfaces/drum"], list(f["fields"])
        frames = len(f["fields/time"])
    made = subprocess.run([TIREFE, "--views", h5], capture_output=True, text=True)
    assert made.returncode == 0 and made.stdout == f"{h5}: {5 * frames} views made\n", made
    named = {dataset_path(item) for item in ElementTree.parse(index).getroot().iter("DataItem") if "frames" in item.text}
    assert len(named) == 5 * frames, len(named)
    during = os.path.join(folder, "run", "xdmf.h5")
    with h5py.File(h5, "r") as f, h5py.File(during, "r") as g:
        for path in named:
            assert np.array_equal(f[path][:], g[path][:]), path
    again = subprocess.run([TIREFE, "--views", h5], capture_output=True, text=True)
    assert again.returncode == 0 and again.stdout == f"{h5}: 0 views made\n", again
    with meshio.xdmf.TimeSeriesReader(index) as reader:
        assert reader.num_steps == frames
        reader.read_points_cells()
        _, point_data, _ = reader.read_data(frames - 1)
        assert set(point_data) == {"displacement", "velocity", "rotation", "deformation"}, set(point_data)
    missing = subprocess.run([TIREFE, "--views", os.path.join(later, "none.h5")], capture_output=True, text=True)
    assert missing.returncode == 1 and "cannot open file" in missing.stderr and "none.h5" in missing.stderr, missing


def test_plot_results_on_the_finished_run(folder):
    """post/plot_results.py: --help prints its usage (it took '--help' for a file name), the
    finished run gives its two plots, a missing file one line that names it."""
    script = os.path.join(os.path.dirname(HERE), "post", "plot_results.py")
    usage = subprocess.run([sys.executable, script, "--help"], capture_output=True, text=True)
    assert usage.returncode == 0 and "usage: plot_results.py" in usage.stdout and "result" in usage.stdout, usage
    plots = subprocess.run([sys.executable, script, os.path.join(folder, "run", "xdmf.h5")], capture_output=True,
                           text=True)
    assert plots.returncode == 0, plots.stderr
    for suffix in ("_history.png", "_shapes.png"):
        assert os.path.getsize(os.path.join(folder, "run", "xdmf" + suffix)) > 10000, suffix
    missing = subprocess.run([sys.executable, script, os.path.join(folder, "no_such.h5")], capture_output=True,
                             text=True)
    assert missing.returncode == 2 and "no_such.h5: not a readable HDF5 result file" in missing.stderr, missing
    assert "Traceback" not in missing.stderr, missing.stderr


def test_plot_drum_cleat_usage_and_bad_files(folder):
    """post/plot_drum_cleat.py: --help prints its usage (it opened '--help' as a result file);
    a missing file, a file that is not HDF5 and another deck's result file each give one line
    naming the file, no traceback. Its plots of a drum-cleat run: tests/test_bad_decks.cpp."""
    script = os.path.join(os.path.dirname(HERE), "post", "plot_drum_cleat.py")
    usage = subprocess.run([sys.executable, script, "--help"], capture_output=True, text=True)
    assert usage.returncode == 0 and "usage: plot_drum_cleat.py" in usage.stdout and "result" in usage.stdout, usage
    text = os.path.join(folder, "text.h5")
    with open(text, "w") as f:
        f.write("not HDF5\n")
    for path, says in ((os.path.join(folder, "no_such.h5"), "not a readable HDF5 result file"),
                       (text, "not a readable HDF5 result file"),
                       (os.path.join(folder, "run", "xdmf.h5"), "not a drum-cleat result file")):
        bad = subprocess.run([sys.executable, script, path], capture_output=True, text=True)
        assert bad.returncode == 1 and bad.stdout == "", bad
        assert bad.stderr.startswith(f"plot_drum_cleat.py: {path}: {says}"), bad.stderr
        assert bad.stderr.count("\n") == 1 and "Traceback" not in bad.stderr, bad.stderr


def test_the_other_grids_show_the_rim_and_the_turning_drum(folder):
    index, h5 = os.path.join(folder, "run", "xdmf.xmf"), os.path.join(folder, "run", "xdmf.h5")
    grids = collections(index)
    assert [name for name, _ in grids] == ["tire_rim", "drum", "mesh"], grids
    assert all(len(frames) == 44 for _, frames in grids)
    frames = dict(grids)
    with h5py.File(h5, "r") as f:
        times = f["fields/time"][:]
        rim = frames["tire_rim"][0].find("Topology")
        assert (rim.get("TopologyType"), dataset_path(rim.find("DataItem"))) == ("Polyvertex", "/mesh/blocks/tire_rim")
        # The drum at every frame where its angle puts it (the first frame, at rest, turned).
        outline = f["surfaces/drum/outline"][:]
        first = outline[0]
        radius = np.hypot(first[:, 0], first[:, 1])
        assert radius.min() > DRUM_RADIUS - 1e-12 and radius.max() < DRUM_RADIUS + 0.01 + 1e-12
        assert (radius > DRUM_RADIUS + 0.01 - 1e-12).sum() > 3  # the cleat's top
        for k, grid in enumerate(frames["drum"]):
            geometry = grid.find("Geometry/DataItem")
            assert np.array_equal(f[dataset_path(geometry)][()], outline[k])
            angle = drum_angle(times[k])
            turn = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
            assert np.abs(outline[k] - first @ turn.T).max() < 1e-12, (k, times[k])
        assert drum_angle(times[-1]) < -1.0


def read_snapshot(index, h5):
    """What a reader gets now: the frames the index lists, their displacements, and the rows
    the HDF5 file holds."""
    with meshio.xdmf.TimeSeriesReader(index) as reader:
        reader.read_points_cells()
        frames = [reader.read_data(k) for k in range(reader.num_steps)]
    with h5py.File(h5, "r") as f:
        rows = f["fields/time"].shape[0]
    return [t for t, _, _ in frames], [data["displacement"] for _, data, _ in frames], rows


def test_a_reader_opening_the_index_while_the_run_writes_it(folder):
    # The run is stopped (SIGSTOP) at whatever it is doing, read, and let go on; a read that
    # catches the file in the middle of a flush fails and is tried again later.
    live = os.path.join(folder, "live")
    os.makedirs(live)
    index, h5 = os.path.join(live, "live.xmf"), os.path.join(live, "live.h5")
    process = subprocess.Popen([TIREFE, DECK, "--quiet", "--output-dir", live, "output=live.h5", "end_time=2.4",
                                "fields_interval=0.005"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    snapshots, failures = [], 0
    try:
        # At least three reads, and on until the index has grown: it follows the flushes,
        # which come further apart as the file grows. The run goes on only between the reads,
        # in short slices, so that even a run of a fifth of a second is read several times.
        def grown():
            return len(snapshots) >= 3 and len(snapshots[-1][0]) > len(snapshots[0][0])

        while process.poll() is None and not grown() and len(snapshots) < 40:
            time.sleep(0.02)
            if not os.path.exists(index):
                continue
            process.send_signal(signal.SIGSTOP)
            try:
                snapshots.append(read_snapshot(index, h5))
            except Exception:  # noqa: BLE001 (the file caught mid-flush: HDF5 has no other promise)
                failures += 1
            finally:
                process.send_signal(signal.SIGCONT)
    finally:
        _, errors = process.communicate(timeout=120)
    assert process.returncode == 0, errors
    assert len(snapshots) >= 3, f"{len(snapshots)} reads during the run, {failures} failed"
    assert failures <= 3, failures
    with h5py.File(h5, "r") as f:
        times, displacement = f["fields/time"][:], f["fields/displacement"][:]
    for frame_times, values, rows in snapshots:
        count = len(frame_times)
        assert 1 <= count <= rows, (count, rows)  # only frames the file held
        assert np.array_equal(frame_times, times[:count])
        for k in range(count):
            assert np.array_equal(values[k][:, :2], displacement[k][:, :2]), k
    # Read later, more frames: the run went on between the reads.
    assert len(snapshots[-1][0]) > len(snapshots[0][0])
    with meshio.xdmf.TimeSeriesReader(index) as reader:
        assert reader.num_steps == len(times)


def test_the_python_examples_of_the_output_docs_run(folder):
    examples = re.findall(r"```python\n(.*?)```", open(DOCS).read(), re.S)
    assert len(examples) >= 2, len(examples)
    work = os.path.join(folder, "docs")
    results = os.path.join(work, "results")
    run_deck(results, "output=drum_cleat.h5")
    result = subprocess.run([TIREFE, os.path.join(os.path.dirname(HERE), "inputs", "cantilever_elastica.lua"),
                             "--quiet", "--output-dir", results], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    for number, example in enumerate(examples, 1):
        run = subprocess.run([sys.executable, "-c", example], cwd=work, capture_output=True, text=True)
        assert run.returncode == 0, f"example {number}:\n{example}\n{run.stderr}"


if __name__ == "__main__":
    script_tests.run(globals(), "tirefe_xdmf_")  # in order: the second reads the first one's run
