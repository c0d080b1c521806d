"""Peer for issue 44 item 6: the Jacobian evaluations scipy's
least_squares (trust-region-reflective, 2-point finite differences) needs
from bumpsim's default start, against which bumpsim's LM iterations are
counted (crates/bumpsim-ident/tests/iterations.rs).

Two uses:

    python3 tests/peers/scipy_trf_iterations.py OUT
        writes bench/peers/scipy_identify.py's series (three synthetic
        pendulum cases of the bundled example's true car, 500 samples at
        5 kHz, exact zoh model by scipy.signal.dlsim, displacement noise
        50 um) as CSV with OUT/study.toml (3 masses, one start, the
        default start);

    python3 tests/peers/scipy_trf_iterations.py OUT OBJECTIVE P1 ... P7
        runs least_squares from the start P (SI, thesis order) in log
        parameters >= 0 with tolerances 1e-10 on OBJECTIVE's residuals
        (displacement, velocity or acceleration: the backward differences
        of the displacement over the step, as bumpsim forms them) and
        prints "njev objective" (objective in the domain's units squared).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../bench/peers"))
import scipy_identify  # noqa: E402
import scipy_iterations  # noqa: E402


def main():
    out = sys.argv[1]
    data = scipy_identify.cases()
    if len(sys.argv) == 2:
        os.makedirs(out, exist_ok=True)
        study = scipy_identify.write_study(out, data, thesis_start=False)
        os.replace(study, os.path.join(out, "study.toml"))
        return
    objective, start = sys.argv[2], [float(v) for v in sys.argv[3:]]
    njev, value = scipy_iterations.scipy_run(data, start, objective)
    print(f"{njev} {value!r}")


if __name__ == "__main__":
    main()
