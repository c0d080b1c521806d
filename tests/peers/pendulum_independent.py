#!/usr/bin/env python3
"""An independent pendulum test series of a 3-mass car (issue 39): what a lab
would record, in several noise draws.

Usage: pendulum_independent.py OUT_DIR [DRAWS]

Writes OUT_DIR/truth.json (the car and the tests) and, for each noise draw
k = 0 .. DRAWS-1 (default 10), OUT_DIR/draw-k/<TEST>.csv (10 kHz, `time [s]`
from -50 ms, the pendulum's load cell in N, two accelerometers on the car's
front mass in m/s^2) and OUT_DIR/draw-k/study.toml (a bumpsim study of the
three tests with the DOF table 1..5). The noiseless tests are simulated
once; the draws differ only in the measurement noise (seed 3900 + k).

The model is written here, not taken from bumpsim, and is of another family:

- the pendulum is a rigid body swinging about its pivot (arm L, mass M,
  radius of gyration about the pivot r_g): I phi'' = -M g l sin(phi) -
  R L cos(phi), its face at x = L sin(phi) (bumpsim's impactor moves on a
  line);
- its face meets the car's bumper through a Hunt-Crossley contact,
  R = k d^n (1 + 3/2 (1 - e) d'/v0) for d > 0 (bumpsim's bumper is a
  three-part or tabulated characteristic with elastic unloading), one
  stiffness, exponent and restitution per head;
- the car is three masses joined by linear springs and dampers (the truth
  the DOF table must find: 3 masses) on tyres with rolling resistance
  f_r m g tanh(v/0.05 m/s) on the body (not in bumpsim's chain);
- integrated by scipy's DOP853 (adaptive, rtol 1e-10) from the trigger
  (t = 0, a few millimetres before contact), not by zoh or leapfrog;
- measured as a lab does: evaluated at 100 kHz, a 4th-order Butterworth
  anti-alias filter at 2.5 kHz (causal, as hardware), sampled at 10 kHz
  with 50 ms of pre-trigger; load cell noise 150 N rms, accelerometer
  noise 0.2 g rms and biases +0.15 g and -0.10 g.
"""
import json
import math
import sys
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.signal import butter, lfilter

G = 9.80665

CAR = {"masses": [28.0, 230.0, 1190.0], "dampers": [7.0e3, 2.2e4], "springs": [1.4e6, 5.5e5],
       "rolling_resistance": 0.012}

PENDULUM = {"mass": 1450.0, "arm": 3.5, "cg": 3.3, "gyration": 3.35}

# head: Hunt-Crossley stiffness (N/m^n), exponent, restitution, speed (km/h)
TESTS = [
    {"name": "FLAT", "k": 1.2e8, "n": 1.6, "e": 0.35, "speed_kmh": 6.0},
    {"name": "NARROW", "k": 6.0e7, "n": 1.5, "e": 0.30, "speed_kmh": 6.0},
    {"name": "POLE", "k": 2.5e7, "n": 1.4, "e": 0.25, "speed_kmh": 5.0},
]

GAP = 0.003       # m between face and bumper at the trigger
STEP = 1e-4       # s, sampling
FINE = 1e-5       # s, the evaluation before the anti-alias filter
PRE = 0.05        # s of pre-trigger
DURATION = 0.25   # s after the trigger


def contact(test, d, rate, v0):
    if d <= 0.0:
        return 0.0
    return max(test["k"] * d ** test["n"] * (1.0 + 1.5 * (1.0 - test["e"]) * rate / v0), 0.0)


