"""Peer benchmark: the same single-start 3-DOF identification with
scipy.optimize.least_squares and with `bumpsim identify`, from two starts:
the thesis's 3-DOF start, and bumpsim's default (data-derived) start, which
scipy is given as the `start` that bumpsim's JSON reports.

Both get the same data (three synthetic pendulum cases, 500 samples each at
5 kHz, written here as CSV), the same exact zoh model, the same log
parameters with the thesis's bounds (every parameter >= 1 SI) and the same
start. scipy: trust-region-reflective with its default 2-point
finite-difference Jacobian, the model simulated by scipy.signal.dlsim.
Prints both wall times and objectives.

Usage: python3 bench/peers/scipy_identify.py [path/to/bumpsim]
(default: target/release/bumpsim; build it with cargo build --release).
"""
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy import linalg, optimize, signal

STEP = 2e-4
TRUTH = ([30.0, 250.0, 1170.0], [8e3, 2.5e4], [1.5e6, 6e5])
START = ([150.0, 500.0, 800.0], [1e2, 2e5], [5e5, 5e5])  # the thesis's 3-DOF start


def system(m, c, k):
    n = len(m)
    K = np.zeros((n, n))
    C = np.zeros((n, n))
    for j in range(n - 1):
        e = np.zeros(n)
        e[j], e[j + 1] = 1.0, -1.0
        K += k[j] * np.outer(e, e)
        C += c[j] * np.outer(e, e)
    Minv = np.diag(1.0 / np.asarray(m))
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
    B = np.zeros((2 * n, 1))
    B[n, 0] = 1.0 / m[0]
    return A, B


def simulate(theta, force):
    m, c, k = theta[:3], theta[3:5], theta[5:7]
    A, B = system(m, c, k)
    aug = np.zeros((7, 7))
    aug[:6, :6], aug[:6, 6:] = A * STEP, B * STEP
    e = linalg.expm(aug)
    C = np.zeros((1, 6))
    C[0, 0] = 1.0
    sys_d = signal.StateSpace(e[:6, :6], e[:6, 6:], C, np.zeros((1, 1)), dt=STEP)
    _, y, _ = signal.dlsim(sys_d, force, x0=np.zeros(6))
    return y[:, 0]


def cases():
    t = np.arange(500) * STEP
    out = []
    theta = np.concatenate(TRUTH)
    rng = np.random.default_rng(5)
    for peak, duration, shape in [(4.5e4, 0.06, 1.0), (3.5e4, 0.07, 1.5), (2.5e4, 0.085, 2.0)]:
        f = np.where(t < duration, peak * np.sin(np.pi * np.minimum(t, duration) / duration) ** shape, 0.0)
        x = simulate(theta, f) + rng.normal(0, 5e-5, len(t))
        out.append((t, f, x))
    return out


def write_study(folder, data, thesis_start=True):
    lines = ["[model]", "dof = 3", "lower_bound = 1.0", "starts = 1", "seed = 1", 'method = "zoh"']
    if thesis_start:
        lines.append("start = { masses = [150, 500, 800], dampers = [1e2, 2e5], springs = [5e5, 5e5] }")
    lines.append("")
    for i, (t, f, x) in enumerate(data):
        path = os.path.join(folder, f"case{i}.csv")
        np.savetxt(path, np.column_stack([t, f, x]), delimiter=",", header="time [s],force [N],x1 [m]", comments="")
        lines += ["[[case]]", f'name = "case{i}"', f'force = {{ path = "case{i}.csv", channel = "force" }}',
                  f'displacement = {{ path = "case{i}.csv", channel = "x1" }}', f"window = [0.0, {float(t[-1])!r}]", ""]
    study = os.path.join(folder, "study.toml" if thesis_start else "default.toml")
    with open(study, "w") as fh:
        fh.write("\n".join(lines))
    return study


def run_scipy(data, start):
    def residuals(p):
        theta = np.exp(p)
        return np.concatenate([simulate(theta, f) - x for _, f, x in data])

    x0 = np.log(np.asarray(start, dtype=float))
    t0 = time.perf_counter()
    res = optimize.least_squares(residuals, x0, bounds=(0.0, np.inf), method="trf", ftol=1e-10, xtol=1e-10, gtol=1e-10)
    return time.perf_counter() - t0, float(np.sum(res.fun ** 2)), res.nfev


def run_bumpsim(binary, study, folder, repeats=21):
    """Median wall time of `repeats` whole processes after one warm-up run
    (a few-ms process is at the mercy of the scheduler and, on its first
    run, of the page cache; scipy's seconds are not)."""
    out = os.path.join(folder, "result.json")
    walls = []
    subprocess.run([binary, "identify", study, "--json", out, "--quiet"], check=True, stdout=subprocess.DEVNULL)
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run([binary, "identify", study, "--json", out, "--quiet"], check=True, stdout=subprocess.DEVNULL)
        walls.append(time.perf_counter() - t0)
    wall = sorted(walls)[len(walls) // 2]
    with open(out) as fh:
        result = json.load(fh)
    return wall, result["run_time"], result["objective"], result["start"]


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "target/release/bumpsim"
    data = cases()
    for name, thesis in [("thesis start", True), ("default (data-derived) start", False)]:
        with tempfile.TemporaryDirectory() as folder:
            study = write_study(folder, data, thesis)
            wall, inner, objective, start = run_bumpsim(binary, study, folder)
            scipy_time, scipy_objective, nfev = run_scipy(data, start)
        print(f"== from the {name}: {', '.join(f'{v:.4g}' for v in start)} (SI)")
        print(f"scipy least_squares (trf, 2-point FD, dlsim): {scipy_time:.3f} s, objective {scipy_objective:.6e} m^2, {nfev} evaluations")
        print(f"bumpsim identify (whole process, median of 21): {wall * 1e3:.1f} ms, objective {objective:.6e} m^2 (identification alone {inner * 1e3:.1f} ms)")
        print(f"speed-up: {scipy_time / wall:.0f}x (whole process), {scipy_time / inner:.0f}x (identification alone)")
        print(f"objective ratio bumpsim/scipy: {objective / scipy_objective:.6f}")


if __name__ == "__main__":
    main()
