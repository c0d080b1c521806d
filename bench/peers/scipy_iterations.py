"""Peer measurement (issue 44): how many iterations bumpsim's bounded LM
needs from its default (data-derived) start, against the Jacobian
evaluations scipy.optimize.least_squares (trust-region-reflective, 2-point
finite differences) needs from the same start, for the objective in each
domain (`[identification] objective`: displacement, velocity,
acceleration; the residuals are the backward differences of the
displacement over the step, as bumpsim forms them).

The data are scipy_identify.py's: three synthetic pendulum cases of the
bundled example's true car, 500 samples each at 5 kHz, the model the exact
zoh one (scipy.signal.dlsim), displacement noise 50 um.

Usage: python3 bench/peers/scipy_iterations.py [path/to/bumpsim]
(default: target/release/bumpsim).
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy import optimize

sys.path.insert(0, os.path.dirname(__file__))
from scipy_identify import STEP, cases, simulate, write_study  # noqa: E402

ORDER = {"displacement": 0, "velocity": 1, "acceleration": 2}


def differenced(y, order):
    for _ in range(order):
        y = np.diff(y) / STEP
    return y


def bumpsim_run(binary, data, objective, folder):
    study = write_study(folder, data, thesis_start=False)
    with open(study) as fh:
        text = fh.read()
    with open(study, "w") as fh:
        fh.write(f'[identification]\nobjective = "{objective}"\n\n' + text)
    out = os.path.join(folder, f"{objective}.json")
    subprocess.run([binary, "identify", study, "--json", out, "--quiet"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(out) as fh:
        result = json.load(fh)
    return result["iterations"], result["objective"], result["start"]


def scipy_run(data, start, objective):
    order = ORDER[objective]

    def residuals(p):
        theta = np.exp(p)
        return np.concatenate([differenced(simulate(theta, f) - x, order) for _, f, x in data])

    res = optimize.least_squares(residuals, np.log(np.asarray(start, dtype=float)),
                                 bounds=(0.0, np.inf), method="trf",
                                 ftol=1e-10, xtol=1e-10, gtol=1e-10)
    return res.njev, float(np.sum(res.fun ** 2))


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "target/release/bumpsim"
    data = cases()
    print("objective      bumpsim LM iterations  scipy TRF Jacobians  objective ratio bumpsim/scipy")
    for objective in ORDER:
        with tempfile.TemporaryDirectory() as folder:
            iterations, value, start = bumpsim_run(binary, data, objective, folder)
        njev, scipy_value = scipy_run(data, start, objective)
        print(f"{objective:<14} {iterations:>21}  {njev:>19}  {value / scipy_value:>29.6f}")


if __name__ == "__main__":
    main()
