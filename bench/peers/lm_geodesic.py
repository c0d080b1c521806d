"""Does geodesic acceleration shorten bumpsim's single start? A prototype.

Runs the bounded Levenberg-Marquardt of `crates/bumpsim-ident/src/lm.rs`
(Marquardt scaling, Nielsen's damping update, the same stopping rules,
log parameters >= 0, i.e. every parameter >= 1 SI) on the peer benchmark's
3-DOF problem (bench/peers/scipy_identify.py: three synthetic pendulum
cases, 500 samples each) from bumpsim's default start, once plain and then
with Transtrum & Sethna's geodesic acceleration (arXiv:1201.5885: the
second directional derivative by a finite difference of step h = 0.1,
acceleration accepted when 2|a|/|v| <= alpha), in the two usual forms:
a step whose acceleration is too large is rejected (damping raised), or
falls back to the plain step. Jacobians are forward differences; the
model is the exact zoh recursion. Prints iterations, residual
evaluations and the final objective of each; about a minute. One more
run keeps the plain step but lowers the damping eagerly; for the plain
run the median gain ratio and damping of its later iterations are shown.

Usage: python3 bench/peers/lm_geodesic.py [path/to/bumpsim]
(the binary reports its default start; default target/release/bumpsim).
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy import linalg

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scipy_identify as peer  # noqa: E402


# the sample interval simulate() works at (lm_coarse.py sets a coarser one)
STEP = peer.STEP


def simulate(theta, force):
    a, b = peer.system(theta[:3], theta[3:5], theta[5:7])
    aug = np.zeros((7, 7))
    aug[:6, :6], aug[:6, 6:] = a * STEP, b * STEP
    e = linalg.expm(aug)
    ad, bd = e[:6, :6], e[:6, 6]
    state, y = np.zeros(6), np.zeros(len(force))
    for i, f in enumerate(force):
        y[i] = state[0]
        state = ad @ state + bd * f
    return y


def residuals(data, p):
    theta = np.exp(p)
    return np.concatenate([simulate(theta, f) - x for _, f, x in data])


def jacobian(data, p, r):
    j = np.zeros((len(r), len(p)))
    for i in range(len(p)):
        q = p.copy()
        q[i] += 1e-7
        j[:, i] = (residuals(data, q) - r) / 1e-7
    return j


def acceleration(data, p, r, j, m, v, alpha, fallback):
    """The step v + a/2, v itself (fallback) or None (rejected)."""
    h = 0.1
    rvv = 2.0 / h * ((residuals(data, p + h * v) - r) / h - j @ v)
    a = -np.linalg.solve(m, j.T @ rvv)
    if 2.0 * np.linalg.norm(a) <= alpha * np.linalg.norm(v):
        return v + 0.5 * a
    return v if fallback else None


def minimise(data, p, geodesic=None, eager=False, limit=1000):
    """geodesic: None (plain LM) or (alpha, fallback); eager: the damping
    divided by 3 at every step with gain ratio > 0.5 (Nielsen otherwise).
    Returns iterations, evaluations, the objective, the (gain ratio,
    damping) of each step and the final point."""
    r = residuals(data, p)
    cost, lam, nu, evaluations, trace = r @ r, None, 2.0, 1, []
    j = jacobian(data, p, r)
    for iteration in range(1, limit + 1):
        jtj, g = j.T @ j, j.T @ r
        lam = 1e-3 * jtj.diagonal().max() if lam is None else lam
        while True:
            m = jtj + lam * np.diag(jtj.diagonal())
            v = -np.linalg.solve(m, g)
            step = v
            if geodesic is not None:
                evaluations += 1
                step = acceleration(data, p, r, j, m, v, *geodesic)
            if step is not None:
                trial = np.maximum(p + step, 0.0)
                step = trial - p
                rt = residuals(data, trial)
                evaluations += 1
                predicted = -(2.0 * g @ step + step @ jtj @ step)
                rho = (cost - rt @ rt) / predicted
                if rt @ rt < cost and rho > 0.0:
                    trace.append((rho, lam))
                    shrink = 1.0 / 3.0 if eager and rho > 0.5 else 1.0 - (2.0 * rho - 1.0) ** 3
                    lam *= max(1.0 / 3.0, shrink)
                    nu = 2.0
                    break
            lam, nu = lam * nu, nu * 2.0
        decrease, directional = (cost - rt @ rt) / cost, abs(2.0 * g @ step)
        p, r, cost = trial, rt, rt @ rt
        j = jacobian(data, p, r)
        if directional < 1e-9 * cost or decrease < 1e-12 or np.abs(step).max() < 1e-10:
            return iteration, evaluations, cost, trace, p
    return limit, evaluations, cost, trace, p


def default_start(binary, data):
    with tempfile.TemporaryDirectory() as folder:
        study = peer.write_study(folder, data, thesis_start=False)
        out = os.path.join(folder, "result.json")
        subprocess.run([binary, "identify", study, "--json", out, "--quiet"], check=True, stdout=subprocess.DEVNULL)
        with open(out) as fh:
            result = json.load(fh)
    return np.log(np.asarray(result["start"])), result["iterations"], result["objective"]


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "target/release/bumpsim"
    data = peer.cases()
    start, iterations, objective = default_start(binary, data)
    print(f"bumpsim identify from its default start: {iterations} iterations, objective {objective:.6e} m^2")
    runs = [("plain LM (bumpsim's rule)", None, False), ("plain LM, damping / 3 at every good step", None, True)]
    runs += [(f"geodesic, alpha {alpha}, too large: {'plain step' if fb else 'rejected'}", (alpha, fb), False)
             for fb in (False, True) for alpha in (0.75, 1.5)]
    for name, geodesic, eager in runs:
        its, evaluations, cost, trace, _ = minimise(data, start.copy(), geodesic, eager)
        print(f"{name}: {its} iterations, {evaluations} residual evaluations, objective {cost:.6e} m^2")
        if geodesic is None and not eager:
            rho, lam = np.median(np.asarray(trace[15:]), axis=0)
            print(f"  iterations 16..{its}: median gain ratio {rho:.2f}, damping {lam:.1e} of the diagonal")


if __name__ == "__main__":
    main()
