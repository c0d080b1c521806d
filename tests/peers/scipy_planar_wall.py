#!/usr/bin/env python3
"""Independent oracle for bumpsim-planar (spec section 9).

Usage: scipy_planar_wall.py PARAMS.json

A rigid body (mass M, yaw inertia I about its CG) carries one point spring at
body coordinates (a, y0). It moves at speed V along +x into a frictionless
rigid wall whose normal towards the body is n = (-cos th, -sin th), placed so
that the spring point just touches it at t = 0. The spring pushes along n with
F = k * max(pen, 0), pen = h - n.p. Newton-Euler, written here separately:

    M X'' = F n_x,   M Y'' = F n_y,   I psi'' = (p - R) x (F n)

integrated by scipy.integrate.solve_ivp (DOP853, rtol 1e-11, atol 1e-13,
max_step 2e-5 s). Prints CSV "t,x,y,psi" at the requested times.
"""
import json
import sys

import numpy as np
from scipy.integrate import solve_ivp


def main(path):
    with open(path) as f:
        p = json.load(f)
    m, inertia, k, a, y0 = p["mass"], p["yaw_inertia"], p["stiffness"], p["a"], p["y0"]
    th, speed = p["angle"], p["speed"]
    n = np.array([-np.cos(th), -np.sin(th)])
    h = n @ np.array([a, y0])

    def rhs(_t, s):
        x, y, psi, vx, vy, w = s
        c, sn = np.cos(psi), np.sin(psi)
        arm = np.array([c * a - sn * y0, sn * a + c * y0])
        point = np.array([x, y]) + arm
        force = k * max(h - n @ point, 0.0) * n
        moment = arm[0] * force[1] - arm[1] * force[0]
        return [vx, vy, w, force[0] / m, force[1] / m, moment / inertia]

    times = np.array(p["times"])
    sol = solve_ivp(rhs, (0.0, times[-1]), [0, 0, 0, speed, 0, 0], method="DOP853",
                    t_eval=times, rtol=1e-11, atol=1e-13, max_step=2e-5)
    if not sol.success:
        sys.exit(f"solve_ivp failed: {sol.message}")
    print("t,x,y,psi")
    for t, x, y, psi in zip(sol.t, sol.y[0], sol.y[1], sol.y[2]):
        print(f"{t:.9g},{x:.17g},{y:.17g},{psi:.17g}")


if __name__ == "__main__":
    main(sys.argv[1])
