"""tirefe: a 2D finite-element tire behind its spindle (docs/python.md).

    Tire           a tire on a road, driven through its spindle (solve, commit, advance, ...)
    static_forces  the tire's static vertical force-deflection curve
    run_deck       runs a tirefe deck in this process
    Fmu            an FMI 2.0 co-simulation FMU (tirefe_tire.fmu or any other) loaded and stepped

Axes: ISO 8855 wheel axes at the wheel centre (x the heading, z up, y the spin axis); SI
units; forces are those the tire exerts on the wheel (a loaded tire: Fz > 0).
Errors: StepFailed (a step that does not converge), ModelError (a tire that cannot be
built), ValueError (bad arguments), FmuError (an FMU call that failed), each with the
library's message.
"""
from ._core import ModelError, StepFailed, Tire, __version__, run_deck, static_forces
from .fmu import Fmu, FmuError

__all__ = ["Fmu", "FmuError", "ModelError", "StepFailed", "Tire", "__version__", "run_deck", "static_forces"]
