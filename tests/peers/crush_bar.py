"""An elastic-plastic crushing bar into a rigid wall: an independent
generator for the identification with yielding links (issue 46).

Another family than bumpsim's lumped chain: the front structure is a bar of
N elements with distributed mass (N + 1 nodes), each element an
elasto-plastic spring (stiffness N k, yield force F_y, hardening ratio r,
unloading stiffness N u k, the plastic strain kept), its rear node rigidly
carrying the body's mass M; the bumper's mass sits on the front node. The
front node meets the wall through a stiff contact spring (compression
only). Integrated by symplectic Euler (velocities first) at a step far
below the elements' period, numpy only, written from the equations alone.

Quasi-statically the bar is one bilinear link: N identical elements in
series yield together, so its stiffness is k, its yield force F_y, its
hardening ratio r and its unloading stiffness u k. That truth is written
beside the series (truth.json) for the test to check the identified
link's intervals against.

    python3 crush_bar.py OUT [SEED]

writes OUT/crush.csv (time s, wall force N (negative: on the car), body
displacement m with N(0, 0.2 mm) noise) and OUT/truth.json.
"""

import json
import sys
from pathlib import Path

import numpy as np

ELEMENTS = 10
BODY = 1200.0  # kg
BUMPER = 15.0  # kg, on the front node
BAR = 20.0  # kg, spread over the bar's nodes
STIFFNESS = 1.0e6  # N/m of the whole bar
YIELD = 1.5e5  # N
HARDENING = 0.1
UNLOADING = 8.0  # unloading stiffness / stiffness
SPEED = 10.0  # m/s
CONTACT = 5.0e9  # N/m
SAMPLE = 1e-4  # s
DURATION = 0.15  # s
NOISE = 2e-4  # m


def element_force(strain, state, k, unload):
    """Elasto-plastic element: bilinear loading, linear unloading about
    the plastic set; `state` holds the largest compression reached."""
    dy = YIELD / k
    reached = np.maximum(state, strain)
    top = np.where(reached <= dy, k * reached, YIELD + HARDENING * k * (reached - dy))
    loading = strain >= state
    on_curve = np.where(strain <= dy, k * strain, YIELD + HARDENING * k * (strain - dy))
    force = np.where(loading, on_curve, top - unload * (state - strain))
    return force, reached


def main():
    out = Path(sys.argv[1])
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    out.mkdir(parents=True, exist_ok=True)
    nodes = ELEMENTS + 1
    mass = np.full(nodes, BAR / nodes)
    mass[0] += BUMPER
    mass[-1] += BODY
    k = ELEMENTS * STIFFNESS
    unload = UNLOADING * k
    omega = np.sqrt(max(2 * k, 2 * unload) / mass.min() + CONTACT / mass[0])
    per_sample = int(np.ceil(SAMPLE / (0.05 * 2.0 / omega)))
    h = SAMPLE / per_sample
    # x forwards; the wall at x = 0 ahead of the front node (node 0)
    x = np.zeros(nodes)
    v = np.full(nodes, SPEED)
    reached = np.zeros(ELEMENTS)
    samples = int(round(DURATION / SAMPLE)) + 1
    wall = np.zeros(samples)
    body = np.zeros(samples)
    impulse = 0.0
    for s in range(1, samples):
        impulse = 0.0
        for _ in range(per_sample):
            strain = x[1:] - x[:-1]  # compression: the rear node gains on the front one
            f, reached = element_force(strain, reached, k, unload)
            contact = -CONTACT * max(x[0], 0.0)
            a = np.zeros(nodes)
            a[:-1] += f  # pushes the front node forwards
            a[1:] -= f
            a[0] += contact
            v += h * a / mass
            x += h * v
            impulse += h * contact
        wall[s] = impulse / SAMPLE
        body[s] = x[-1]
    time = np.arange(samples) * SAMPLE
    noisy = body + np.random.default_rng(seed).normal(0.0, NOISE, samples)
    noisy[0] = 0.0
    rows = np.column_stack([time, wall, noisy])
    np.savetxt(out / "crush.csv", rows, delimiter=",", header="time_s,wall_force_N,body_m", comments="")
    truth = {
        "stiffness": STIFFNESS,
        "yield_force": YIELD,
        "hardening": HARDENING,
        "unloading": UNLOADING,
        "speed": SPEED,
        "noise": NOISE,
        "total_mass": BODY + BUMPER + BAR,
    }
    (out / "truth.json").write_text(json.dumps(truth, indent=1))


if __name__ == "__main__":
    main()