def rhs(test, v0):
    m, c, k = CAR["masses"], CAR["dampers"], CAR["springs"]
    p = PENDULUM
    inertia = p["mass"] * p["gyration"] ** 2
    total = sum(m)

    def f(t, y):
        phi, omega, x, v = y[0], y[1], y[2:5], y[5:8]
        face, face_rate = p["arm"] * math.sin(phi), p["arm"] * math.cos(phi) * omega
        r = contact(test, face - GAP - x[0], face_rate - v[0], v0)
        a = np.zeros(3)
        a[0] += r
        for j in range(2):
            link = k[j] * (x[j] - x[j + 1]) + c[j] * (v[j] - v[j + 1])
            a[j] -= link
            a[j + 1] += link
        a[2] -= CAR["rolling_resistance"] * total * G * math.tanh(v[2] / 0.05)
        a /= np.array(m)
        alpha = (-p["mass"] * G * p["cg"] * math.sin(phi) - r * p["arm"] * math.cos(phi)) / inertia
        return [omega, alpha, *v, *a], r

    return f


def simulate(test):
    v0 = test["speed_kmh"] / 3.6
    f = rhs(test, v0)
    y0 = [0.0, v0 / PENDULUM["arm"], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    sol = solve_ivp(lambda t, y: f(t, y)[0], (0.0, DURATION), y0, method="DOP853",
                    rtol=1e-10, atol=1e-12, max_step=2e-5, dense_output=True)
    assert sol.success, sol.message
    t = np.arange(-PRE, DURATION + FINE / 2, FINE)
    force, acc = np.zeros_like(t), np.zeros_like(t)
    for i, ti in enumerate(t):
        if ti < 0.0:
            continue
        y = sol.sol(ti)
        dy, r = f(ti, y)
        force[i], acc[i] = r, dy[5]
    b, a = butter(4, 2500.0, fs=1.0 / FINE)
    every = int(round(STEP / FINE))
    return t[::every], lfilter(b, a, force)[::every], lfilter(b, a, acc)[::every]


def write(out, test, signals, rng):
    t, force, acc = signals
    lines = ["time [s],force [N],acc_left [m/s^2],acc_right [m/s^2]"]
    left = acc + 0.15 * G + rng.normal(0.0, 0.2 * G, t.size)
    right = acc - 0.10 * G + rng.normal(0.0, 0.2 * G, t.size)
    measured = force + rng.normal(0.0, 150.0, t.size)
    for row in zip(t, measured, left, right):
        lines.append(",".join(f"{v:.9g}" for v in row))
    (out / f"{test['name']}.csv").write_text("\n".join(lines) + "\n")


def study(out):
    lines = [
        "# A study of the independent pendulum series (tests/peers/pendulum_independent.py).",
        "[model]",
        "dof = [1, 2, 3, 4, 5]",
        "starts = 8",
        "seed = 1",
        "",
    ]
    for test in TESTS:
        path = f"{test['name']}.csv"
        lines += [
            "[[case]]",
            f'name = "{test["name"].lower()}"',
            f'force = {{ path = "{path}", channel = "force" }}',
            "acceleration = [",
            f'  {{ path = "{path}", channel = "acc_left" }},',
            f'  {{ path = "{path}", channel = "acc_right" }},',
            "]",
            "cfc = 180",
            "output_dof = 1",
            'window = "contact"',
            "",
        ]
    (out / "study.toml").write_text("\n".join(lines))


def main():
    out = Path(sys.argv[1])
    draws = int(sys.argv[2]) if len(sys.argv) > 2 else 10
    out.mkdir(parents=True, exist_ok=True)
    signals = [simulate(test) for test in TESTS]
    for k in range(draws):
        rng = np.random.default_rng(3900 + k)
        folder = out / f"draw-{k}"
        folder.mkdir(exist_ok=True)
        for test, s in zip(TESTS, signals):
            write(folder, test, s, rng)
        study(folder)
    peaks = {t["name"]: float(np.max(s[1])) for t, s in zip(TESTS, signals)}
    truth = {"car": CAR, "pendulum": PENDULUM, "tests": TESTS, "dof": 3, "peak_force": peaks,
             "draws": draws}
    (out / "truth.json").write_text(json.dumps(truth, indent=2) + "\n")


if __name__ == "__main__":
    main()
