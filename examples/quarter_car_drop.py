"""A quarter car dropped onto a tirefe tire, integrated in Python: the host of
examples/quarter_car_drop.c (a 300 kg mass on a damped guide, let go at rest with the tire
touching the road; Newmark with a Newton corrector on the spindle height that uses the
tire's spindle Jacobian), with the tire as a tirefe.Tire.

    python3 quarter_car_drop.py [TIRE] [STEPS]
"""
import sys

import tirefe


def drop(source="tires.145SR12", steps=1000, m=300.0, c=4000.0, g=9.81, h=1e-3):
    tire = tirefe.Tire(source)
    z, v, a = 0.0, 0.0, -g  # the spindle: height z [m], velocity, acceleration
    carried = 0.0  # mean of Fz over the last 20 steps
    for step in range(steps):
        z_new = z + h * v + 0.5 * h * h * a  # predictor: the same acceleration
        for _ in range(20):  # corrector
            a_new = 4.0 / (h * h) * (z_new - z - h * v) - a
            v_new = v + 0.5 * h * (a + a_new)
            force, jacobian = tire.solve(h, 0.0, z_new)
            # The mass: m a = -c v - m g + Fz (the force the tire exerts on the wheel).
            residual = m * a_new + c * v_new + m * g - force[1]
            if abs(residual) < 1e-8 * m * g:
                break
            z_new -= residual / (4.0 * m / (h * h) + 2.0 * c / h - jacobian[1, 1])
        tire.commit()
        z, v, a = z_new, v_new, a_new
        if step >= steps - 20:
            carried += force[1] / 20.0
    state = tire.state()
    return state["time"], z, state["force"][1], carried, m * g


if __name__ == "__main__":
    t, z, fz, carried, weight = drop(*(sys.argv[1:2] or ["tires.145SR12"]), *[int(s) for s in sys.argv[2:3]])
    print(f"t = {t:.3f} s  z = {z:.6e} m  Fz = {fz:.6e} N  carried {carried:.6e} N (weight {weight:.1f} N)")
