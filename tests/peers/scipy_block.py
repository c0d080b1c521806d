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

With a "box" entry in the parameters (the crash boxes, issue 45), the
spring carries a tip mass m (both sides' tips together) joined to the body
M through the crash boxes: a spring kc (both boxes) whose stroke ends at
Dc, past which a block kcb (both boxes) adds kcb * (e - Dc). With xt and
xb the tip's and the body's travel since first touch, d = xt the segment's
crush and e = xb - xt the boxes' compression,

    m xt'' = -F_s(d) + F_c(e),   M xb'' = -F_c(e),
    F_s(d) = k d + kb max(d - D, 0)  (d > 0, else 0),
    F_c(e) = kc e + kcb max(e - Dc, 0),

with the same integrator and an event at e = Dc. Prints CSV "t,d,e" and
the lines "bottomed,T" (d reaches D) and "box_bottomed,T" (e reaches Dc).
"""
import json
import sys

from scipy.integrate import solve_ivp


def segment_force(p, d):
    """The segment's force at crush d, N."""
    if d <= 0.0:
        return 0.0
    return p["stiffness"] * d + p["block"] * max(d - p["depth"], 0.0)


def boxes(p):
    """The two-mass run with the crash boxes' block."""
    b = p["box"]
    m, big, kc, kcb, dc = b["tip_mass"], p["mass"], b["stiffness"], b["block"], b["depth"]
    speed, times = p["speed"], p["times"]

    def box_force(e):
        return kc * e + kcb * max(e - dc, 0.0)

    def rhs(_t, s):
        xt, xb, vt, vb = s
        fs, fc = segment_force(p, xt), box_force(xb - xt)
        return [vt, vb, (fc - fs) / m, -fc / big]

    def bottom(_t, s):
        return s[0] - p["depth"]

    def box_bottom(_t, s):
        return s[1] - s[0] - dc

    bottom.direction = 1.0
    box_bottom.direction = 1.0
    sol = solve_ivp(rhs, (0.0, times[-1]), [0.0, 0.0, speed, speed], method="DOP853",
                    t_eval=times, rtol=1e-11, atol=1e-14, max_step=1e-5,
                    events=[bottom, box_bottom])
    if not sol.success:
        sys.exit(f"solve_ivp failed: {sol.message}")
    print("t,d,e")
    for t, xt, xb in zip(sol.t, sol.y[0], sol.y[1]):
        print(f"{t:.9g},{max(xt, 0.0):.17g},{xb - xt:.17g}")
    for name, events in zip(["bottomed", "box_bottomed"], sol.t_events):
        if len(events):
            print(f"{name},{events[0]:.17g}")


def main(path):
    with open(path) as f:
        p = json.load(f)
    if "box" in p:
        boxes(p)
        return
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
