"""Fmu: an FMI 2.0 co-simulation FMU loaded into this process and stepped from Python, so
that an FMU (tirefe_tire.fmu or another) can be checked without other tools.

    with tirefe.Fmu("build/tirefe_tire.fmu") as fmu:
        fmu.set(pressure=180e3, z=-0.005)        # parameters and the inputs at the start
        fmu.initialize()
        fmu.step(1e-3)
        print(fmu.get("Fz"))

The archive is unpacked into a temporary folder (removed by close()); the binary for this
platform (binaries/linux64) is loaded with its resources folder as a file: URI. Every call
goes through the FMI 2.0 functions; what the FMU logs is kept in `messages`.
"""
import math
import os
import pathlib
import shutil
import tempfile
import xml.etree.ElementTree as ET
import zipfile
from dataclasses import dataclass
from typing import Callable, Dict, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core

STATUS = ("OK", "Warning", "Discard", "Error", "Fatal", "Pending")
# What Fmu.set takes for a variable of each type (no bool for a number, nor a number for a bool).
VALUE_TYPES = {"Real": (int, float, np.integer, np.floating), "Integer": (int, np.integer),
               "Enumeration": (int, np.integer), "Boolean": (bool, np.bool_), "String": (str,)}


class FmuError(RuntimeError):
    """An FMU that cannot be loaded, or a call that failed: the message says which call
    and what the FMU logged. `status` is the FMI status ("Error", "Discard", ...); after a
    discarded step, `time` is where the FMU stopped (fmi2LastSuccessfulTime)."""

    def __init__(self, message: str, status: str = "Error", time: Optional[float] = None):
        super().__init__(message)
        self.status = status
        self.time = time


@dataclass(frozen=True)
class Variable:
    """A scalar variable of the model description."""
    name: str
    value_reference: int
    type: str  # Real, Integer, Boolean, String or Enumeration
    causality: str
    variability: str
    start: Optional[str]
    unit: Optional[str]
    description: str


Value = Union[float, int, bool, str]
Input = Union[Callable[[float], float], Tuple[Sequence[float], Sequence[float]]]


