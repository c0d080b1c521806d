"""Two elastic-plastic crushing bars into a rigid wall: an independent
generator for the identification with yielding links (issue 46).

Another family than bumpsim's lumped chain: the car is a bumper, a front
bar (the crush zone, 10 elements), the engine, a rear bar (the engine's
load path into the body, 5 elements) and the body. Each bar has
distributed mass (its nodes) and elements that are elasto-plastic
springs (stiffness N k, yield force F_y, hardening ratio r, unloading
stiffness N u k past yield, elastic along N k before it, the plastic
strain kept). The bumper meets the wall through a stiff contact spring
with a damper at critical for the bumper (compression only): a bumper
beam that hits a wall crushes, it does not ring off it at the impact
speed (an undamped contact made the 2 kg bumper bounce off the wall and
back, the wall force alternating between a 440 kN spike and nothing for
the first 5 ms). Integrated by symplectic Euler (velocities first) at a
step far below the elements' period, numpy only, written from the
equations alone. The bars are light (2 kg each, the bumper 2 kg): the
lumped chain takes m1 as one rigid body, so heavy parts ahead of the
engine, stopped by the wall before it, would bias the link it identifies
beyond its interval (with 15 kg of bumper and 20 kg of front bar the
yield force came out 17 % high).

Quasi-statically a bar is one bilinear link: N identical elements in
series yield together, so its stiffness is k, its yield force F_y, its
hardening ratio r and its unloading stiffness u k. The rear bar's values
are the truth of the identified chain's link between m1 (bumper, front
bar and engine) and m2 (the body), written beside the series
(truth.json); the front bar is what the wall force measures.

    python3 crush_bar.py OUT [SEED] [SPEED]

(SPEED m/s, 10 by default: another speed is a held-out test of the same
car) writes OUT/crush.csv (time s, wall force N (negative: on the car), body
displacement m with N(0, 0.2 mm) noise) and OUT/truth.json.
"""

import json
import sys
from pathlib import Path

import numpy as np

# front bar, rear bar: elements, nodes' mass kg, stiffness N/m, yield N,
# hardening, unloading / stiffness
FRONT = (10, 2.0, 1.0e6, 1.5e5, 0.1, 8.0)
REAR = (5, 2.0, 2.0e6, 8.0e4, 0.2, 6.0)
BUMPER = 2.0  # kg
ENGINE = 300.0  # kg, between the bars
BODY = 900.0  # kg
SPEED = 10.0  # m/s
CONTACT = 5.0e9  # N/m
SAMPLE = 1e-4  # s
DURATION = 0.15  # s
NOISE = 2e-4  # m


def element_force(strain, state, k, fy, r, unload):
    """Elasto-plastic elements: bilinear loading, linear unloading about
    the plastic set; `state` holds the largest compression reached. An
    element that never yielded (state <= dy) unloads elastically along k,
    with no set, whatever its unloading stiffness."""
    dy = fy / k
    reached = np.maximum(state, strain)
    top = np.where(reached <= dy, k * reached, fy + r * k * (reached - dy))
    loading = strain >= state
    on_curve = np.where(strain <= dy, k * strain, fy + r * k * (strain - dy))
    slope = np.where(state <= dy, k, unload)
    force = np.where(loading, on_curve, top - slope * (state - strain))
    return force, reached


def main():
    out = Path(sys.argv[1])
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    speed = float(sys.argv[3]) if len(sys.argv) > 3 else SPEED
    out.mkdir(parents=True, exist_ok=True)
    nf, nr = FRONT[0], REAR[0]
    nodes = nf + nr + 1
    mass = np.zeros(nodes)
    mass[: nf + 1] += FRONT[1] / (nf + 1)
    mass[nf:] += REAR[1] / (nr + 1)
    mass[0] += BUMPER
    mass[nf] += ENGINE
    mass[-1] += BODY
    # per element: stiffness, yield, hardening, unloading stiffness
    k = np.array([FRONT[2] * nf] * nf + [REAR[2] * nr] * nr)
    fy = np.array([FRONT[3]] * nf + [REAR[3]] * nr)
    r = np.array([FRONT[4]] * nf + [REAR[4]] * nr)
    unload = np.array([FRONT[5]] * nf + [REAR[5]] * nr) * k
    omega = np.sqrt(2 * unload.max() / mass.min() + CONTACT / mass[0])
    damper = 2.0 * np.sqrt(CONTACT * mass[0])  # N s/m, critical for the bumper
    per_sample = int(np.ceil(SAMPLE / (0.05 * 2.0 / omega)))
    h = SAMPLE / per_sample
    # x forwards; the wall at x = 0 ahead of the front node (node 0)
    x = np.zeros(nodes)
    v = np.full(nodes, speed)
    reached = np.zeros(nodes - 1)
    samples = int(round(DURATION / SAMPLE)) + 1
    wall = np.zeros(samples)
    body = np.zeros(samples)
    impulse = 0.0
    for s in range(1, samples):
        impulse = 0.0
        for _ in range(per_sample):
            strain = x[1:] - x[:-1]  # compression: the rear node gains on the front one
            f, reached = element_force(strain, reached, k, fy, r, unload)
            contact = -max(CONTACT * x[0] + damper * v[0], 0.0) if x[0] > 0.0 else 0.0
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
        "stiffness": REAR[2],
        "yield_force": REAR[3],
        "hardening": REAR[4],
        "unloading": REAR[5],
        "front": {
            "stiffness": FRONT[2],
            "yield_force": FRONT[3],
            "hardening": FRONT[4],
            "unloading": FRONT[5],
        },
        "front_mass": BUMPER + FRONT[1] + ENGINE,  # kg, without the rear bar
        "speed": speed,
        "noise": NOISE,
        "total_mass": BODY + BUMPER + ENGINE + FRONT[1] + REAR[1],
    }
    (out / "truth.json").write_text(json.dumps(truth, indent=1))


if __name__ == "__main__":
    main()
