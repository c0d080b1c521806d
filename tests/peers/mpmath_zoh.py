#!/usr/bin/env python3
"""Independent check of bumpsim's zoh output (modal form and state space) with mpmath.

Usage: mpmath_zoh.py CASE.json

CASE.json (written by crates/bumpsim-core/tests/analytic.rs) holds one chain
model (`masses` kg, `dampers` N s/m, `springs` N/m; damper and spring j join
masses j and j + 1, the force acts on mass 0), the sample `step` (s), the
`initial_velocity` (m/s, every mass moving at it, displacements zero), the
`force` samples (N, each held over one step), the `output` mass (0-based) and
bumpsim's two evaluations of the same zoh-sampled displacement of that mass:
`modal` (`ModalForm::simulate`; null when the modal form refused the model,
`modal_refusal` then says why) and `state_space` (`DiscreteModel::output`).

Computes the exact zoh response in 50-digit arithmetic: the state [x; v] with
A = [[0, I], [-M^-1 K, -M^-1 C]] and B = [0; e0 / m0], Phi and Gamma from
mpmath.expm of the augmented matrix [[A, B], [0, 0]] T, then
x[k + 1] = Phi x[k] + Gamma f[k], the output being x_out[k] before the step
(sample k is the state at k T, sample 0 the initial state). Prints each
evaluation's largest difference relative to the reference's peak |y| and
exits 1 when the modal one (if present) exceeds 1e-10 or the state-space one
1e-9.
"""
import json
import sys

import mpmath
from mpmath import mp, mpf

MODAL_LIMIT = 1e-10
STATE_SPACE_LIMIT = 1e-9


def reference(case):
    m = [mpf(v) for v in case["masses"]]
    c = [mpf(v) for v in case["dampers"]]
    k = [mpf(v) for v in case["springs"]]
    n = len(m)
    order = 2 * n
    # augmented [[A, B], [0, 0]] T: its exponential is [[Phi, Gamma], [0, 1]]
    aug = mpmath.zeros(order + 1, order + 1)
    for i in range(n):
        aug[i, n + i] = mpf(1)
    for j in range(n - 1):
        for (row, col, sign) in ((j, j, 1), (j + 1, j + 1, 1), (j, j + 1, -1), (j + 1, j, -1)):
            aug[n + row, col] -= sign * k[j] / m[row]
            aug[n + row, n + col] -= sign * c[j] / m[row]
    aug[n, order] = 1 / m[0]
    e = mpmath.expm(aug * mpf(case["step"]))
    phi = [[e[r, s] for s in range(order)] for r in range(order)]
    gamma = [e[r, order] for r in range(order)]
    v0 = mpf(case["initial_velocity"])
    x = [mpf(0)] * n + [v0] * n
    out = case["output"]
    y = []
    for f in case["force"]:
        y.append(x[out])
        f = mpf(f)
        x = [mpmath.fsum(p * xs for p, xs in zip(row, x)) + g * f for row, g in zip(phi, gamma)]
    return y


def relative_error(ours, exact):
    if len(ours) != len(exact):
        raise ValueError(f"{len(ours)} samples from bumpsim, {len(exact)} expected")
    peak = max(max(abs(v) for v in exact), mpf("1e-300"))
    worst = max(abs(mpf(a) - b) for a, b in zip(ours, exact))
    return float(worst / peak), float(peak)


def main(path):
    mp.dps = 50
    with open(path) as f:
        case = json.load(f)
    name = case.get("name", path)
    exact = reference(case)
    failed = False
    ss, peak = relative_error(case["state_space"], exact)
    print(f"{name}: peak |y| {peak:.4e} m")
    print(f"{name}: state space  largest difference {ss:.2e} of the peak (limit {STATE_SPACE_LIMIT:g})")
    if not ss <= STATE_SPACE_LIMIT:
        failed = True
    if case.get("modal") is None:
        print(f"{name}: modal        refused ({case.get('modal_refusal', 'no reason given')})")
    else:
        modal, _ = relative_error(case["modal"], exact)
        print(f"{name}: modal        largest difference {modal:.2e} of the peak (limit {MODAL_LIMIT:g})")
        if not modal <= MODAL_LIMIT:
            failed = True
    print(f"{name}: {'FAILED' if failed else 'ok'}")
    return 1 if failed else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1]))
