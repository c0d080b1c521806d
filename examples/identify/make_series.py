"""Makes the bundled synthetic pendulum test series (ISO-MME) for `bumpsim identify`.

A 1450 kg pendulum with a flat, a 600 mm and a pole head strikes the bumper of
a parked car at 6, 6 and 5 km/h (the thesis's load cases). The car is a 3-DOF
chain (masses m, dampers c, springs k below); the bumper is a spring-damper
per head between pendulum and m1 that carries compression only. The motion is
integrated with scipy's solve_ivp (Radau, rtol 1e-10) and sampled at 10 kHz
with a 10 ms pre-trigger. The measurement chain adds to the true signals:
load-cell force noise (150 N rms), and two side-member accelerometers on m1
(left and right) with noise (0.4 g rms) and a bias (+0.15 g left, -0.1 g
right). Fixed seed: the files are reproducible.

Run from this folder: python3 make_series.py
"""
import numpy as np
from scipy.integrate import solve_ivp

G = 9.80665
CAR = dict(m=[30.0, 250.0, 1170.0], c=[8.0e3, 2.5e4], k=[1.5e6, 6.0e5])
PENDULUM = 1450.0
HEADS = {  # name: (speed km/h, bumper stiffness N/m, bumper damping Ns/m, code letter)
    "FLAT": (6.0, 1.2e6, 4.0e3),
    "P600": (6.0, 8.0e5, 3.0e3),
    "POLE": (5.0, 4.0e5, 2.0e3),
}
STEP, PRE, DURATION = 1e-4, 0.01, 0.16


def rhs(_t, y, kb, cb):
    m, c, k = CAR["m"], CAR["c"], CAR["k"]
    xp, vp = y[0], y[1]
    x, v = y[2:5], y[5:8]
    squeeze = xp - x[0]
    contact = max(kb * squeeze + cb * (vp - v[0]), 0.0) if squeeze > 0 else 0.0
    a = np.zeros(3)
    f = [contact, 0.0, 0.0]
    for i in range(3):
        s = f[i]
        if i > 0:
            s += k[i - 1] * (x[i - 1] - x[i]) + c[i - 1] * (v[i - 1] - v[i])
        if i < 2:
            s -= k[i] * (x[i] - x[i + 1]) + c[i] * (v[i] - v[i + 1])
        a[i] = s / m[i]
    return np.concatenate([[vp, -contact / PENDULUM], v, a]), contact, a


def run(name, speed, kb, cb, rng):
    t = np.arange(0.0, DURATION + STEP / 2, STEP)
    y0 = np.zeros(8)
    y0[1] = speed / 3.6
    sol = solve_ivp(lambda tt, y: rhs(tt, y, kb, cb)[0], (0, DURATION), y0, t_eval=t,
                    method="Radau", rtol=1e-10, atol=1e-12, max_step=2e-4)
    force = np.array([rhs(0, y, kb, cb)[1] for y in sol.y.T])
    accel = np.array([rhs(0, y, kb, cb)[2][0] for y in sol.y.T])
    pre = int(round(PRE / STEP))
    force = np.concatenate([np.zeros(pre), force]) + rng.normal(0, 150.0, pre + len(t))
    accel = np.concatenate([np.zeros(pre), accel])
    left = accel / G + 0.15 + rng.normal(0, 0.4, len(accel))
    right = accel / G - 0.10 + rng.normal(0, 0.4, len(accel))
    write(name, speed, [
        ("P0IMPA000000FOXP", "Pendulum load cell X", "kN", force / 1e3),
        ("10SIMELE0000ACXP", "Side member left X", "g", left),
        ("10SIMERI0000ACXP", "Side member right X", "g", right),
    ])


def header(key, value):
    return f"{key:<28}:{value}\r\n"


def write(name, speed, channels):
    import os
    os.makedirs(f"{name}/Channel", exist_ok=True)
    with open(f"{name}/{name}.mme", "w", newline="") as f:
        f.write(header("Data format edition number", "1.6"))
        f.write(header("Laboratory name", "bumpsim synthetic series (make_series.py)"))
        f.write(header("Title", f"Pendulum 1450 kg, {name} head, {speed} km/h, synthetic"))
        f.write(header("Velocity test object 1", f"{speed / 3.6:.6f}"))
        f.write(header("Mass test object 1", f"{PENDULUM}"))
    with open(f"{name}/Channel/{name}.chn", "w", newline="") as f:
        f.write(header("Number of channels", len(channels)))
        for i, (code, label, _, _) in enumerate(channels, 1):
            f.write(header(f"Name of channel {i:03d}", f"{code} / {label}"))
    for i, (code, label, unit, values) in enumerate(channels, 1):
        with open(f"{name}/Channel/{name}.{i:03d}", "w", newline="") as f:
            for k, v in [("Name of the channel", label), ("Channel code", code), ("Unit", unit),
                         ("Time of first sample", f"{-PRE:.6e}"), ("Sampling interval", f"{STEP:.6e}"),
                         ("Number of samples", len(values)), ("Reference channel", "implicit")]:
                f.write(header(k, v))
            f.write("".join(f"{v:.6e}\r\n" for v in values))


if __name__ == "__main__":
    rng = np.random.default_rng(20061)
    for name, (speed, kb, cb) in HEADS.items():
        run(name, speed, kb, cb, rng)