class Fmu:
    """An FMI 2.0 co-simulation FMU: `path` is a .fmu archive or an unpacked folder."""

    def __init__(self, path: Union[str, os.PathLike], instance_name: str = "fmu", logging: bool = False):
        path = os.fspath(path)
        self._unpacked = None
        if os.path.isdir(path):
            folder = path
        else:
            try:
                archive = zipfile.ZipFile(path)
            except (OSError, zipfile.BadZipFile) as error:
                raise FmuError(f"{path}: not an FMU archive ({error})") from None
            folder = self._unpacked = tempfile.mkdtemp(prefix="tirefe_fmu_")
            with archive:
                archive.extractall(folder)
        try:
            root = ET.parse(os.path.join(folder, "modelDescription.xml")).getroot()
        except (OSError, ET.ParseError) as error:
            self.close()
            raise FmuError(f"{path}: no readable modelDescription.xml ({error})") from None
        cosimulation = root.find("CoSimulation")
        if not root.get("fmiVersion", "").startswith("2.") or cosimulation is None:
            self.close()
            raise FmuError(f"{path}: not an FMI 2.0 co-simulation FMU (fmiVersion {root.get('fmiVersion')!r})")
        self.model_name: str = root.get("modelName", "")
        self.guid: str = root.get("guid", "")
        self.variables: Dict[str, Variable] = {}
        for element in root.find("ModelVariables").findall("ScalarVariable"):
            typed = next(child for child in element if child.tag in ("Real", "Integer", "Boolean", "String",
                                                                      "Enumeration"))
            self.variables[element.get("name")] = Variable(
                element.get("name"), int(element.get("valueReference")), typed.tag,
                element.get("causality", "local"), element.get("variability", "continuous"), typed.get("start"),
                typed.get("unit"), element.get("description", ""))
        binary = os.path.join(folder, "binaries", "linux64", cosimulation.get("modelIdentifier") + ".so")
        resources = pathlib.Path(os.path.abspath(folder), "resources").as_uri()  # percent-encoded
        self.messages: list = []  # (status, category, text) as the FMU logged them
        self.time: Optional[float] = None
        try:
            self._fmi = _core.FmiInstance(binary, self.guid, resources, instance_name, logging)
        except RuntimeError as error:
            self.close()
            raise FmuError(f"{path}: {error}") from None

    # Lifecycle (FMI 2.0 section 4.2.4).
    def initialize(self, start_time: float = 0.0, stop_time: Optional[float] = None) -> None:
        """fmi2SetupExperiment, fmi2EnterInitializationMode and fmi2ExitInitializationMode:
        the parameters and inputs set so far are the start."""
        fmi = self._live()
        self._check(fmi.setup_experiment(start_time, stop_time), "fmi2SetupExperiment")
        self._check(fmi.enter_initialization_mode(), "fmi2EnterInitializationMode")
        self._check(fmi.exit_initialization_mode(), "fmi2ExitInitializationMode")
        self.time = start_time

    def step(self, step_size: float) -> float:
        """fmi2DoStep from the current time with the inputs set (start-of-step values);
        returns the new time. A discarded step raises FmuError (status "Discard", time where
        the FMU stopped)."""
        fmi = self._live()
        if self.time is None:
            raise FmuError("initialize() the FMU before stepping it")
        status = fmi.do_step(self.time, step_size)
        if status == 2:
            stopped = fmi.last_successful_time()
            self._check(status, f"fmi2DoStep from t = {self.time} s", time=stopped)
        self._check(status, f"fmi2DoStep from t = {self.time} s")
        self.time += step_size
        return self.time

    def reset(self) -> None:
        """fmi2Reset: back to the start values; initialize() again to simulate."""
        self._check(self._live().reset(), "fmi2Reset")
        self.time = None

    def terminate(self) -> None:
        self._check(self._live().terminate(), "fmi2Terminate")

    def close(self) -> None:
        """Frees the instance, unloads the binary and removes the unpacked archive."""
        fmi = getattr(self, "_fmi", None)
        if fmi is not None:
            fmi.free()
            self._fmi = None
        if self._unpacked:
            shutil.rmtree(self._unpacked, ignore_errors=True)
            self._unpacked = None

    def __enter__(self) -> "Fmu":
        return self

    def __exit__(self, *exception) -> None:
        self.close()

    def __del__(self):
        self.close()

    # Variables by name.
    def set(self, values: Optional[Dict[str, Value]] = None, **more: Value) -> None:
        """Sets variables by name (parameters before initialize(), inputs at any time)."""
        fmi = self._live()
        for name, value in {**(values or {}), **more}.items():
            variable = self.variable(name)
            reference = [variable.value_reference]
            truth = isinstance(value, (bool, np.bool_))
            if not isinstance(value, VALUE_TYPES[variable.type]) or truth != (variable.type == "Boolean"):
                raise TypeError(f"{name} is a {variable.type} variable: {value!r} is not one")
            if variable.type == "Real":
                status = fmi.set_real(reference, [float(value)])
            elif variable.type in ("Integer", "Enumeration"):
                status = fmi.set_integer(reference, [int(value)])
            elif variable.type == "Boolean":
                status = fmi.set_boolean(reference, [bool(value)])
            else:
                status = fmi.set_string(reference, [value])
            self._check(status, f"setting {name} = {value!r}")

    def get(self, *names: str):
        """The values of the named variables: one value for one name, else a tuple."""
        fmi, values = self._live(), []
        for name in names:
            variable = self.variable(name)
            getter = {"Real": fmi.get_real, "Integer": fmi.get_integer, "Enumeration": fmi.get_integer,
                      "Boolean": fmi.get_boolean, "String": fmi.get_string}
            status, value = getter[variable.type]([variable.value_reference])
            self._check(status, f"getting {name}")
            values.append(value[0])
        return values[0] if len(values) == 1 else tuple(values)

    def variable(self, name: str) -> Variable:
        if name not in self.variables:
            raise KeyError(f"the FMU {self.model_name!r} has no variable {name!r} "
                           f"(it has {', '.join(sorted(self.variables))})")
        return self.variables[name]

    def names(self, causality: str) -> list:
        """The names of the variables of a causality ("input", "output", "parameter", ...)."""
        return [v.name for v in self.variables.values() if v.causality == causality]

    def simulate(self, stop_time: float, step_size: float, inputs: Optional[Dict[str, Input]] = None,
                 start_time: float = 0.0) -> Dict[str, np.ndarray]:
        """Initializes the FMU and steps it to stop_time in fixed communication steps, as a
        generic master does: each input (a function of time, or (times, values) interpolated
        linearly and held beyond its ends) is set at every communication point before the
        step from it. Returns {"time": ..., output: ...} at every communication point."""
        if not (math.isfinite(start_time) and math.isfinite(stop_time) and stop_time >= start_time):
            raise ValueError(f"simulate from {start_time} s to {stop_time} s: give finite times, the stop "
                             "time not before the start")
        if not (math.isfinite(step_size) and step_size > 0.0):
            raise ValueError(f"simulate in steps of {step_size} s: give a finite step_size > 0")
        signals = {name: self._signal(name, source) for name, source in (inputs or {}).items()}
        outputs = self.names("output")
        rows = []

        def apply(t):
            if signals:
                self.set({name: signal(t) for name, signal in signals.items()})

        apply(start_time)
        self.initialize(start_time, stop_time)
        steps = int(round((stop_time - start_time) / step_size))
        for k in range(steps + 1):
            t = start_time + k * step_size
            rows.append([t] + [self.get(name) for name in outputs])
            if k == steps:
                break
            apply(t)
            self.time = t
            self.step(step_size)
        table = np.array(rows)
        return {name: table[:, i] for i, name in enumerate(["time"] + outputs)}

    def _signal(self, name: str, source: Input) -> Callable[[float], float]:
        variable = self.variable(name)
        if variable.causality != "input":
            raise ValueError(f"{name} is not an input of the FMU")
        if callable(source):
            return source
        try:
            times, values = (np.asarray(v, dtype=float) for v in source)
            if times.ndim != 1 or times.shape != values.shape or times.size == 0:
                raise ValueError
        except (TypeError, ValueError):
            raise ValueError(f"input {name}: give a function of time or (times, values) of equal length, "
                             f"not {source!r}") from None
        return lambda t: float(np.interp(t, times, values))

    def _live(self):
        """The instance's FMI calls; FmuError once closed."""
        if getattr(self, "_fmi", None) is None:
            raise FmuError("the FMU is closed: load it again with tirefe.Fmu(path)")
        return self._fmi

    def _check(self, status: int, what: str, time: Optional[float] = None) -> None:
        logged = self._fmi.take_messages()
        self.messages.extend(logged)
        if status in (0, 1):
            return
        said = "; ".join(text for _, _, text in logged) or "the FMU logged nothing"
        raise FmuError(f"{what}: {STATUS[status] if 0 <= status < len(STATUS) else status}: {said}",
                       STATUS[status] if 0 <= status < len(STATUS) else str(status), time)
