#!/usr/bin/env python3
"""Independent check of `bumpsim simulate` with scipy.

Usage: scipy_simulate.py CAR.toml FORCE.csv RESPONSE.csv METHOD

Builds the chain model's A and B from the car file (spec section 2), discretises
with scipy.signal.cont2discrete (zoh or foh), simulates with dlsim, and
compares every displacement and velocity with bumpsim's response CSV. Prints
the largest difference relative to each signal's peak and exits 1 when it
exceeds 1e-9.
"""
import csv
import sys
import tomllib

import numpy as np
from scipy import signal

FACTORS = {"s": 1.0, "ms": 1e-3, "N": 1.0, "kN": 1e3}


def read_csv(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    header, data = rows[0], np.array(rows[1:], dtype=float)
    units = [h[h.rindex("[") + 1 : -1] for h in header]
    names = [h[: h.rindex("[")].strip() for h in header]
    return names, data * np.array([FACTORS.get(u, 1.0) for u in units])


def main(car_path, force_path, response_path, method):
    with open(car_path, "rb") as f:
        car = tomllib.load(f)
    m = np.array(car["masses"], dtype=float)
    c = np.array(car.get("dampers", []), dtype=float)
    k = np.array(car.get("springs", []), dtype=float)
    n = len(m)

    def chain(links):
        mat = np.zeros((n, n))
        for j, v in enumerate(links):
            mat[j, j] += v
            mat[j + 1, j + 1] += v
            mat[j, j + 1] -= v
            mat[j + 1, j] -= v
        return mat

    a = np.block([[np.zeros((n, n)), np.eye(n)], [-chain(k) / m[:, None], -chain(c) / m[:, None]]])
    b = np.zeros((2 * n, 1))
    b[n, 0] = 1.0 / m[0]
    _, force = read_csv(force_path)
    t, f = force[:, 0], force[:, 1]
    dt = (t[-1] - t[0]) / (len(t) - 1)
    ad, bd, cd, dd, _ = signal.cont2discrete((a, b, np.eye(2 * n), np.zeros((2 * n, 1))), dt, method=method)
    _, y, _ = signal.dlsim((ad, bd, cd, dd, dt), f)
    names, response = read_csv(response_path)
    worst = 0.0
    for i in range(n):
        for prefix, col in (("x", i), ("v", n + i)):
            ours = response[:, names.index(f"{prefix}{i + 1}")]
            scale = max(np.abs(y[:, col]).max(), 1e-300)
            diff = np.abs(ours - y[:, col]).max() / scale
            print(f"{prefix}{i + 1}: largest difference {diff:.2e} of its peak {scale:.4e} (SI)")
            worst = max(worst, diff)
    print(f"{method}: worst relative difference {worst:.2e}")
    return 0 if worst <= 1e-9 else 1


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
