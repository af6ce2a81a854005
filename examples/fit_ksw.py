"""Fits the sidewall bending stiffness k_sw of the 145 SR-12 to its vertical
force-deflection curve at 208 kPa (inputs/145SR12_vertical_208kPa.csv) with
scipy.optimize, the tire's static curve from tirefe.static_forces: the fit that
inputs/fit_ksw_145SR12.lua does with tirefe.fit (k_sw_sign = +1, docs/fitting.md).

    python3 fit_ksw.py [ELEMENTS]      (default 100)
"""
import os
import sys

import numpy as np
from scipy.optimize import least_squares

import tirefe

HERE = os.path.dirname(os.path.abspath(__file__))
CURVE = os.path.join(HERE, "..", "inputs", "145SR12_vertical_208kPa.csv")


def reference():
    """Deflections [m] and forces [N] of the reference curve (comment lines start with #)."""
    with open(CURVE) as f:
        rows = [line.split(",") for line in f if line.strip() and not line.startswith("#")]
    assert [name.strip() for name in rows[0]] == ["deflection_mm", "force_N"], rows[0]
    values = np.array([[float(v) for v in row] for row in rows[1:]])
    return values[:, 0] * 1e-3, values[:, 1]


def fit_ksw(elements=100):
    deflections, forces = reference()

    def misfit(q):
        parameters = {"k_sw": q[0], "k_sw_sign": 1, "pressure": 208e3, "elements": elements}
        return tirefe.static_forces("tires.145SR12", parameters, list(deflections)) - forces

    # Bounded trust region, forward differences of 1e-3 relative: the C++ fit's step.
    fit = least_squares(misfit, x0=[100.0], bounds=([0.0], [400.0]), diff_step=1e-3, xtol=1e-6)
    return fit.x[0], fit.nfev, np.sqrt(np.mean(fit.fun ** 2))


if __name__ == "__main__":
    k_sw, evaluations, rms = fit_ksw(*[int(a) for a in sys.argv[1:2]])
    print(f"k_sw = {k_sw:.3f} N m after {evaluations} evaluations (rms misfit {rms:.1f} N)")
