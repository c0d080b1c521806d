#!/usr/bin/env python3
"""Independent oracle for the end of a bumper segment's stroke (issue 45).

Usage: scipy_block.py PARAMS.json

A mass M moves at speed V into a rigid wall through one elastic spring k
whose stroke ends at a depth D: past it a block of stiffness kb adds
kb * (d - D). With d the spring's compression,

    M d'' = -(k d + kb max(d - D, 0))   while d > 0,

integrated by scipy.integrate.solve_ivp (DOP853, rtol 1e-11, atol 1e-14,
max_step 1e-5 s) with an event at d = D. Prints CSV "t,d" at the requested
times, then a line "bottomed,T" with the first time d reaches D.
"""
import json
import sys

from scipy.integrate import solve_ivp


def main(path):
    with open(path) as f:
        p = json.load(f)
    m, k, kb, depth, speed = p["mass"], p["stiffness"], p["block"], p["depth"], p["speed"]

    def rhs(_t, s):
        d, v = s
        force = k * max(d, 0.0) + kb * max(d - depth, 0.0) if d > 0.0 else 0.0
        return [v, -force / m]

    def bottom(_t, s):
        return s[0] - depth

    bottom.direction = 1.0
    times = p["times"]
    sol = solve_ivp(rhs, (0.0, times[-1]), [0.0, speed], method="DOP853", t_eval=times,
                    rtol=1e-11, atol=1e-14, max_step=1e-5, events=bottom)
    if not sol.success:
        sys.exit(f"solve_ivp failed: {sol.message}")
    print("t,d")
    for t, d in zip(sol.t, sol.y[0]):
        print(f"{t:.9g},{max(d, 0.0):.17g}")
    print(f"bottomed,{sol.t_events[0][0]:.17g}")


if __name__ == "__main__":
    main(sys.argv[1])
