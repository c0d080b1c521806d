#!/usr/bin/env python3
"""Times scipy on the case of the `propagate/3dof/1000` and `simulate/3dof_response/1000`
criterion benchmarks: the same 3-DOF chain (m = 150, 250, 350 kg; c = 2e3 N*s/m;
k = 5e5 N/m), 1000 samples at 10 kHz, zoh. Prints the median of repeated runs."""
import timeit

import numpy as np
from scipy import signal

m = np.array([150.0, 250.0, 350.0])
n = 3


def chain(v):
    mat = np.zeros((n, n))
    for j in range(n - 1):
        mat[j, j] += v
        mat[j + 1, j + 1] += v
        mat[j, j + 1] -= v
        mat[j + 1, j] -= v
    return mat


a = np.block([[np.zeros((n, n)), np.eye(n)], [-chain(5e5) / m[:, None], -chain(2e3) / m[:, None]]])
b = np.zeros((2 * n, 1))
b[n, 0] = 1 / m[0]
f = 4e4 * np.maximum(np.sin(np.arange(1000) * 0.005), 0.0)
sysd = signal.cont2discrete((a, b, np.eye(2 * n), np.zeros((2 * n, 1))), 1e-4, method="zoh")


def run_dlsim():
    signal.dlsim(sysd, f)


def run_all():
    d = signal.cont2discrete((a, b, np.eye(2 * n), np.zeros((2 * n, 1))), 1e-4, method="zoh")
    signal.dlsim(d, f)


for name, fn in (("dlsim only (propagation)", run_dlsim), ("cont2discrete + dlsim", run_all)):
    times = timeit.repeat(fn, number=20, repeat=7)
    per = sorted(times)[3] / 20
    print(f"scipy {name}: {per * 1e6:.1f} us per 1000-sample run ({999 / per / 1e6:.2f} M updates/s)")
